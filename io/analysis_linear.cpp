// Analyses "linear_static" and "stiffness".
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <utility>

#include "core/errors.hpp"
#include "io/analysis.hpp"
#include "io/ellipsoid_vtk.hpp"
#include "io/json_util.hpp"
#include "io/model_check.hpp"
#include "io/load_reader.hpp"
#include "io/model_reader.hpp"
#include "io/result_status.hpp"
#include "io/static_results.hpp"
#include "io/stiffness_indices_output.hpp"
#include "io/vtk_writer.hpp"
#include "solvers/condensed_stiffness.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/member_loading.hpp"

namespace beamfea {

// Objects here are built with room for all their keys (object_with_capacity) and filled by moves:
// an ordered_json object that grows deep copies what it holds, which at 97,344 DOFs cost a tenth
// of the whole run (the result object copying its nodes and elements when its tenth key came).

void set_solver_report(ojson& v, const SolverReport& report) {
  ObjectFiller o(v, 3);
  set_string(o.slot("type"), report.iterative ? "iterative" : "direct");
  o.slot("iterations") = report.iterations;
  o.slot("residual") = report.residual;
  o.finish();
}

ojson mechanism_json(const Model& model, const std::vector<ZeroEnergyMode>& modes) {
  ojson out = ojson::array();
  for (const auto& m : modes) {
    ojson o = object_with_capacity(5);
    o["description"] = m.description;
    ojson nodes = ojson::array(), elements = ojson::array(), joints = ojson::array(), dofs = ojson::array();
    for (int n : m.nodes) nodes.push_back(model.nodes[n].id);
    for (int e : m.elements) elements.push_back(model.elements[e].id);
    for (int j : m.joints) joints.push_back(model.joints[j].id);
    for (const auto& d : m.dofs) dofs.push_back(model.describe(d));
    o["nodes"] = std::move(nodes);
    o["elements"] = std::move(elements);
    o["joints"] = std::move(joints);
    o["dofs"] = std::move(dofs);
    out.push_back(std::move(o));
  }
  return out;
}

namespace {

// [first six, last six] of a 12-vector: a pair of 6-vectors (end 1, end 2), written over `v`.
void set_ends(ojson& v, const Vec12& x) {
  auto& ends = set_array(v, 2);
  set_numbers(ends[0], x.data(), 6);
  set_numbers(ends[1], x.data() + 6, 6);
}

// One member's output, written over `v`: a member meshed into several elements reports the forces
// at its own ends (first element's end 1, last element's end 2), and the section forces at
// stations along it.
// `stations`, `positions`: storage for member_stations, kept by the caller.
void set_member(ojson& v, const Model& model, const LinearStaticResult& r, std::size_t mi, int interior_stations,
                std::vector<Station>& stations, std::vector<double>& positions) {
  const std::vector<Vec12>& end_forces = r.end_forces;
  const auto& mem = model.members[mi];
  const Vec12& first = end_forces[mem.elements.front()];
  const Vec12& last = end_forces[mem.elements.back()];
  Vec12 ends;
  ends << first.head<6>(), last.tail<6>();
  const Vec12 s = section_forces(ends);
  ObjectFiller o(v, 4);
  set_ends(o.slot("end_forces"), ends);
  set_ends(o.slot("section_forces"), s);
  if (mem.type == MemberType::Beam) {
    member_stations(model, static_cast<int>(mi), end_forces, r.element_loads, interior_stations, stations, positions);
    auto& items = set_array(o.slot("stations"), stations.size());
    for (std::size_t k = 0; k < stations.size(); ++k) {
      ObjectFiller station(items[k], 2);
      station.slot("x") = stations[k].x;
      set_numbers(station.slot("forces"), stations[k].forces.data(), 6);
      station.finish();
    }
  }
  if (mem.elements.size() > 1) {
    auto& items = set_array(o.slot("segments"), mem.elements.size());
    for (std::size_t k = 0; k < mem.elements.size(); ++k) {
      const int e = mem.elements[k];
      ObjectFiller seg(items[k], 2);
      set_string(seg.slot("id"), model.elements[e].id);
      set_ends(seg.slot("end_forces"), end_forces[e]);
      seg.finish();
    }
  }
  o.finish();
}

// Whether every number set_member writes for member `mi` is finite, answered from what they are
// made of without writing them: its elements' end forces (its end and section forces are those
// with signs changed, its segments' are those) and its stations.
bool member_finite(const Model& model, const LinearStaticResult& r, std::size_t mi, int interior_stations,
                   std::vector<Station>& stations, std::vector<double>& positions) {
  const auto& mem = model.members[mi];
  for (const int e : mem.elements)
    if (!r.end_forces[e].allFinite()) return false;
  if (mem.type != MemberType::Beam) return true;
  member_stations(model, static_cast<int>(mi), r.end_forces, r.element_loads, interior_stations, stations, positions);
  for (const auto& st : stations)
    if (!std::isfinite(st.x) || !st.forces.allFinite()) return false;
  return true;
}

// One node's output, written over `v`: its displacement, and its reaction where it is supported.
void set_node(ojson& v, const LinearStaticResult& r, std::size_t n) {
  ObjectFiller o(v, 3);
  set_numbers(o.slot("displacement"), r.u.data() + 6 * n, 6);
  if (r.supported[n]) set_numbers(o.slot("reaction"), r.reactions[n].data(), 6);
  if (!r.skewed.empty() && r.skewed[n]) set_numbers(o.slot("reaction_local"), r.reactions_local[n].data(), 6);
  o.finish();
}

// Whether every number set_node writes for node `n` is finite.
bool node_finite(const LinearStaticResult& r, std::size_t n) {
  return r.u.segment(static_cast<Eigen::Index>(6 * n), 6).allFinite() && (!r.supported[n] || r.reactions[n].allFinite()) &&
         (r.skewed.empty() || !r.skewed[n] || r.reactions_local[n].allFinite());
}

// A deferred object (io/deferred_results.hpp) of `count` members, made one by one while
// results.json is written: member i is keyed `key(i)`, written over a reused value by
// `set(v, i, scratch)`, and its numbers are all finite when `finite(i, scratch)`. Each range (and
// the check) has its own `Scratch`, on its stack: ranges may be made at once on several threads.
template <class Scratch, class Key, class Set, class Finite>
void defer_each(DeferredParts& deferred, ojson& slot, std::size_t count, Key key, Set set, Finite finite) {
  DeferredMembers part;
  part.size = count;
  part.make = [key, set](std::size_t first, std::size_t end, const MemberSink& emit) {
    ojson v;
    Scratch scratch;
    for (std::size_t i = first; i < end; ++i) {
      set(v, i, scratch);
      emit(key(i), v);
    }
  };
  part.all_finite = [count, finite] {
    Scratch scratch;
    for (std::size_t i = 0; i < count; ++i)
      if (!finite(i, scratch)) return false;
    return true;
  };
  deferred.defer(slot, std::move(part));
}

// The nodes' and the members' objects, deferred: made from `r`, which the parts share.
struct NoScratch {};
struct StationScratch {
  std::vector<Station> stations;
  std::vector<double> positions;
};
void defer_nodes(DeferredParts& deferred, ojson& slot, const Model& model, std::shared_ptr<const LinearStaticResult> r) {
  defer_each<NoScratch>(
      deferred, slot, model.nodes.size(), [&model](std::size_t n) -> const std::string& { return model.nodes[n].id; },
      [r](ojson& v, std::size_t n, NoScratch&) { set_node(v, *r, n); },
      [r](std::size_t n, NoScratch&) { return node_finite(*r, n); });
}
void defer_members(DeferredParts& deferred, ojson& slot, const Model& model, std::shared_ptr<const LinearStaticResult> r,
                   int interior_stations) {
  defer_each<StationScratch>(
      deferred, slot, model.members.size(), [&model](std::size_t m) -> const std::string& { return model.members[m].id; },
      [&model, r, interior_stations](ojson& v, std::size_t m, StationScratch& s) {
        set_member(v, model, *r, m, interior_stations, s.stations, s.positions);
      },
      [&model, r, interior_stations](std::size_t m, StationScratch& s) {
        return member_finite(model, *r, m, interior_stations, s.stations, s.positions);
      });
}

// Interior stations per member (the spec's "stations"), default 10.
constexpr int kDefaultStations = 10;
constexpr int kMaxStations = 10000;

struct LinearStaticSpec {
  std::string load_case;  // "": the default loads
  int stations = kDefaultStations;
};

}  // namespace

int read_stations(const nlohmann::json& spec, const json_in::Pointer& p, const std::string& type) {
  const nlohmann::json* stations = json_in::field(spec, "stations");
  if (!stations) return kDefaultStations;
  const int n = json_in::integer_at_least(*stations, json_in::child(p, "stations"), type + " stations", 0);
  if (n > kMaxStations) throw InputError(json_in::child(p, "stations"), type + ": at most 10000 stations");
  return n;
}

namespace {

LinearStaticSpec check_linear_static(const Model& model, const nlohmann::json& spec, const json_in::Pointer& p) {
  LinearStaticSpec s;
  s.load_case = read_load_case(model, spec, p);
  json_in::expect_keys(spec, p, {"id", "type", "description", "load_case", "stations"});
  s.stations = read_stations(spec, p, "linear_static");
  return s;
}

// The linear system of the run (one factorisation for every linear case of the run): with a
// workspace kept from the last run (a sweep worker's), the system of the last run when the
// model's structure is the same (solvers/structure_cache.hpp).
std::shared_ptr<const LinearSystem> run_linear_system(const AnalysisContext& ctx) {
  if (ctx.cache && ctx.cache->linear) return ctx.cache->linear;
  RunWorkspace* kept = ctx.cache ? ctx.cache->workspace : nullptr;
  LinearStaticOptions options;
  options.parallel = ctx.parallel;
  std::shared_ptr<const LinearSystem> system =
      kept ? kept->systems.get(ctx.model) : std::make_shared<const LinearSystem>(ctx.model, options);
  if (ctx.cache) ctx.cache->linear = system;
  return system;
}

// The displaced shape and the section forces, as DIR/<id>.vtu.
void write_linear_vtu(const AnalysisContext& ctx, const LinearStaticResult& r, const std::string& file) {
  const Model& model = ctx.model;
  VtkFrame f;
  for (std::size_t n = 0; n < model.nodes.size(); ++n) {
    f.displacement.push_back(r.u.segment<3>(6 * n));
    f.rotation.push_back(r.u.segment<3>(6 * n + 3));
  }
  f.end_forces = r.end_forces;
  // Diagrams follow the member loads between the nodes.
  f.section_forces = [&](int e, double xi) {
    const auto& el = model.elements[e];
    const double Le = (flexible_end(model, el, 1) - flexible_end(model, el, 0)).norm();
    return section_forces_at(xi * Le, r.end_forces[e], r.element_loads[e]);
  };
  write_vtu((ctx.out_dir / file).string(), model, f);
}

// The joints' coordinates and reactions, written over `v`.
void set_joints(ojson& v, const Model& model, const LinearStaticResult& r) {
  ObjectFiller joints(v, model.joints.size());
  std::size_t offset = 6 * model.nodes.size();
  for (std::size_t j = 0; j < model.joints.size(); ++j) {
    const auto nc = static_cast<std::size_t>(model.joints[j].coordinates());
    ObjectFiller o(joints.slot(model.joints[j].id), 2);
    set_numbers(o.slot("coordinates"), r.u.data() + offset, nc);
    set_numbers(o.slot("reaction"), r.joint_forces[j].data(), 6);
    o.finish();
    offset += nc;
  }
  joints.finish();
}

}  // namespace

void set_static_solution(ObjectFiller& res, const AnalysisContext& ctx, std::shared_ptr<const LinearStaticResult> held,
                         int stations, std::vector<Station>& station_storage, std::vector<double>& position_storage) {
  const Model& model = ctx.model;
  const LinearStaticResult& r = *held;
  if (ctx.deferred) {
    // Nobody reads the tree (`beamfea run`): the nodes and members are made as results.json is
    // written. The parts hold the solution: a fresh one is shared with them; a kept one (a reused
    // report's) lives in the run's workspace, which outlives the writing.
    defer_nodes(*ctx.deferred, res.slot("nodes"), model, held);
    defer_members(*ctx.deferred, res.slot("elements"), model, held, stations);
  } else {
    ObjectFiller nodes(res.slot("nodes"), model.nodes.size());
    for (std::size_t n = 0; n < model.nodes.size(); ++n) set_node(nodes.slot(model.nodes[n].id), r, n);
    nodes.finish();
    ObjectFiller members(res.slot("elements"), model.members.size());
    for (std::size_t m = 0; m < model.members.size(); ++m)
      set_member(members.slot(model.members[m].id), model, r, m, stations, station_storage, position_storage);
    members.finish();
  }
  set_joints(res.slot("joints"), model, r);
  // The forces of ties (on nodes[1], per DOF ux..rz) and the multipliers of linear constraints.
  if (!model.ties.empty()) set_vectors(res.slot("tie_forces"), r.tie_forces);
  if (!model.constraints.empty()) set_numbers(res.slot("constraint_forces"), r.constraint_forces.data(), r.constraint_forces.size());
  set_strings(res.slot("statically_indeterminate"), r.statically_indeterminate);
  if (!ctx.out_dir.empty() && ctx.write_vtk) {
    const std::string file = ctx.id + ".vtu";
    write_linear_vtu(ctx, r, file);
    set_string(res.slot("vtk"), file);
  }
}

namespace {

// The keys of a linear_static result (type, load_case, status, message, free_dofs, factorizations,
// solver, mechanism, nodes, elements, joints, tie_forces, constraint_forces, statically_indeterminate,
// vtk) and run_document's wall_time_s.
constexpr std::size_t kLinearStaticResultKeys = 16;

// Below this reciprocal condition estimate of the Jacobi-scaled stiffness (LinearSystem::rcond) a
// linear solution is flagged as doubtful: the relative error bound eps / rcond passes about 2e-6,
// so the last of the 6-7 significant digits results are read with may be wrong. Unit-free.
constexpr double kDoubtfulRcond = 1e-10;

AnalysisOutcome run_linear_static(const AnalysisContext& ctx, const LinearStaticSpec& spec) {
  const Model& model = ctx.model;
  // Tension-only and compression-only members: solved until their set stays the same.
  if (has_behaviour_members(model)) {
    SecondOrderOptions options;
    options.geometric = false;
    return run_iterated_static(ctx, "linear_static", spec.load_case, spec.stations, options);
  }
  AnalysisOutcome out;
  const std::shared_ptr<const LinearSystem> system = run_linear_system(ctx);
  // With a workspace kept from the last run, the solution is written over the last one.
  RunWorkspace* kept = ctx.cache ? ctx.cache->workspace : nullptr;
  const LoadSet& loads = model.loads_for(spec.load_case);
  std::shared_ptr<const LinearStaticResult> fresh;  // when nothing is kept (shared with deferred parts)
  std::vector<Station> fresh_stations;
  std::vector<double> fresh_positions;
  if (kept) system->solve(loads, kept->linear, kept->linear_scratch);
  else fresh = std::make_shared<const LinearStaticResult>(system->solve(loads));
  const LinearStaticResult& r = kept ? kept->linear : *fresh;
  const int stations = spec.stations;
  // Written over the previous run's result when there is one (a sweep worker's: the nodes' and
  // elements' objects and arrays keep their storage when the model keeps its shape).
  if (ctx.previous_result) out.result = std::move(*ctx.previous_result);
  ObjectFiller res(out.result, kLinearStaticResultKeys);
  set_string(res.slot("type"), "linear_static");
  if (!spec.load_case.empty()) set_string(res.slot("load_case"), spec.load_case);
  set_string(res.slot("status"), result_status(r.status));
  set_string(res.slot("message"), r.message);
  res.slot("free_dofs") = r.free_dofs;
  res.slot("factorizations") = system->factorizations();
  // Copied into the previous run's message storage when there is one (no allocation in a sweep).
  if (ctx.previous_message) out.message.swap(*ctx.previous_message);
  out.message.assign(r.message);
  if (r.status == SolveStatus::Succeeded || r.status == SolveStatus::NotConverged) set_solver_report(res.slot("solver"), r.solver);
  if (r.status != SolveStatus::Succeeded) {
    out.termination = r.status == SolveStatus::Mechanism      ? AnalysisTermination::Mechanism
                      : r.status == SolveStatus::NotConverged ? AnalysisTermination::NotConverged
                                                              : AnalysisTermination::Failed;
    if (r.status != SolveStatus::NotConverged) res.slot("mechanism") = mechanism_json(model, r.modes);
    res.finish();
    return out;
  }
  if (ctx.warning && system->rcond() < kDoubtfulRcond)
    ctx.warning(fmt::format("analysis '{}': the stiffness is ill-conditioned (reciprocal condition estimate {:.3g} of the "
                            "Jacobi-scaled K, about {:.0f} of 16 digits lost): the answer is doubtful; look for parts far "
                            "stiffer or softer than the rest, or a near-mechanism",
                            ctx.id, system->rcond(), std::ceil(-std::log10(system->rcond()))));
  auto held = kept ? std::shared_ptr<const LinearStaticResult>(std::shared_ptr<void>(), &kept->linear) : fresh;
  set_static_solution(res, ctx, held, stations, kept ? kept->stations : fresh_stations,
                      kept ? kept->station_positions : fresh_positions);
  res.finish();
  return out;
}

// The keys of a stiffness result (type, node, load_case, about, geometric_stiffness, status, message, matrix, rank, null_space,
// compliance, compliance_bounded, unbounded_directions, rigid_directions, statically_indeterminate,
// length_scale, scaled_eigenvalues, indices, ellipsoid, solver), and run_document's wall_time_s.
constexpr std::size_t kStiffnessResultKeys = 21;

struct StiffnessSpec {
  int node = -1;
  std::string load_case;  // "": the linear stiffness; otherwise the loaded-mode one about this case
  PreloadOptions preload;  // about which equilibrium of the case, with which K_g
  IndicesRequest indices;  // "directions", "reference_wrench"
  bool ellipsoid = false;  // write DIR/<id>_ellipsoid.vtp
};

StiffnessSpec check_stiffness(const Model& model, const nlohmann::json& spec, const json_in::Pointer& p) {
  StiffnessSpec s;
  s.load_case = read_load_case(model, spec, p);
  json_in::expect_keys(spec, p,
                       {"id", "type", "description", "node", "load_case", "about", "geometric_stiffness", "directions",
                        "reference_wrench", "ellipsoid"});
  s.preload = read_preload(spec, p, "stiffness", !s.load_case.empty());
  if (s.preload.about == Equilibrium::SecondOrder) check_nonlinear_model(model, p);
  s.node = node_ref(model, json_in::require(spec, p, "node", "stiffness analysis"), json_in::child(p, "node"));
  s.indices = read_indices_request(spec, p);
  if (const nlohmann::json* e = json_in::field(spec, "ellipsoid"))
    s.ellipsoid = json_in::boolean(*e, json_in::child(p, "ellipsoid"), "stiffness ellipsoid");
  // Any node answers: where supports, loops or rigid links hold it, its compliance is zero and
  // rigid_directions names the directions (solvers/condensed_stiffness.hpp, node_compliance).
  return s;
}

// The translational compliance ellipsoid, written over `v`: {scale, semi_axes, axes, file}, and
// DIR/<id>_ellipsoid.vtp when the run writes VTK files ("file" only then).
void set_ellipsoid(ojson& v, const AnalysisContext& ctx, const CondensedStiffness& k, int node) {
  const ComplianceAxes axes = compliance_axes(k.compliance.topLeftCorner<3, 3>());
  const double scale = ellipsoid_scale(axes, ctx.model.length_scale());
  ObjectFiller o(v, 4);
  o.slot("scale") = scale;
  set_numbers(o.slot("semi_axes"), axes.semi_axes.data(), 3);
  auto& directions = set_array(o.slot("axes"), 3);
  for (std::size_t i = 0; i < 3; ++i) set_numbers(directions[i], axes.axes.col(static_cast<Eigen::Index>(i)).data(), 3);
  if (!ctx.out_dir.empty() && ctx.write_vtk) {
    const std::string file = ctx.id + "_ellipsoid.vtp";
    write_compliance_ellipsoid((ctx.out_dir / file).string(), ctx.model.nodes[node].x, axes, scale);
    set_string(o.slot("file"), file);
  }
  o.finish();
}

AnalysisOutcome run_stiffness(const AnalysisContext& ctx, const StiffnessSpec& spec) {
  const Model& model = ctx.model;
  const int node = spec.node;
  AnalysisOutcome out;
  // With a load case, the loaded-mode stiffness about its preload (K + K_g).
  const bool loaded = !spec.load_case.empty();
  // Written over the last run's when a workspace is kept (a sweep worker's: the vectors of
  // directions and names keep their storage).
  RunWorkspace* kept = ctx.cache ? ctx.cache->workspace : nullptr;
  CondensedStiffness fresh;
  CondensedStiffness& k = kept ? kept->stiffness : fresh;
  if (loaded) {
    k = loaded_node_stiffness(model, model.loads_for(spec.load_case), node, spec.preload);
  } else {
    // The message formatted into the previous run's message storage, when there is one (a sweep
    // case then allocates nothing for it).
    if (ctx.previous_message) k.message.swap(*ctx.previous_message);
    linear_node_stiffness(model, node, k);
  }
  // Written over the previous run's result when there is one (its storage reused: a sweep case
  // allocates nothing for it), with room for every key (and run_document's wall_time_s): an
  // ordered_json object that grows deep copies what it already holds.
  if (ctx.previous_result) out.result = std::move(*ctx.previous_result);
  ObjectFiller r(out.result, kStiffnessResultKeys);
  set_string(r.slot("type"), "stiffness");
  set_string(r.slot("node"), model.nodes[node].id);
  if (loaded) {
    set_string(r.slot("load_case"), spec.load_case);
    set_string(r.slot("about"), spec.preload.about == Equilibrium::SecondOrder ? "second_order" : "linear_static");
    set_string(r.slot("geometric_stiffness"), spec.preload.geometric_stiffness == GeometricStiffness::Full ? "full" : "axial");
  }
  set_string(r.slot("status"), k.not_converged ? result_status(SolveStatus::NotConverged) : stiffness_status(k.ok));
  set_string(r.slot("message"), k.message);
  out.message = std::move(k.message);
  if (k.ok || k.not_converged) set_solver_report(r.slot("solver"), k.solver);
  if (k.not_converged) {
    out.termination = AnalysisTermination::NotConverged;
    r.finish();
    return out;
  }
  if (!k.ok) {
    out.termination = AnalysisTermination::Mechanism;
    r.slot("mechanism") = mechanism_json(model, k.modes);
    r.finish();
    return out;
  }
  set_matrix(r.slot("matrix"), k.K);
  r.slot("rank") = k.rank;
  set_vectors(r.slot("null_space"), k.null_space);
  set_matrix(r.slot("compliance"), k.compliance);
  r.slot("compliance_bounded") = k.compliance_bounded();
  set_vectors(r.slot("unbounded_directions"), k.unbounded_directions());
  set_vectors(r.slot("rigid_directions"), k.rigid_directions);
  set_strings(r.slot("statically_indeterminate"), k.statically_indeterminate);
  r.slot("length_scale") = model.length_scale();
  set_numbers(r.slot("scaled_eigenvalues"), k.eigenvalues.data(), static_cast<std::size_t>(k.eigenvalues.size()));
  set_indices(r.slot("indices"), k, model.length_scale(), spec.indices);
  if (spec.ellipsoid) set_ellipsoid(r.slot("ellipsoid"), ctx, k, node);
  r.finish();
  return out;
}

}  // namespace

AnalysisType linear_static_analysis() {
  return register_analysis<LinearStaticSpec>("linear_static", check_linear_static, run_linear_static,
                                             [](const std::string& id) { return AnalysisFiles{{id + ".vtu"}, {}}; });
}
AnalysisType stiffness_analysis() {
  return register_analysis<StiffnessSpec>("stiffness", check_stiffness, run_stiffness, [](const std::string& id) {
    return AnalysisFiles{{id + "_ellipsoid.vtp"}, {}};  // with "ellipsoid": true
  });
}

}  // namespace beamfea
