// Analysis "frf": frequency response functions (solvers/frequency_response.hpp).
//   {"id": "h", "type": "frf", "input": {"node": n, "dof": d} | {"joint": j, "coordinate": c},
//    "outputs": [{"node": m, "dof": e} | {"joint", "coordinate"}, ...] | "all",
//    "frequencies": {"from": f0, "to": f1, "count": N, "spacing": "log" | "linear"} | [f, ...],
//    "method": "direct" | "modal", "modes": k, "residual_flexibility": false, "mass": ...,
//    "load_case": ..., "about": ..., "geometric_stiffness": ...}
// "all": the 6 x 6 receptance matrix of the input's node (every input DOF to every output DOF).
// Result analyses.<id>: type, status, message, method, modes and mode_frequencies (modal),
// input, frequencies (Hz), outputs[] {node/dof or joint/coordinate, input (with "all"), real, imag,
// magnitude, phase_deg (lists over the frequencies), peak_frequency, peak_magnitude}, csv; file
// DIR/<id>.csv (frequency_hz, then <label>_real, _imag, _magnitude, _phase_deg per output).
#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "core/errors.hpp"
#include "io/analysis.hpp"
#include "io/atomic_file.hpp"
#include "io/dynamic_input.hpp"
#include "io/json_util.hpp"
#include "io/load_reader.hpp"
#include "io/model_reader.hpp"
#include "io/static_results.hpp"
#include "solvers/frequency_response.hpp"
#include "solvers/modal.hpp"

namespace beamfea {

namespace {

// The documented bound of the number of frequencies of one FRF (docs/analyses/frf.md).
constexpr int kMaxFrequencies = 1'000'000;

struct FrfSpec {
  FrfOptions options;
  std::string load_case;
  std::vector<DofRef> inputs, outputs;
  bool all = false;  // the 6 x 6 matrix of one node
  Eigen::VectorXd hz;
};

Eigen::VectorXd read_frequencies(const nlohmann::json& v, const json_in::Pointer& p) {
  using namespace json_in;
  if (v.is_array()) {
    const std::vector<double> f = numbers(v, p, "frf frequencies");
    if (f.empty()) throw InputError(p, "frf frequencies: expected at least one frequency");
    if (static_cast<long long>(f.size()) > kMaxFrequencies)
      throw InputError(p, fmt::format("frf frequencies: at most {} frequencies", kMaxFrequencies));
    for (std::size_t i = 0; i < f.size(); ++i) {
      if (!(f[i] > 0.0)) throw InputError(child(p, i), "frf frequencies: a frequency must be positive (Hz)");
      if (i > 0 && !(f[i] > f[i - 1])) throw InputError(child(p, i), "frf frequencies: the frequencies must increase");
    }
    return Eigen::Map<const Eigen::VectorXd>(f.data(), static_cast<Eigen::Index>(f.size()));
  }
  const Fields fs(object(v, p, "frf frequencies"), p, {"from", "to", "count", "spacing"});
  const double from = positive(fs.require("from", "frf frequencies"), child(p, "from"), "frf frequencies from");
  const double to = number(fs.require("to", "frf frequencies"), child(p, "to"), "frf frequencies to");
  if (!(to > from)) throw InputError(child(p, "to"), "frf frequencies: 'to' must exceed 'from' (the frequencies must increase)");
  const int count = integer_in(fs.require("count", "frf frequencies"), child(p, "count"), "frf frequencies count", 2, kMaxFrequencies);
  bool log = false;
  if (const nlohmann::json* s = fs.get("spacing")) {
    const std::string spacing = string(*s, child(p, "spacing"), "frf frequencies spacing");
    if (spacing != "log" && spacing != "linear")
      throw InputError(child(p, "spacing"), "frf frequencies: unknown spacing '" + spacing + "' (expected log or linear)");
    log = spacing == "log";
  }
  Eigen::VectorXd hz(count);
  for (int k = 0; k < count; ++k) {
    const double s = static_cast<double>(k) / (count - 1);
    hz[k] = log ? from * std::pow(to / from, s) : from + (to - from) * s;
  }
  hz[0] = from, hz[count - 1] = to;  // both ends exactly
  return hz;
}

FrfSpec check_frf(const Model& model, const nlohmann::json& spec, const json_in::Pointer& p) {
  using namespace json_in;
  FrfSpec s;
  const Fields f(spec, p,
                 {"id", "type", "description", "input", "outputs", "frequencies", "method", "modes", "residual_flexibility", "mass",
                  "load_case", "about", "geometric_stiffness"});
  check_dynamic_mass(model, p, "frf");
  s.load_case = read_load_case(model, spec, p);
  s.options.system.preload = !s.load_case.empty();
  s.options.system.about_state = read_preload(spec, p, "frf", s.options.system.preload);
  if (s.options.system.about_state.about == Equilibrium::SecondOrder) check_nonlinear_model(model, p);
  if (const nlohmann::json* mass = f.get("mass")) s.options.system.mass = mass_kind(*mass, child(p, "mass"), "frf mass", "frf");
  if (const nlohmann::json* method = f.get("method")) {
    const std::string m = string(*method, child(p, "method"), "frf method");
    if (m != "direct" && m != "modal") throw InputError(child(p, "method"), "frf: unknown method '" + m + "' (expected direct or modal)");
    s.options.method = m == "modal" ? FrfMethod::Modal : FrfMethod::Direct;
  }
  const bool modal = s.options.method == FrfMethod::Modal;
  if (!modal) {
    for (const char* key : {"modes", "residual_flexibility"})
      if (f.get(key)) throw InputError(child(p, key), std::string("frf: \"") + key + "\" applies to \"method\": \"modal\" only");
    reject_modal_damping(model, p, "needs an frf with \"method\": \"modal\"");
  }
  if (const nlohmann::json* modes = f.get("modes")) {
    s.options.modes = integer_in(*modes, child(p, "modes"), "frf modes", 1, kMaxModes);
    const int n = modal_dof_count(model);
    if (s.options.modes > n)
      throw InputError(child(p, "modes"), fmt::format("frf: {} modes asked for, but the model has only {} free DOFs", s.options.modes, n));
  } else if (modal) {
    s.options.modes = std::min(s.options.modes, modal_dof_count(model));
  }
  if (const nlohmann::json* rf = f.get("residual_flexibility"))
    s.options.residual_flexibility = boolean(*rf, child(p, "residual_flexibility"), "frf residual_flexibility");
  s.hz = read_frequencies(f.require("frequencies", "frf"), child(p, "frequencies"));

  const DofMap map(model);
  const nlohmann::json& input = f.require("input", "frf");
  const nlohmann::json& outputs = f.require("outputs", "frf");
  const json_in::Pointer ip = child(p, "input"), op = child(p, "outputs");
  if (outputs.is_string()) {
    if (outputs.get<std::string>() != "all")
      throw InputError(op, "frf outputs: expected an array of DOFs or \"all\" (the 6 x 6 matrix of the input's node)");
    s.all = true;
    object(input, ip, "frf input");
    expect_keys(input, ip, {"node"});
    const int node = node_ref(model, require(input, ip, "node", "frf input"), child(ip, "node"));
    for (int c = 0; c < 6; ++c) {
      s.inputs.push_back({DofRef::Owner::Node, node, c});
      s.outputs.push_back({DofRef::Owner::Node, node, c});
    }
    return s;
  }
  s.inputs.push_back(read_dynamic_dof(model, input, ip, "frf input", &map));
  const nlohmann::json& arr = array(outputs, op, "frf outputs");
  if (arr.empty()) throw InputError(op, "frf outputs: expected at least one output DOF");
  for (std::size_t i = 0; i < arr.size(); ++i) s.outputs.push_back(read_dynamic_dof(model, arr[i], child(op, i), "frf output", nullptr));
  return s;
}

ojson dof_json(const Model& model, const DofRef& d) {
  if (d.owner == DofRef::Owner::Node)
    return ojson{{"node", model.nodes[static_cast<std::size_t>(d.index)].id}, {"dof", kDofNames[static_cast<std::size_t>(d.comp)]}};
  return ojson{{"joint", model.joints[static_cast<std::size_t>(d.index)].id}, {"coordinate", d.comp}};
}

double phase_in_degrees(std::complex<double> h) { return std::arg(h) * 180.0 / std::numbers::pi; }

AnalysisOutcome run_frf(const AnalysisContext& ctx, const FrfSpec& spec) {
  const Model& model = ctx.model;
  const FrfResult r = frequency_response(model, spec.inputs, spec.outputs, spec.hz, model.loads_for(spec.load_case), spec.options);
  AnalysisOutcome out;
  out.result = object_with_capacity(14);
  out.result["type"] = "frf";
  out.result["status"] = to_string(r.status);
  out.result["message"] = r.message;
  out.result["method"] = spec.options.method == FrfMethod::Modal ? "modal" : "direct";
  if (!spec.load_case.empty()) out.result["load_case"] = spec.load_case;
  out.message = r.message;
  if (r.status != FrfStatus::Succeeded) {
    out.termination = r.status == FrfStatus::Singular ? AnalysisTermination::Mechanism : AnalysisTermination::Failed;
    out.result["frequencies"] = ojson::array();
    return out;
  }
  if (spec.options.method == FrfMethod::Modal) {
    out.result["modes"] = r.mode_frequencies.size();
    out.result["mode_frequencies"] = to_json(r.mode_frequencies);
  }
  out.result["input"] = spec.all ? ojson{{"node", model.nodes[static_cast<std::size_t>(spec.inputs[0].index)].id}} : dof_json(model, spec.inputs[0]);
  out.result["frequencies"] = to_json(spec.hz);
  const Eigen::Index nf = spec.hz.size();
  ojson outputs = ojson::array();
  std::string csv = "frequency_hz";
  std::vector<const Eigen::VectorXcd*> columns;
  std::vector<Eigen::VectorXcd> storage;
  storage.reserve(spec.inputs.size() * spec.outputs.size());
  for (std::size_t o = 0; o < spec.outputs.size(); ++o)
    for (std::size_t i = 0; i < spec.inputs.size(); ++i) {
      if (!spec.all && i > 0) break;
      storage.push_back(r.receptance[i].col(static_cast<Eigen::Index>(o)));
      const Eigen::VectorXcd& h = storage.back();
      Eigen::VectorXd re = h.real(), im = h.imag(), mag = h.cwiseAbs(), ph(nf);
      for (Eigen::Index k = 0; k < nf; ++k) ph[k] = phase_in_degrees(h[k]);
      Eigen::Index peak = 0;
      mag.maxCoeff(&peak);
      ojson entry = dof_json(model, spec.outputs[o]);
      if (spec.all) entry["input"] = dof_json(model, spec.inputs[i]);
      entry["real"] = to_json(re);
      entry["imag"] = to_json(im);
      entry["magnitude"] = to_json(mag);
      entry["phase_deg"] = to_json(ph);
      entry["peak_frequency"] = spec.hz[peak];
      entry["peak_magnitude"] = mag[peak];
      outputs.push_back(std::move(entry));
      std::string label = dof_label(model, spec.outputs[o]);
      if (spec.all) label.append("/").append(dof_label(model, spec.inputs[i]));
      for (const char* part : {"_real", "_imag", "_magnitude", "_phase_deg"}) csv.append(",").append(label).append(part);
      columns.push_back(&h);
    }
  out.result["outputs"] = std::move(outputs);
  if (!ctx.out_dir.empty()) {
    csv += "\n";
    for (Eigen::Index k = 0; k < nf; ++k) {
      csv += fmt::format("{:.12g}", spec.hz[k]);
      for (const Eigen::VectorXcd* h : columns)
        csv += fmt::format(",{:.12g},{:.12g},{:.12g},{:.9g}", (*h)[k].real(), (*h)[k].imag(), std::abs((*h)[k]), phase_in_degrees((*h)[k]));
      csv += "\n";
    }
    write_text_atomic(ctx.out_dir / (ctx.id + ".csv"), csv);
    out.result["csv"] = ctx.id + ".csv";
  }
  return out;
}

}  // namespace

AnalysisType frf_analysis() {
  return register_analysis<FrfSpec>("frf", check_frf, run_frf, [](const std::string& id) { return AnalysisFiles{{id + ".csv"}, {}}; });
}

}  // namespace beamfea
