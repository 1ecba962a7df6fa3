#include "solvers/actuator_load_case.hpp"

#include <functional>

#include "core/assembly.hpp"
#include "core/dof_map.hpp"
#include "core/errors.hpp"
#include "solvers/initial_stress.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/member_loading.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

LoadSet nodal_equivalent(const Model& model, const LoadSet& loads) {
  const DofMap map(model);
  LoadSet without_joint_loads = loads;
  without_joint_loads.joint.clear();
  const Eigen::VectorXd f = external_force(model, map, without_joint_loads);
  LoadSet out;
  out.joint = loads.joint;
  for (int n = 0; n < static_cast<int>(model.nodes.size()); ++n) {
    const Vec3 force = f.segment<3>(map.raw_node(n, 0)), moment = f.segment<3>(map.raw_node(n, 3));
    if (force.isZero(0.0) && moment.isZero(0.0)) continue;
    out.nodal.push_back({n, force, moment});
  }
  return out;
}

namespace {

// What the frozen model's solution adds (the efforts): called with its map, structure and solution.
using SolutionVisitor = std::function<void(const Model&, const DofMap&, const LinearStructure&, const LinearStaticResult&)>;

// The model's default loads (the case): linear solution, platform displacement, loaded stiffness.
LoadedSchemeModel solve_loaded(const Model& m, const AllocationOptions& o, const SolutionVisitor& visit = {}) {
  LoadedSchemeModel out;
  const LinearStaticResult lin = solve_linear_static(m);
  if (lin.status != SolveStatus::Succeeded) {
    out.message = lin.message;
    out.stiffness_message = "no linear solution of the case";
    return out;
  }
  out.ok = true;
  out.message = lin.message;
  const DofMap map(m);
  for (int k = 0; k < 6; ++k) out.platform[k] = lin.u[map.raw_node(o.platform_node, k)];
  const LinearStructure structure(m);
  if (visit) visit(m, map, structure, lin);
  try {
    SystemAssembler assembler(map);
    assembler.begin();
    structure.assemble(map, assembler);
    assembler.end();
    const SparseMatrix Kg = geometric_stiffness(m, map, structure, lin, m.default_loads());
    // Symmetric part, as the loaded mode of `stiffness` (the skew part of applied moments dropped).
    const SparseMatrix Kt = assembler.K_ff() + SparseMatrix(0.5 * (Kg + SparseMatrix(Kg.transpose())));
    const DirectionalStiffness ds = condense_to_directions(m, map, Kt, o.platform_node, o.directions);
    out.stiffness_ok = ds.ok;
    out.stiffness_message = ds.ok ? "K + K_g of the case, condensed to the directions" : ds.message;
    if (ds.ok) out.K_loaded = ds.K;
  } catch (const Error& e) {
    out.stiffness_message = std::string("no loaded stiffness: ") + e.what();
  }
  return out;
}

}  // namespace

SchemeLoadResponse scheme_load_response(const Model& model, const AllocationOptions& o, const std::vector<int>& actuated,
                                        const LoadSet& loads) {
  o.validate(model);
  SchemeLoadResponse r;
  const int na = static_cast<int>(actuated.size());
  r.efforts = Eigen::VectorXd::Zero(na);

  // Frozen structure: the efforts are the frozen coordinates' reactions.
  const Model frozen = scheme_model(model, o, actuated, SchemeLinks::Flexible, SchemeActuators::Frozen, loads);
  r.structural = solve_loaded(frozen, o, [&](const Model& m, const DofMap& map, const LinearStructure& structure,
                                             const LinearStaticResult& lin) {
    const Eigen::VectorXd res = structure.internal_force(map, lin.u) - external_force(m, map, m.default_loads());
    const auto cf = map.constraint_forces(res);
    for (int k = 0; k < na; ++k) {
      const auto& c = o.candidates[actuated[k]];
      const int p = map.prescribed_index(map.raw_joint(c.joint, c.coordinate));
      if (p < 0) {
        r.efforts_message = "joint '" + m.joints[c.joint].id + "' coordinate " + std::to_string(c.coordinate) +
                            " is not an independent coordinate of the frozen structure: no reaction";
        return;
      }
      r.efforts[k] = cf.prescribed[p];
    }
    r.efforts_ok = true;
    r.efforts_message = "reactions of the frozen actuators";
  });
  if (!r.structural.ok) r.efforts_message = "with the actuators frozen: " + r.structural.message;

  const Model total = scheme_model(model, o, actuated, SchemeLinks::Flexible, SchemeActuators::Springs, loads);
  r.total = solve_loaded(total, o);
  const Model rigid =
      scheme_model(model, o, actuated, SchemeLinks::Rigid, SchemeActuators::Springs, nodal_equivalent(model, loads));
  r.actuated = solve_loaded(rigid, o);
  return r;
}

}  // namespace beamfea
