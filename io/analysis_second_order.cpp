// Analysis "second_order": P-Delta statics (solvers/second_order.hpp).
//   {"id": "s", "type": "second_order", "load_case": ..., "tolerance": 1e-10, "max_iterations": 100,
//    "geometric_stiffness": "full" | "axial", "stations": 10}
// Result analyses.<id>: as linear_static's (type, load_case, status, message, free_dofs,
// factorizations, nodes, elements with end_forces and stations, joints, statically_indeterminate,
// vtk) plus geometric_stiffness, iterations, amplification, inactive_members, and when it diverged
// critical_load_factor and the linear step's nodes and elements. Also the writer of linear_static
// for a model with tension-only or compression-only members (inactive_members added).
#include <fmt/format.h>

#include <cmath>

#include "core/errors.hpp"
#include "io/json_util.hpp"
#include "io/load_reader.hpp"
#include "io/result_status.hpp"
#include "io/static_results.hpp"

namespace beamfea {

namespace {

struct SecondOrderSpec {
  std::string load_case;  // "": the default loads
  int stations = 0;
  SecondOrderOptions options;
};

// The bound of "max_iterations" (each is a factorisation).
constexpr int kMaxSecondOrderIterations = 10000;

SecondOrderSpec check_second_order(const Model& model, const nlohmann::json& spec, const json_in::Pointer& p) {
  SecondOrderSpec s;
  s.load_case = read_load_case(model, spec, p);
  json_in::expect_keys(spec, p,
                       {"id", "type", "description", "load_case", "stations", "tolerance", "max_iterations", "geometric_stiffness"});
  s.stations = read_stations(spec, p, "second_order");
  if (const nlohmann::json* t = json_in::field(spec, "tolerance")) {
    const json_in::Pointer tp = json_in::child(p, "tolerance");
    s.options.tolerance = json_in::positive(*t, tp, "second_order tolerance");
    if (s.options.tolerance >= 1.0) throw InputError(tp, "second_order: tolerance must be below 1 (a relative change)");
  }
  if (const nlohmann::json* n = json_in::field(spec, "max_iterations"))
    s.options.max_iterations = json_in::integer_in(*n, json_in::child(p, "max_iterations"), "second_order max_iterations", 1,
                                                   kMaxSecondOrderIterations);
  if (const nlohmann::json* g = json_in::field(spec, "geometric_stiffness"))
    s.options.kind = json_in::geometric_stiffness_kind(*g, json_in::child(p, "geometric_stiffness"),
                                                       "second_order geometric_stiffness", "second_order");
  check_nonlinear_model(model, p);
  return s;
}

AnalysisTermination termination_of(SecondOrderStatus s) {
  switch (s) {
    case SecondOrderStatus::Converged: return AnalysisTermination::Succeeded;
    case SecondOrderStatus::Mechanism: return AnalysisTermination::Mechanism;
    case SecondOrderStatus::NotConverged: return AnalysisTermination::NotConverged;
    case SecondOrderStatus::Diverged:
    case SecondOrderStatus::Failed: return AnalysisTermination::Failed;
  }
  return AnalysisTermination::Failed;
}

AnalysisOutcome run_second_order(const AnalysisContext& ctx, const SecondOrderSpec& spec) {
  return run_iterated_static(ctx, "second_order", spec.load_case, spec.stations, spec.options);
}

}  // namespace

PreloadOptions read_preload(const nlohmann::json& spec, const json_in::Pointer& p, const std::string& type, bool loaded) {
  PreloadOptions out;
  if (const nlohmann::json* about = json_in::field(spec, "about")) {
    const json_in::Pointer ap = json_in::child(p, "about");
    const std::string a = json_in::string(*about, ap, type + " about");
    if (a == "second_order") out.about = Equilibrium::SecondOrder;
    else if (a != "linear_static")
      throw InputError(ap, type + ": unknown about '" + a + "' (expected linear_static or second_order)");
    if (!loaded) throw InputError(ap, type + ": \"about\" names the equilibrium of a load case: give \"load_case\"");
  }
  if (const nlohmann::json* g = json_in::field(spec, "geometric_stiffness")) {
    const json_in::Pointer gp = json_in::child(p, "geometric_stiffness");
    out.geometric_stiffness = json_in::geometric_stiffness_kind(*g, gp, type + " geometric_stiffness", type);
    if (!loaded)
      throw InputError(gp, type + ": \"geometric_stiffness\" is that of a load case's axial forces: give \"load_case\"");
  }
  return out;
}

AnalysisOutcome run_iterated_static(const AnalysisContext& ctx, const std::string& type, const std::string& load_case,
                                    int stations, const SecondOrderOptions& options) {
  const Model& model = ctx.model;
  auto r = std::make_shared<SecondOrderResult>(solve_second_order(model, model.loads_for(load_case), options));
  AnalysisOutcome out;
  out.result = object_with_capacity(22);
  ObjectFiller res(out.result, 22);
  set_string(res.slot("type"), type);
  if (!load_case.empty()) set_string(res.slot("load_case"), load_case);
  const bool ok = r->status == SecondOrderStatus::Converged;
  // A failure that left a solution to show: the linear step (diverged, or not converged).
  const bool kept_linear = r->status == SecondOrderStatus::Diverged || r->status == SecondOrderStatus::NotConverged;
  set_string(res.slot("status"), ok ? result_status(SolveStatus::Succeeded)
                                 : r->status == SecondOrderStatus::Mechanism ? result_status(SolveStatus::Mechanism)
                                                                             : result_status(SolveStatus::Failed));
  set_string(res.slot("message"), r->message);
  out.message = r->message;
  out.termination = termination_of(r->status);
  res.slot("free_dofs") = r->solution.free_dofs;
  res.slot("factorizations") = r->factorizations;
  if (options.geometric) {
    set_string(res.slot("geometric_stiffness"), options.kind == GeometricStiffness::Full ? "full" : "axial");
    res.slot("iterations") = r->iterations;
    res.slot("amplification") = r->amplification;
  }
  std::vector<std::string> inactive;
  for (const int m : r->inactive_members) inactive.push_back(model.members[m].id);
  set_strings(res.slot("inactive_members"), inactive);
  if (r->status == SecondOrderStatus::Diverged && std::isfinite(r->critical_load_factor))
    res.slot("critical_load_factor") = r->critical_load_factor;
  if (r->status == SecondOrderStatus::Mechanism) res.slot("mechanism") = mechanism_json(model, r->solution.modes);
  if (ok || kept_linear) {
    // The parts share the result: the solution, or the linear step after a failure.
    std::shared_ptr<const LinearStaticResult> held(r, ok ? &r->solution : &r->linear);
    std::vector<Station> station_storage;
    std::vector<double> position_storage;
    set_static_solution(res, ctx, held, stations, station_storage, position_storage);
  }
  res.finish();
  return out;
}

AnalysisType second_order_analysis() {
  return register_analysis<SecondOrderSpec>("second_order", check_second_order, run_second_order,
                                            [](const std::string& id) { return AnalysisFiles{{id + ".vtu"}, {}}; });
}

}  // namespace beamfea
