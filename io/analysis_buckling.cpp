// Analysis "buckling": linearised buckling load factors and modes (solvers/buckling.hpp).
//   {"id": "b", "type": "buckling", "modes": 4, "load_case": ..., "geometric_stiffness": "full" | "axial"}
// Result analyses.<id>: type, load_case, geometric_stiffness, status, message, free_dofs, solver
// (io/eigen_solver_report.hpp), load_factors (ascending),
// modes[] {mode, load_factor, nodes.<id>.displacement (6, normalised: largest translation 1)},
// vtk (the .pvd) and files DIR/<id>_mode<k>.vtu, DIR/<id>.pvd (time = mode number).

#include "core/errors.hpp"
#include "io/analysis.hpp"
#include "io/eigen_solver_report.hpp"
#include "io/mode_shapes_vtk.hpp"
#include "io/json_util.hpp"
#include "io/load_reader.hpp"
#include "io/result_status.hpp"
#include "solvers/buckling.hpp"

namespace beamfea {

namespace {

struct BucklingSpec {
  BucklingOptions options;
  std::string load_case;  // "": the default loads
};

BucklingSpec check_buckling(const Model& model, const nlohmann::json& spec, const json_in::Pointer& p) {
  BucklingSpec s;
  s.load_case = read_load_case(model, spec, p);
  json_in::expect_keys(spec, p, {"id", "type", "description", "modes", "load_case", "geometric_stiffness"});
  if (const nlohmann::json* g = json_in::field(spec, "geometric_stiffness"))
    s.options.geometric_stiffness = json_in::geometric_stiffness_kind(*g, json_in::child(p, "geometric_stiffness"),
                                                                      "buckling geometric_stiffness", "buckling");
  if (const nlohmann::json* modes = json_in::field(spec, "modes"))
    s.options.modes = json_in::integer_in(*modes, json_in::child(p, "modes"), "buckling modes", 1, kMaxModes);
  check_nonlinear_model(model, p);
  return s;
}

AnalysisOutcome run_buckling(const AnalysisContext& ctx, const BucklingSpec& spec) {
  const Model& model = ctx.model;
  // The reference load: the analysis's load case, or the default loads.
  const BucklingResult r = solve_buckling(model, model.loads_for(spec.load_case), spec.options);
  AnalysisOutcome out;
  // Room for every key (type, load_case, geometric_stiffness, status, message, free_dofs, solver, load_factors, modes,
  // vtk, vtk_scale, wall_time_s): an ordered_json object that grows deep copies what it holds.
  out.result = object_with_capacity(12);
  out.result["type"] = "buckling";
  if (!spec.load_case.empty()) out.result["load_case"] = spec.load_case;
  out.result["geometric_stiffness"] = spec.options.geometric_stiffness == GeometricStiffness::Full ? "full" : "axial";
  out.result["status"] = result_status(r.status);
  out.result["message"] = r.message;
  out.result["free_dofs"] = r.free_dofs;
  out.result["solver"] = eigen_solver_json(r.solver);
  out.message = r.message;
  if (r.status != BucklingStatus::Succeeded) {
    if (r.status == BucklingStatus::Mechanism) out.termination = AnalysisTermination::Mechanism;
    else if (r.status == BucklingStatus::NotConverged) out.termination = AnalysisTermination::NotConverged;
    else if (r.status != BucklingStatus::NoCompression) out.termination = AnalysisTermination::Failed;
    out.result["load_factors"] = ojson::array();
    return out;
  }
  out.result["load_factors"] = to_json(r.load_factors);
  ojson modes = ojson::array();
  for (std::size_t k = 0; k < r.modes.size(); ++k) {
    ojson mode = object_with_capacity(3);
    append_new_key(mode, "mode", k + 1);
    append_new_key(mode, "load_factor", r.load_factors[static_cast<Eigen::Index>(k)]);
    append_new_key(mode, "nodes", mode_nodes_json(model, r.modes[k]));
    modes.push_back(std::move(mode));
  }
  out.result["modes"] = std::move(modes);
  if (!ctx.out_dir.empty() && ctx.write_vtk) {
    // Modes are normalised already (largest translation 1): the writer draws them at 10 % of the
    // model size, load factors as field data.
    const double scale = write_mode_shapes(model, ctx.out_dir, ctx.id, r.modes, "load_factor", r.load_factors);
    out.result["vtk"] = ctx.id + ".pvd";
    out.result["vtk_scale"] = scale;
  }
  return out;
}

}  // namespace

AnalysisType buckling_analysis() {
  return register_analysis<BucklingSpec>("buckling", check_buckling, run_buckling,
                                         [](const std::string& id) { return AnalysisFiles{{id + ".pvd"}, {id + "_mode"}}; });
}

}  // namespace beamfea
