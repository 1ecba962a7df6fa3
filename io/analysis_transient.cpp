// Analysis "transient": the time response of the linear structure (solvers/transient.hpp).
//   {"id": "t", "type": "transient", "dt": h, "duration": T,
//    "method": "newmark" | "hht" | "generalized_alpha",
//    "parameters": {"gamma", "beta"} | {"alpha"} | {"rho_inf"},
//    "loads": [{"load_case": c, "time_function": {"type": "step" | "ramp" | "sine" | "table", ...}}],
//    "initial": {"displacement": "static" | "zero", "velocity": "zero" | [{"node", "dof", "value"}, ...]},
//    "track": [node ids], "output_every": n, "mass": ..., "modes": k}
// "modes": k checks that dt resolves the k lowest modes (a warning otherwise), as it checks the
// frequencies of sine loads.
// Result analyses.<id>: type, status, message, method, parameters {gamma, beta, alpha_m, alpha_f},
// dt, steps (integration steps), max_energy_error, peaks {<node>: {peak_displacement, peak_time,
// settling_time}}, steps[] {time, nodes.<id>.displacement/velocity/acceleration (6 each), energy
// {kinetic, strain, dissipated, work}}, csv, vtk; files DIR/<id>.csv, DIR/<id>_step<k>.vtu and
// DIR/<id>.pvd (time = the step's time).
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "core/errors.hpp"
#include "io/analysis.hpp"
#include "io/atomic_file.hpp"
#include "io/dynamic_input.hpp"
#include "io/json_util.hpp"
#include "io/load_reader.hpp"
#include "io/model_reader.hpp"
#include "io/vtk_writer.hpp"
#include "solvers/modal.hpp"

namespace beamfea {

namespace {

// A step resolves a vibration of period T when dt <= T / kStepsPerPeriod (the average
// acceleration method then lengthens the period by at most 3.3 %: tan(w' dt/2) = w dt/2).
constexpr double kStepsPerPeriod = 10.0;
// A tracked node has settled when its translation stays within this fraction of its peak
// deviation from the final value.
constexpr double kSettlingBand = 0.02;

struct TransientSpec {
  TransientOptions options;
  std::vector<std::string> load_cases;  // one per load
  std::vector<TimeFunction> functions;
  int check_modes = 0;
};

void read_parameters(TransientOptions& o, const nlohmann::json* v, const json_in::Pointer& p) {
  using namespace json_in;
  if (!v) return;
  if (o.method == Integrator::Newmark) {
    const Fields f(object(*v, p, "newmark parameters"), p, {"gamma", "beta"});
    if (const nlohmann::json* g = f.get("gamma")) o.gamma = positive(*g, child(p, "gamma"), "newmark gamma");
    if (const nlohmann::json* b = f.get("beta")) o.beta = positive(*b, child(p, "beta"), "newmark beta");
    if (o.gamma < 0.5) throw InputError(child(p, "gamma"), "newmark gamma below 1/2 amplifies the response (negative numerical damping)");
  } else if (o.method == Integrator::Hht) {
    const Fields f(object(*v, p, "hht parameters"), p, {"alpha"});
    if (const nlohmann::json* a = f.get("alpha")) o.alpha = number(*a, child(p, "alpha"), "hht alpha");
    if (!(o.alpha >= -1.0 / 3.0 && o.alpha <= 0.0)) throw InputError(child(p, "alpha"), "hht alpha must be in [-1/3, 0] (Hilber, Hughes & Taylor 1977)");
  } else {
    const Fields f(object(*v, p, "generalized_alpha parameters"), p, {"rho_inf"});
    if (const nlohmann::json* r = f.get("rho_inf")) o.rho_inf = number(*r, child(p, "rho_inf"), "generalized_alpha rho_inf");
    if (!(o.rho_inf >= 0.0 && o.rho_inf <= 1.0)) throw InputError(child(p, "rho_inf"), "generalized_alpha rho_inf must be in [0, 1]");
  }
}

void read_initial(const Model& model, TransientOptions& o, const nlohmann::json& v, const json_in::Pointer& p) {
  using namespace json_in;
  const Fields f(object(v, p, "transient initial"), p, {"displacement", "velocity"});
  if (const nlohmann::json* d = f.get("displacement")) {
    const std::string s = string(*d, child(p, "displacement"), "transient initial displacement");
    if (s != "static" && s != "zero")
      throw InputError(child(p, "displacement"), "transient initial displacement: unknown '" + s + "' (expected static or zero)");
    o.static_initial = s == "static";
  }
  const nlohmann::json* vel = f.get("velocity");
  if (!vel) return;
  const json_in::Pointer vp = child(p, "velocity");
  if (vel->is_string() && vel->get<std::string>() == "zero") return;
  if (!vel->is_array()) throw InputError(vp, "transient initial velocity: expected \"zero\" or an array of {\"node\", \"dof\", \"value\"}");
  const DofMap map(model);
  for (std::size_t i = 0; i < vel->size(); ++i) {
    const json_in::Pointer ep = child(vp, i);
    const nlohmann::json& e = object((*vel)[i], ep, "initial velocity");
    expect_keys(e, ep, {"node", "dof", "joint", "coordinate", "value"});
    nlohmann::json target = e;
    target.erase("value");
    const DofRef d = read_dynamic_dof(model, target, ep, "initial velocity", &map);
    if (map.free_index(map.raw_index(d)) < 0)
      throw InputError(ep, "initial velocity: " + model.describe(d) + " follows other DOFs (a slave of a rigid link or joint): give the velocity of the DOF it follows");
    o.initial_velocity.emplace_back(d, number(require(e, ep, "value", "initial velocity"), child(ep, "value"), "initial velocity value"));
  }
}

TransientSpec check_transient(const Model& model, const nlohmann::json& spec, const json_in::Pointer& p) {
  using namespace json_in;
  TransientSpec s;
  TransientOptions& o = s.options;
  const Fields f(spec, p,
                 {"id", "type", "description", "dt", "duration", "method", "parameters", "loads", "initial", "track", "output_every",
                  "mass", "modes"});
  check_dynamic_mass(model, p, "transient");
  reject_modal_damping(model, p, "is no damping matrix: a transient analysis needs one");
  o.dt = positive(f.require("dt", "transient"), child(p, "dt"), "transient dt");
  o.duration = positive(f.require("duration", "transient"), child(p, "duration"), "transient duration");
  if (o.step_count() > kMaxTransientSteps)
    throw InputError(child(p, "dt"), fmt::format("transient: duration / dt is more than {} steps", kMaxTransientSteps));
  if (const nlohmann::json* m = f.get("method")) {
    const std::string name = string(*m, child(p, "method"), "transient method");
    if (name == "newmark") o.method = Integrator::Newmark;
    else if (name == "hht") o.method = Integrator::Hht;
    else if (name == "generalized_alpha") o.method = Integrator::GeneralizedAlpha;
    else throw InputError(child(p, "method"), "transient: unknown method '" + name + "' (expected newmark, hht or generalized_alpha)");
  }
  read_parameters(o, f.get("parameters"), child(p, "parameters"));
  if (const nlohmann::json* mass = f.get("mass")) o.mass = mass_kind(*mass, child(p, "mass"), "transient mass", "transient");
  if (const nlohmann::json* every = f.get("output_every"))
    o.output_every = integer_in(*every, child(p, "output_every"), "transient output_every", 1, std::numeric_limits<int>::max());
  if (const nlohmann::json* modes = f.get("modes")) {
    s.check_modes = integer_in(*modes, child(p, "modes"), "transient modes", 1, kMaxModes);
    if (s.check_modes > modal_dof_count(model))
      throw InputError(child(p, "modes"), fmt::format("transient: {} modes asked for, but the model has only {} free DOFs", s.check_modes, modal_dof_count(model)));
  }
  if (const nlohmann::json* initial = f.get("initial")) read_initial(model, o, *initial, child(p, "initial"));
  if (const nlohmann::json* track = f.get("track")) {
    const json_in::Pointer tp = child(p, "track");
    const nlohmann::json& arr = array(*track, tp, "transient track");
    for (std::size_t i = 0; i < arr.size(); ++i) o.track.push_back(node_ref(model, arr[i], child(tp, i)));
  }
  const json_in::Pointer lp = child(p, "loads");
  const nlohmann::json& loads = array(f.require("loads", "transient"), lp, "transient loads");
  for (std::size_t i = 0; i < loads.size(); ++i) {
    const json_in::Pointer ep = child(lp, i);
    const Fields fl(object(loads[i], ep, "transient load"), ep, {"load_case", "time_function"});
    s.load_cases.push_back(read_load_case(model, loads[i], ep));
    s.functions.push_back(read_time_function(fl.require("time_function", "transient load"), child(ep, "time_function")));
  }
  o.validate();
  return s;
}

// Warnings where dt is too long for the vibrations asked for: the k lowest modes, the sine loads.
void check_resolution(const AnalysisContext& ctx, const TransientSpec& spec, std::vector<std::string>& warnings) {
  const double dt = spec.options.dt;
  for (std::size_t i = 0; i < spec.functions.size(); ++i)
    if (spec.functions[i].kind == TimeFunction::Kind::Sine && dt * spec.functions[i].frequency * kStepsPerPeriod > 1.0)
      warnings.push_back(fmt::format("transient: dt = {:.6g} resolves the sine load {} ({:.6g} Hz) with {:.3g} steps per period; use dt <= {:.6g}", dt,
                                     ctx.pointer + "/loads/" + std::to_string(i), spec.functions[i].frequency,
                                     1.0 / (dt * spec.functions[i].frequency), 1.0 / (spec.functions[i].frequency * kStepsPerPeriod)));
  if (spec.check_modes == 0) return;
  ModalOptions mo;
  mo.modes = spec.check_modes;
  mo.mass = spec.options.mass;
  const ModalResult m = solve_modal(ctx.model, mo);
  if (m.status != ModalStatus::Succeeded || m.frequencies.size() == 0) return;
  const Eigen::Index k = m.frequencies.size() - 1;
  const double f = m.frequencies[k];
  if (f > 0.0 && dt * f * kStepsPerPeriod > 1.0)
    warnings.push_back(fmt::format("transient: dt = {:.6g} cannot resolve mode {} ({:.6g} Hz, period {:.6g}): {:.3g} steps per period; use dt <= {:.6g}",
                                   dt, k + 1, f, 1.0 / f, 1.0 / (dt * f), 1.0 / (f * kStepsPerPeriod)));
}

ojson vec6_json(const Eigen::MatrixXd& m, Eigen::Index row, Eigen::Index t) {
  return to_json(Vec6(m.row(row).segment<6>(6 * t).transpose()));
}

AnalysisOutcome run_transient(const AnalysisContext& ctx, const TransientSpec& spec) {
  const Model& model = ctx.model;
  const TransientOptions& o = spec.options;
  std::vector<TransientLoad> loads;
  for (std::size_t i = 0; i < spec.functions.size(); ++i) loads.push_back({&model.loads_for(spec.load_cases[i]), spec.functions[i]});
  std::vector<std::string> warnings;
  check_resolution(ctx, spec, warnings);

  const bool vtk = !ctx.out_dir.empty() && ctx.write_vtk;
  std::vector<std::pair<double, std::string>> pvd;
  ShapeSink shapes;
  if (vtk)
    shapes = [&](double t, const Eigen::VectorXd& u) {
      VtkFrame frame;
      for (std::size_t n = 0; n < model.nodes.size(); ++n) {
        frame.displacement.push_back(u.segment<3>(6 * static_cast<Eigen::Index>(n)));
        frame.rotation.push_back(u.segment<3>(6 * static_cast<Eigen::Index>(n) + 3));
      }
      frame.field_data["time"] = t;
      const std::string file = fmt::format("{}_step{}.vtu", ctx.id, pvd.size());
      write_vtu((ctx.out_dir / file).string(), model, frame);
      pvd.emplace_back(t, file);
    };
  const TransientResult r = solve_transient(model, loads, o, shapes);
  warnings.insert(warnings.end(), r.warnings.begin(), r.warnings.end());
  for (const std::string& w : warnings)
    if (ctx.warning) ctx.warning(w);

  AnalysisOutcome out;
  out.result = object_with_capacity(16);
  out.result["type"] = "transient";
  out.result["status"] = to_string(r.status);
  out.result["message"] = r.message;
  out.result["method"] = to_string(o.method);
  out.result["parameters"] = ojson{{"gamma", r.gamma}, {"beta", r.beta}, {"alpha_m", r.am}, {"alpha_f", r.af}};
  out.result["dt"] = o.dt;
  out.result["steps_taken"] = r.steps;
  if (!warnings.empty()) out.result["warnings"] = warnings;
  out.message = r.message;
  if (r.status != TransientStatus::Succeeded) {
    out.termination = r.status == TransientStatus::Diverged ? AnalysisTermination::NotConverged : AnalysisTermination::Failed;
    out.result["steps"] = ojson::array();
    return out;
  }
  out.result["max_energy_error"] = r.max_energy_error;
  const Eigen::Index rows = static_cast<Eigen::Index>(r.times.size());
  // Peaks and settling of each tracked node's translation.
  ojson peaks = ojson::object();
  for (std::size_t t = 0; t < o.track.size(); ++t) {
    const Eigen::Index c = 6 * static_cast<Eigen::Index>(t);
    const Eigen::MatrixXd u = r.displacement.middleCols(c, 3);
    Eigen::Index at = 0;
    const double peak = u.rowwise().norm().maxCoeff(&at);
    const Eigen::RowVector3d last = u.row(rows - 1);
    const Eigen::VectorXd dev = (u.rowwise() - last).rowwise().norm();
    const double band = kSettlingBand * dev.maxCoeff();
    double settling = 0.0;
    for (Eigen::Index k = rows - 1; k >= 0; --k)
      if (dev[k] > band) {
        settling = r.times[static_cast<std::size_t>(std::min(k + 1, rows - 1))];
        break;
      }
    peaks[model.nodes[static_cast<std::size_t>(o.track[t])].id] =
        ojson{{"peak_displacement", peak}, {"peak_time", r.times[static_cast<std::size_t>(at)]}, {"settling_time", settling}};
  }
  out.result["peaks"] = std::move(peaks);
  ojson steps = ojson::array();
  std::string csv = "time";
  for (int t : o.track)
    for (const char* q : {"", "v_", "a_"})
      for (const char* dof : kDofNames) csv += fmt::format(",{}.{}{}", model.nodes[static_cast<std::size_t>(t)].id, q, dof);
  csv += ",kinetic,strain,dissipated,work\n";
  for (Eigen::Index k = 0; k < rows; ++k) {
    ojson step = object_with_capacity(3);
    step["time"] = r.times[static_cast<std::size_t>(k)];
    ojson nodes = object_with_capacity(o.track.size());
    csv += fmt::format("{:.12g}", r.times[static_cast<std::size_t>(k)]);
    for (std::size_t t = 0; t < o.track.size(); ++t) {
      const Eigen::Index ti = static_cast<Eigen::Index>(t);
      nodes[model.nodes[static_cast<std::size_t>(o.track[t])].id] = ojson{
          {"displacement", vec6_json(r.displacement, k, ti)}, {"velocity", vec6_json(r.velocity, k, ti)}, {"acceleration", vec6_json(r.acceleration, k, ti)}};
      for (const Eigen::MatrixXd* m : {&r.displacement, &r.velocity, &r.acceleration})
        for (int c = 0; c < 6; ++c) csv += fmt::format(",{:.12g}", (*m)(k, 6 * ti + c));
    }
    step["nodes"] = std::move(nodes);
    step["energy"] = ojson{{"kinetic", r.energy(k, 0)}, {"strain", r.energy(k, 1)}, {"dissipated", r.energy(k, 2)}, {"work", r.energy(k, 3)}};
    csv += fmt::format(",{:.12g},{:.12g},{:.12g},{:.12g}\n", r.energy(k, 0), r.energy(k, 1), r.energy(k, 2), r.energy(k, 3));
    steps.push_back(std::move(step));
  }
  out.result["steps"] = std::move(steps);
  if (!ctx.out_dir.empty()) {
    write_text_atomic(ctx.out_dir / (ctx.id + ".csv"), csv);
    out.result["csv"] = ctx.id + ".csv";
  }
  if (vtk) {
    write_pvd((ctx.out_dir / (ctx.id + ".pvd")).string(), pvd);
    out.result["vtk"] = ctx.id + ".pvd";
  }
  return out;
}

}  // namespace

AnalysisType transient_analysis() {
  return register_analysis<TransientSpec>("transient", check_transient, run_transient, [](const std::string& id) {
    return AnalysisFiles{{id + ".csv", id + ".pvd"}, {id + "_step"}};
  });
}

}  // namespace beamfea
