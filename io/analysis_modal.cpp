// Analysis "modal": natural frequencies and mode shapes (solvers/modal.hpp).
//   {"id": "m", "type": "modal", "modes": 10, "mass": "consistent" | "lumped", "load_case": ...,
//    "about": "linear_static" | "second_order", "geometric_stiffness": "full" | "axial"}
// Result analyses.<id>: type, status, message, free_dofs, solver (io/eigen_solver_report.hpp), mass, load_case, about, geometric_stiffness, frequencies (Hz,
// ascending), eigenvalues (omega^2), kinds, total_mass {ux..rz}, effective_mass {ux..rz: one per
// mode}, effective_mass_sum {ux..rz}, modes[] {mode, frequency, kind, participation[6],
// effective_mass[6], nodes.<id>.displacement (6, mass-normalised)}, vtk, vtk_scale; files
// DIR/<id>_mode<k>.vtu and DIR/<id>.pvd (time = mode number).
#include "core/errors.hpp"
#include "io/analysis.hpp"
#include "io/eigen_solver_report.hpp"
#include "io/json_util.hpp"
#include "io/load_reader.hpp"
#include "io/mode_shapes_vtk.hpp"
#include "io/result_status.hpp"
#include "io/static_results.hpp"
#include "solvers/modal.hpp"

namespace beamfea {

namespace {

constexpr const char* kDirections[6] = {"ux", "uy", "uz", "rx", "ry", "rz"};

struct ModalSpec {
  ModalOptions options;   // preload: with a load case
  std::string load_case;  // "": no preload; otherwise about the linear static state of this case
};

ModalSpec check_modal(const Model& model, const nlohmann::json& spec, const json_in::Pointer& p) {
  ModalSpec s;
  s.load_case = read_load_case(model, spec, p);
  s.options.preload = !s.load_case.empty();
  json_in::expect_keys(spec, p,
                       {"id", "type", "description", "modes", "mass", "load_case", "about", "geometric_stiffness"});
  s.options.about_state = read_preload(spec, p, "modal", s.options.preload);
  if (s.options.about_state.about == Equilibrium::SecondOrder) check_nonlinear_model(model, p);
  if (const nlohmann::json* modes = json_in::field(spec, "modes")) {
    const json_in::Pointer mp = json_in::child(p, "modes");
    s.options.modes = json_in::integer_in(*modes, mp, "modal modes", 1, kMaxModes);
    const int n = modal_dof_count(model);
    if (s.options.modes > n)
      throw InputError(mp, "modal: " + std::to_string(s.options.modes) + " modes asked for, but the model has only " +
                               std::to_string(n) + " free DOFs");
  }
  if (const nlohmann::json* mass = json_in::field(spec, "mass"))
    s.options.mass = json_in::mass_kind(*mass, json_in::child(p, "mass"), "modal mass", "modal");
  return s;
}

ojson per_direction(const Eigen::VectorXd& v) {
  ojson o = ojson::object();
  for (int d = 0; d < 6; ++d) o[kDirections[d]] = v[d];
  return o;
}

AnalysisOutcome run_modal(const AnalysisContext& ctx, const ModalSpec& spec) {
  const Model& model = ctx.model;
  const ModalOptions& opt = spec.options;
  const ModalResult r = solve_modal(model, model.loads_for(spec.load_case), opt);
  AnalysisOutcome out;
  // Room for every key (19 with run_document's wall_time_s): an ordered_json object that grows
  // deep copies what it holds.
  out.result = object_with_capacity(19);
  out.result["type"] = "modal";
  out.result["status"] = result_status(r.status);
  out.result["message"] = r.message;
  out.result["free_dofs"] = r.free_dofs;
  out.result["mass"] = opt.mass == MassKind::Lumped ? "lumped" : "consistent";
  if (!spec.load_case.empty()) {
    out.result["load_case"] = spec.load_case;
    out.result["about"] = opt.about_state.about == Equilibrium::SecondOrder ? "second_order" : "linear_static";
    out.result["geometric_stiffness"] = opt.about_state.geometric_stiffness == GeometricStiffness::Full ? "full" : "axial";
  }
  out.result["solver"] = eigen_solver_json(r.solver);
  out.message = r.message;
  if (r.status != ModalStatus::Succeeded) {
    out.termination = r.status == ModalStatus::MasslessMechanism ? AnalysisTermination::Mechanism
                      : r.status == ModalStatus::Failed          ? AnalysisTermination::NotConverged
                                                                 : AnalysisTermination::Failed;
    out.result["frequencies"] = ojson::array();
    return out;
  }
  const Eigen::Index count = r.frequencies.size();
  out.result["frequencies"] = to_json(r.frequencies);
  out.result["eigenvalues"] = to_json(r.eigenvalues);
  ojson kinds = ojson::array();
  for (ModeKind k : r.kinds) kinds.push_back(to_string(k));
  out.result["kinds"] = std::move(kinds);
  out.result["total_mass"] = per_direction(r.total_mass);
  ojson eff = ojson::object(), eff_sum = ojson::object();
  for (int d = 0; d < 6; ++d) {
    eff[kDirections[d]] = to_json(Eigen::VectorXd(r.effective_mass.col(d)));
    eff_sum[kDirections[d]] = r.effective_mass.col(d).sum();
  }
  out.result["effective_mass"] = std::move(eff);
  out.result["effective_mass_sum"] = std::move(eff_sum);
  ojson modes = ojson::array();
  for (Eigen::Index k = 0; k < count; ++k) {
    ojson mode = object_with_capacity(6);
    append_new_key(mode, "mode", k + 1);
    append_new_key(mode, "frequency", r.frequencies[k]);
    append_new_key(mode, "kind", to_string(r.kinds[static_cast<std::size_t>(k)]));
    append_new_key(mode, "participation", to_json(Vec6(r.participation.row(k).transpose())));
    append_new_key(mode, "effective_mass", to_json(Vec6(r.effective_mass.row(k).transpose())));
    append_new_key(mode, "nodes", mode_nodes_json(model, r.modes[static_cast<std::size_t>(k)]));
    modes.push_back(std::move(mode));
  }
  out.result["modes"] = std::move(modes);
  if (!ctx.out_dir.empty() && ctx.write_vtk) {
    const double scale = write_mode_shapes(model, ctx.out_dir, ctx.id, r.modes, "frequency", r.frequencies);
    out.result["vtk"] = ctx.id + ".pvd";
    out.result["vtk_scale"] = scale;
  }
  return out;
}

}  // namespace

AnalysisType modal_analysis() {
  return register_analysis<ModalSpec>("modal", check_modal, run_modal,
                                      [](const std::string& id) { return AnalysisFiles{{id + ".pvd"}, {id + "_mode"}}; });
}

}  // namespace beamfea
