// Analysis "path": nonlinear equilibrium path with stability (solvers/path_following.hpp).
//
// {"id": "p", "type": "path", "track": ["D"], "stiffness_node": "D", "max_steps": 500,
//  "control": {"load_factor": 2.0, "increments": 20}                 load control, or
//  "control": {"node": "D", "dof": "ux", "to": -1.0, "increments": 20}  displacement control, or
//  "control": {"arc_length": 0.05, "min": 1e-5, "max": 0.5}            arc length (initial step), or
//  "control": {"arc_length": "auto"}                                  the first step from the structure
//  "stop": {"load_factor": 2.0} | {"node": "D", "dof": "uy", "beyond": -60.0} | {"steps": 300},
//  "branch_switch": true, "imperfection": {"mode": 1, "amplitude": 0.001},
//  "stability": true, "save_every": 1, "desired_iterations": 5, "max_cuts": 10,
//  "frequencies": {"modes": 3, "mass": "consistent" | "lumped"}}     natural frequencies at every step
//
// Result analyses.<id>: type, status, termination, completed, free_dofs, control,
// steps[] {step, load_factor, control, arc_length, iterations, chord_iterations, nodes.<tracked>.displacement,
//          negative_eigenvalues, stable, min_eigenvalue, stiffness, compliance, compliance_bounded,
//          rank, null_space, unbounded_directions, rigid_directions, indices (when stiffness_node), reaction
//          (imposed motion), frequencies (Hz, with "frequencies"; null and frequencies_failure when the
//          eigen-solver failed), step_control (displacement control: "displacement", or "arc_length" through
//          a snap-back of the controlled DOF), statically_indeterminate (where the redundant constraint
//          rows were chosen afresh: those dropped from that step on)}, critical_points[] {type, load_factor, step, control,
//          negative_before, negative_after, load_work, reaction (imposed motion), branch_switched,
//          mode.nodes.<id>.displacement; a singularity also joints, nodes (ids) and passed},
// files: csv, vtk. Files: DIR/<id>.csv (one row per step), DIR/<id>.pvd and DIR/<id>_step<k>.vtu.
#include <fmt/format.h>

#include <iostream>
#include <optional>
#include <sstream>

#include "core/errors.hpp"
#include "io/analysis.hpp"
#include "io/stiffness_indices_output.hpp"
#include "io/atomic_file.hpp"
#include "io/json_util.hpp"
#include "io/model_check.hpp"
#include "io/load_reader.hpp"
#include "solvers/member_loading.hpp"
#include "solvers/element_factory.hpp"
#include "io/model_reader.hpp"
#include "io/result_status.hpp"
#include "solvers/structure.hpp"
#include "io/vtk_writer.hpp"
#include "solvers/path_following.hpp"

namespace beamfea {

namespace {

using json_in::child;

// Documented upper bounds (docs/analyses/path.md): beyond them a path would exhaust memory or
// time long before it told anything more.
constexpr int kMaxSteps = 100000;            // max_steps, stop steps, increments
constexpr int kMaxDesiredIterations = 100;
constexpr int kMaxCuts = 100;
constexpr int kMaxImperfectionMode = 1000;   // as buckling's "modes"
constexpr int kMaxFrequencyModes = 1000;     // as modal's "modes"

int dof_of(const nlohmann::json& v, const json_in::Pointer& p) { return json_in::dof_name(v, p, "dof", ""); }

// The smallest arc length (and `min`) accepted, relative to the model's size (Model::length_scale):
// ds is a length in the model's units (docs/analyses/path.md), and a step of 1e-12 of the model is
// at the round-off of its coordinates, so a path of such steps could never move (and takes
// max_steps steps to say so). Relative, so the same in every unit system.
constexpr double kMinArcLengthRatio = 1e-12;

// Arc-length limits that cannot work: below kMinArcLengthRatio of the model's size, `min` above
// `max`.
void check_arc_lengths(const Model& model, const json_in::Pointer& pc, const PathOptions& o) {
  const double floor = kMinArcLengthRatio * model.length_scale();
  const auto at_least_floor = [&](const char* key, double v) {
    if (v > 0.0 && v < floor)
      throw InputError(child(pc, key), fmt::format("path control: {} {:.6g} is below {:.0e} of the model's size ({:.6g}): "
                                                   "steps this small cannot move the model",
                                                   key, v, kMinArcLengthRatio, model.length_scale()));
  };
  at_least_floor("arc_length", o.arc_length_auto ? 0.0 : o.arc_length);
  at_least_floor("min", o.min_arc_length);
  if (o.min_arc_length > 0.0 && o.max_arc_length > 0.0 && o.min_arc_length > o.max_arc_length)
    throw InputError(child(pc, "min"), fmt::format("path control: min {:.6g} is above max {:.6g}", o.min_arc_length, o.max_arc_length));
}

PathOptions parse(const Model& model, const nlohmann::json& spec, const json_in::Pointer& p) {
  PathOptions o;
  json_in::expect_keys(spec, p, {"id", "type", "description", "control", "stop", "max_steps", "track", "stiffness_node",
                                 "branch_switch", "stability", "desired_iterations", "max_cuts", "imperfection",
                                 "save_every", "load_case", "frequencies"});
  const auto& c = json_in::object(json_in::require(spec, p, "control", "path analysis"), child(p, "control"), "path control");
  const json_in::Pointer pc = child(p, "control");
  json_in::expect_keys(c, pc, {"load_factor", "to", "node", "dof", "arc_length", "min", "max", "increments"});
  const int kinds = (c.contains("load_factor") ? 1 : 0) + (c.contains("to") ? 1 : 0) + (c.contains("arc_length") ? 1 : 0);
  if (kinds != 1)
    throw InputError(pc, "path control: give exactly one of 'load_factor', 'to' (with node and dof) or 'arc_length'");
  if (c.contains("load_factor")) {
    o.control = PathControl::LoadFactor;
    o.target = json_in::number(c["load_factor"], child(pc, "load_factor"), "control load_factor");
  } else if (c.contains("to")) {
    o.control = PathControl::Displacement;
    o.control_node = node_ref(model, json_in::require(c, pc, "node", "displacement control"), child(pc, "node"));
    o.control_dof = dof_of(json_in::require(c, pc, "dof", "displacement control"), child(pc, "dof"));
    o.target = json_in::number(c["to"], child(pc, "to"), "control to");
  } else {
    o.control = PathControl::ArcLength;
    if (c["arc_length"].is_string()) {
      const std::string v = json_in::string(c["arc_length"], child(pc, "arc_length"), "arc_length");
      if (v != "auto") throw InputError(child(pc, "arc_length"), "arc_length: a positive number or \"auto\", not '" + v + "'");
      o.arc_length_auto = true;
    } else {
      o.arc_length = json_in::positive(c["arc_length"], child(pc, "arc_length"), "arc_length");
    }
    if (c.contains("min")) o.min_arc_length = json_in::positive(c["min"], child(pc, "min"), "arc_length min");
    if (c.contains("max")) o.max_arc_length = json_in::positive(c["max"], child(pc, "max"), "arc_length max");
    check_arc_lengths(model, pc, o);
  }
  if (c.contains("increments")) {
    o.increments = json_in::integer_in(c["increments"], child(pc, "increments"), "increments", 1, kMaxSteps);
  }
  if (spec.contains("stop")) {
    const json_in::Pointer ps = child(p, "stop");
    const auto& s = json_in::object(spec["stop"], ps, "path stop");
    json_in::expect_keys(s, ps, {"load_factor", "beyond", "node", "dof", "steps"});
    if (s.contains("load_factor")) o.stop_load_factor = json_in::number(s["load_factor"], child(ps, "load_factor"), "stop load_factor");
    if (s.contains("beyond")) {
      o.stop_beyond = json_in::number(s["beyond"], child(ps, "beyond"), "stop beyond");
      o.stop_node = node_ref(model, json_in::require(s, ps, "node", "stop"), child(ps, "node"));
      o.stop_dof = dof_of(json_in::require(s, ps, "dof", "stop"), child(ps, "dof"));
    }
    if (s.contains("steps")) {
      o.stop_steps = json_in::integer_in(s["steps"], child(ps, "steps"), "stop steps", 1, kMaxSteps);
    }
  }
  if (spec.contains("max_steps")) {
    o.max_steps = json_in::integer_in(spec["max_steps"], child(p, "max_steps"), "max_steps", 1, kMaxSteps);
  }
  if (spec.contains("track")) {
    const auto& t = json_in::array(spec["track"], child(p, "track"), "track");
    for (std::size_t i = 0; i < t.size(); ++i) o.track.push_back(node_ref(model, t[i], child(child(p, "track"), i)));
  }
  if (spec.contains("stiffness_node")) o.stiffness_node = node_ref(model, spec["stiffness_node"], child(p, "stiffness_node"));
  if (spec.contains("branch_switch")) o.branch_switch = json_in::boolean(spec["branch_switch"], child(p, "branch_switch"), "branch_switch");
  if (spec.contains("stability")) o.stability = json_in::boolean(spec["stability"], child(p, "stability"), "stability");
  if (spec.contains("desired_iterations")) {
    o.desired_iterations =
        json_in::integer_in(spec["desired_iterations"], child(p, "desired_iterations"), "desired_iterations", 1, kMaxDesiredIterations);
  }
  if (spec.contains("max_cuts")) {
    o.max_cuts = json_in::integer_in(spec["max_cuts"], child(p, "max_cuts"), "max_cuts", 0, kMaxCuts);
  }
  if (spec.contains("imperfection")) {
    const json_in::Pointer pi = child(p, "imperfection");
    const auto& im = json_in::object(spec["imperfection"], pi, "imperfection");
    json_in::expect_keys(im, pi, {"mode", "amplitude"});
    o.imperfection_mode =
        json_in::integer_in(json_in::require(im, pi, "mode", "imperfection"), child(pi, "mode"), "imperfection mode", 1,
                            kMaxImperfectionMode);
    o.imperfection_amplitude = json_in::number(json_in::require(im, pi, "amplitude", "imperfection"), child(pi, "amplitude"), "imperfection amplitude");
  }
  if (spec.contains("frequencies")) {
    const json_in::Pointer pf = child(p, "frequencies");
    const auto& f = json_in::object(spec["frequencies"], pf, "path frequencies");
    json_in::expect_keys(f, pf, {"modes", "mass"});
    o.frequency_modes = f.contains("modes") ? json_in::integer_in(f["modes"], child(pf, "modes"), "frequencies modes", 1,
                                                                  kMaxFrequencyModes)
                                            : 1;
    if (f.contains("mass")) {
      o.frequency_mass = json_in::mass_kind(f["mass"], child(pf, "mass"), "frequencies mass", "path frequencies");
    }
  }
  if (o.branch_switch && o.control != PathControl::ArcLength)
    throw InputError(child(p, "branch_switch"), "branch switching needs arc-length control");
  return o;
}

struct PathSpec {
  PathOptions options;
  std::string load_case;  // "": the default loads
  int save_every = 1;     // a .vtu every save_every steps (and the last)
};

PathSpec check_path(const Model& model, const nlohmann::json& spec, const json_in::Pointer& p) {
  PathSpec ps;
  ps.load_case = read_load_case(model, spec, p);
  // A temperature change is an initial strain of the linear theory (FrameElement::thermal_loads);
  // the co-rotational beams of a path have no thermal strain.
  for (const MemberLoad& l : model.loads_for(ps.load_case).member)
    if (l.kind == MemberLoad::Kind::Temperature)
      throw InputError(child(p, "load_case"), "path: the loads of load case '" + (ps.load_case.empty() ? std::string(kDefaultLoadCase) : ps.load_case) +
                                                 "' include a temperature change on element '" + model.members[l.member].id +
                                                 "': temperature loads are for linear_static and the linear preloads (buckling, modal, stiffness), not for a path");
  ps.options = parse(model, spec, p);
  const PathOptions& o = ps.options;
  if (const nlohmann::json* save_every = json_in::field(spec, "save_every"))
    ps.save_every = json_in::integer_at_least(*save_every, child(p, "save_every"), "save_every", 1);
  // What the path needs of the model, decided before anything runs.
  check_nonlinear_model(model, p);
  // Dead loads follow the turning chord by their consistent vectors (elements/span_loads.hpp,
  // DeadLoadTerm), which know nothing of a wrapped element's condensation or arms.
  const std::vector<ElementLoads> member_loads = element_loads(model, model.loads_for(ps.load_case));
  for (std::size_t e = 0; e < member_loads.size(); ++e)
    if (!member_loads[e].empty() && is_transformed(model.elements[e]))
      throw InputError(p, "element '" + model.elements[e].id +
                              "': member loads and self-weight on a member with releases, offsets or rigid_ends are "
                              "not supported by path analyses (the linear analyses take them); load its nodes instead");
  const DofMap map(model);
  if (o.control == PathControl::Displacement) {
    const std::string why = why_held(model, map, o.control_node, o.control_dof);
    if (!why.empty())
      throw InputError(child(child(p, "control"), "dof"), "displacement control: " +
                                                              model.describe({DofRef::Owner::Node, o.control_node, o.control_dof}) +
                                                              " " + why + ": it cannot be the controlled DOF");
  } else {
    // The reference load: the analysis's load case, or the default loads.
    const Eigen::VectorXd f = external_force(model, map, model.loads_for(ps.load_case));
    if (f.size() == 0 || !(f.cwiseAbs().maxCoeff() > 0.0))
      throw InputError(child(p, "control"), "path: the model has no loads to scale; add \"loads\", or use displacement "
                                            "control ({\"node\", \"dof\", \"to\"}) to impose a motion");
  }
  if (o.frequency_modes > map.free_size())
    throw InputError(child(child(p, "frequencies"), "modes"),
                     fmt::format("path frequencies: {} modes asked for, but the model has only {} free DOFs",
                                 o.frequency_modes, map.free_size()));
  if (o.frequency_modes > 0) {
    bool has_mass = !model.masses.empty();
    for (const auto& e : model.elements)
      if (e.type == MemberType::Beam && model.materials[e.material].density > 0.0) has_mass = true;
    if (!has_mass)
      throw InputError(child(p, "frequencies"), "path frequencies: the model has no mass (give the materials a "
                                                "\"density\" or add \"masses\")");
  }
  if (o.imperfection_mode > 0 && o.imperfection_mode > map.free_size())
    throw InputError(child(child(p, "imperfection"), "mode"),
                     fmt::format("imperfection: buckling mode {} does not exist: the model has {} free DOF(s)",
                                 o.imperfection_mode, map.free_size()));
  return ps;
}

ojson node_map(const Model& model, const Eigen::VectorXd& raw) {
  ojson nodes = ojson::object();
  for (std::size_t n = 0; n < model.nodes.size(); ++n)
    append_new_key(nodes, model.nodes[n].id, ojson{{"displacement", to_json(Vec6(raw.segment<6>(6 * n)))}});
  return nodes;
}

const char* control_name(PathControl c) {
  switch (c) {
    case PathControl::LoadFactor: return "load_factor";
    case PathControl::Displacement: return "displacement";
    case PathControl::ArcLength: return "arc_length";
  }
  return "?";
}

// One step's object (`imposed`: a reaction is reported).
ojson step_json(const Model& model, const PathOptions& o, const PathStep& s, bool imposed) {
  ojson j = object_with_capacity(22);  // a step's keys (at most 21)
  j["step"] = s.step;
  j["load_factor"] = s.load_factor;
  j["control"] = s.control;
  j["arc_length"] = s.arc_length;
  // All corrector iterations of the step; those on the start state's factor also apart.
  j["iterations"] = s.iterations + s.chord_iterations;
  j["chord_iterations"] = s.chord_iterations;
  ojson nodes = ojson::object();
  for (std::size_t k = 0; k < o.track.size(); ++k)
    nodes[model.nodes[o.track[k]].id] = ojson{{"displacement", to_json(s.track[k])}};
  j["nodes"] = std::move(nodes);
  j["negative_eigenvalues"] = s.negative_eigenvalues;
  j["stable"] = s.stable;
  j["min_eigenvalue"] = s.min_eigenvalue;
  if (o.stiffness_node >= 0) {
    j["stiffness"] = s.stiffness ? to_json(*s.stiffness) : ojson(nullptr);
    const bool ok = s.node_stiffness && s.node_stiffness->ok;
    j["compliance"] = ok ? to_json(s.node_stiffness->compliance) : ojson(nullptr);
    j["compliance_bounded"] = ok ? ojson(s.node_stiffness->compliance_bounded()) : ojson(nullptr);
    j["rank"] = ok ? ojson(s.node_stiffness->rank) : ojson(nullptr);
    ojson ns = ojson::array(), ud = ojson::array(), rd = ojson::array();
    if (ok) {
      for (const auto& v : s.node_stiffness->null_space) ns.push_back(to_json(v));
      for (const auto& v : s.node_stiffness->unbounded_directions()) ud.push_back(to_json(v));
      for (const auto& v : s.node_stiffness->rigid_directions) rd.push_back(to_json(v));
    }
    j["null_space"] = std::move(ns);
    j["unbounded_directions"] = std::move(ud);
    j["rigid_directions"] = std::move(rd);
    ojson indices;  // null when the condensation failed
    if (ok) set_indices(indices, *s.node_stiffness, model.length_scale());
    j["indices"] = std::move(indices);
  }
  if (imposed) j["reaction"] = s.reaction;
  if (o.frequency_modes > 0) {
    j["frequencies"] = s.frequencies_failure.empty() ? to_json(s.frequencies) : ojson(nullptr);
    if (!s.frequencies_failure.empty()) j["frequencies_failure"] = s.frequencies_failure;
  }
  // Displacement control: "arc_length" on the steps taken through a snap-back of the controlled DOF.
  if (o.control == PathControl::Displacement) j["step_control"] = control_name(s.step_control);
  // Where the redundant constraint rows were chosen afresh: the rows dropped from this step on.
  if (s.statically_indeterminate) j["statically_indeterminate"] = *s.statically_indeterminate;
  return j;
}

ojson critical_points_json(const Model& model, const PathResult& r, bool imposed) {
  ojson cps = ojson::array();
  for (const auto& c : r.critical_points) {
    ojson j = object_with_capacity(14);  // a critical point's keys
    j["type"] = to_string(c.type);
    j["load_factor"] = c.load_factor;
    j["step"] = c.step;
    j["control"] = c.control;
    j["negative_before"] = c.negative_before;
    j["negative_after"] = c.negative_after;
    j["load_work"] = c.load_work;
    if (imposed) j["reaction"] = c.reaction;
    j["branch_switched"] = c.branch_switched;
    j["mode"] = c.mode.size() ? ojson{{"nodes", node_map(model, c.mode)}} : ojson(nullptr);
    if (c.type == CriticalPointType::Singularity) {  // the loop's joints and nodes, by id
      ojson joints = ojson::array(), nodes = ojson::array();
      for (int k : c.joints) joints.push_back(model.joints[k].id);
      for (int n : c.nodes) nodes.push_back(model.nodes[n].id);
      j["joints"] = std::move(joints);
      j["nodes"] = std::move(nodes);
      j["passed"] = c.passed;
    }
    cps.push_back(std::move(j));
  }
  return cps;
}

// DIR/<id>.csv: one row per step.
std::string path_csv(const Model& model, const PathOptions& o, const PathResult& r, bool imposed) {
  std::ostringstream csv;
  csv << "step,load_factor,control,arc_length,iterations,negative_eigenvalues,stable,min_eigenvalue";
  if (imposed) csv << ",reaction";
  for (int k = 0; k < o.frequency_modes; ++k) csv << ",f" << k + 1;
  for (int n : o.track)
    for (const char* d : kDofNames) csv << "," << model.nodes[n].id << "_" << d;
  csv << "\n";
  for (const auto& s : r.steps) {
    csv << fmt::format("{},{:.17g},{:.17g},{:.17g},{},{},{},{:.17g}", s.step, s.load_factor, s.control, s.arc_length,
                       s.iterations + s.chord_iterations, s.negative_eigenvalues, s.stable ? 1 : 0, s.min_eigenvalue);
    if (imposed) csv << fmt::format(",{:.17g}", s.reaction);
    for (int k = 0; k < o.frequency_modes; ++k)  // empty cells where fewer (or none) were found
      csv << (k < s.frequencies.size() ? fmt::format(",{:.17g}", s.frequencies[k]) : std::string(","));
    for (const auto& t : s.track)
      for (int k = 0; k < 6; ++k) csv << fmt::format(",{:.17g}", t[k]);
    csv << "\n";
  }
  return csv.str();
}

// DIR/<id>_step<k>.vtu every save_every steps (and the last), and DIR/<id>.pvd.
void write_path_vtk(const AnalysisContext& ctx, const Model& model, const PathResult& r, int save_every) {
  const NonlinearStructure ns(model);
  std::vector<std::pair<double, std::string>> entries;
  for (std::size_t i = 0; i < r.steps.size(); ++i) {
    const auto& s = r.steps[i];
    if (i % static_cast<std::size_t>(save_every) != 0 && i + 1 != r.steps.size()) continue;
    VtkFrame f;
    for (std::size_t n = 0; n < model.nodes.size(); ++n) {
      f.displacement.push_back(s.state.x[n] - model.nodes[n].x);
      f.rotation.push_back(log_so3(s.state.R[n]));
    }
    f.end_forces = s.end_forces;
    f.shape = [&](int e, double xi) { return ns.beam_shape(s.state, e, xi); };
    f.field_data["load_factor"] = s.load_factor;
    f.field_data["step"] = s.step;
    f.field_data["stable"] = s.stable ? 1.0 : 0.0;
    f.field_data["control"] = s.control;
    const std::string file = fmt::format("{}_step{}.vtu", ctx.id, s.step);
    write_vtu((ctx.out_dir / file).string(), model, f);
    entries.emplace_back(static_cast<double>(s.step), file);
  }
  write_pvd((ctx.out_dir / (ctx.id + ".pvd")).string(), entries);
}

AnalysisOutcome run_path(const AnalysisContext& ctx, const PathSpec& spec) {
  // The reference load: the analysis's load case, or the default loads (no copy of the model).
  const Model& model = ctx.model;
  const LoadSet& loads = model.loads_for(spec.load_case);
  PathOptions o = spec.options;
  // One line per step on stderr through the run's progress sink (silent with --quiet).
  if (ctx.progress) o.progress = [&](const std::string& s) { ctx.progress("path " + ctx.id + ": " + s); };
  const PathResult r = follow_path(model, loads, o);
  if (ctx.warning && r.termination == PathTermination::MaxSteps)
    ctx.warning(fmt::format("analysis '{}': the path used up max_steps ({}) before its target or a stop, at load "
                            "factor {:.6g} (raise max_steps, or take longer steps)",
                            ctx.id, o.max_steps, r.steps.empty() ? 0.0 : r.steps.back().load_factor));
  for (const auto& c : r.critical_points)
    if (ctx.warning && c.type == CriticalPointType::Singularity && c.passed)
      ctx.warning(fmt::format("analysis '{}': the path passed a singular pose at load factor {:.6g} (control {:.6g}): {}",
                              ctx.id, c.load_factor, c.control, c.what));
  std::string rechosen;  // the steps where the redundant rows were chosen afresh
  int times = 0;
  for (const auto& s : r.steps)
    if (s.statically_indeterminate) rechosen += (times++ ? ", " : "") + std::to_string(s.step);
  if (ctx.warning && times)
    ctx.warning(fmt::format("analysis '{}': the redundant constraint rows were chosen afresh along the path, at step{} {} "
                            "(the rows kept lost rank there; each such step's statically_indeterminate names the rows "
                            "dropped from it on)",
                            ctx.id, times > 1 ? "s" : "", rechosen));
  const bool imposed = o.control == PathControl::Displacement && r.steps.size() &&
                       std::any_of(r.steps.begin(), r.steps.end(), [](const PathStep& s) { return s.reaction != 0.0; });

  AnalysisOutcome out;
  // Room for every key (13 with run_document's wall_time_s): an ordered_json object that grows
  // deep copies what it holds (here the steps).
  out.result = object_with_capacity(16);
  out.result["type"] = "path";
  out.result["status"] = path_status(r.completed);
  out.result["termination"] = r.brief_report();
  out.result["completed"] = r.completed;
  out.result["control"] = control_name(o.control);
  out.result["free_dofs"] = r.free_dofs;
  if (!r.completed) out.termination = AnalysisTermination::NotConverged;
  out.result["statically_indeterminate"] = r.statically_indeterminate;
  out.message = fmt::format("path: {} steps, {}", r.steps.empty() ? 0 : r.steps.size() - 1, r.brief_report());
  ojson steps = ojson::array();
  for (const auto& s : r.steps) steps.push_back(step_json(model, o, s, imposed));
  out.result["steps"] = std::move(steps);
  out.result["critical_points"] = critical_points_json(model, r, imposed);
  out.result["factorizations"] = r.factorizations;
  out.result["symbolic_analyses"] = r.symbolic_analyses;
  if (!ctx.out_dir.empty()) {
    write_text_atomic(ctx.out_dir / (ctx.id + ".csv"), path_csv(model, o, r, imposed));
    ojson files;
    files["csv"] = ctx.id + ".csv";
    if (ctx.write_vtk) {
      write_path_vtk(ctx, model, r, spec.save_every);
      files["vtk"] = ctx.id + ".pvd";
    }
    out.result["files"] = std::move(files);
  }
  return out;
}

}  // namespace

AnalysisType path_analysis() {
  return register_analysis<PathSpec>("path", check_path, run_path, [](const std::string& id) {
    return AnalysisFiles{{id + ".csv", id + ".pvd"}, {id + "_step"}};
  });
}

}  // namespace beamfea
