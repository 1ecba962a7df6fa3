#include "solvers/linear_static.hpp"

#include <fmt/format.h>

#include "core/assembly.hpp"
#include "core/errors.hpp"
#include "solvers/sparse_factor.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

const char* to_string(SolveStatus s) {
  switch (s) {
    case SolveStatus::Converged: return "converged";
    case SolveStatus::Mechanism: return "mechanism";
    case SolveStatus::Failed: return "failed";
  }
  return "?";
}

void LinearStaticOptions::validate() const {
  if (!(singular_rcond > 0.0 && singular_rcond < 1.0)) throw Error("LinearStaticOptions: singular_rcond must be in (0, 1)");
  if (!(zero_energy_tolerance > 0.0)) throw Error("LinearStaticOptions: zero_energy_tolerance must be positive");
}

LinearStaticResult solve_linear_static(const Model& model, const LinearStaticOptions& options) {
  options.validate();
  LinearStaticResult res;
  const DofMap map(model);
  const Eigen::VectorXd up = map.prescribed_values();
  if (auto conflict = map.check_consistency(up); !conflict.empty()) throw ModelError("supports and prescribed values", conflict);
  const LinearStructure structure(model);
  SystemAssembler assembler(map);
  assembler.begin();
  structure.assemble(map, assembler);
  assembler.end();
  const SparseMatrix& K = assembler.K_ff();
  res.free_dofs = map.free_size();

  const Eigen::VectorXd f_raw = external_force(model, map);
  Eigen::VectorXd f = map.reduce(f_raw);
  if (map.prescribed_size() > 0) f -= assembler.K_fp() * up;

  SparseFactor factor;
  FactorOptions fo;
  fo.singular_rcond = options.singular_rcond;
  const FactorStatus fs = factor.factorize(K, fo);
  if (fs == FactorStatus::TooLarge) {
    res.status = SolveStatus::Failed;
    res.message = fmt::format("the factorisation of {} free DOFs is too large for CHOLMOD's symbolic analysis "
                              "(factor over 2^31 entries or out of memory)", map.free_size());
    return res;
  }
  if (fs != FactorStatus::Ok) {
    res.modes = zero_energy_modes(model, map, K, 12, options.zero_energy_tolerance);
    if (!res.modes.empty()) {
      res.status = SolveStatus::Mechanism;
      res.message = describe_mechanism(res.modes);
      return res;
    }
    if (fs == FactorStatus::Singular || !factor.usable()) {
      res.status = SolveStatus::Failed;
      res.message = "the stiffness matrix could not be factorised";
      return res;
    }
    // Ill-conditioned but without a zero-energy mode: the factorisation stands.
  }
  const Eigen::VectorXd uf = factor.solve(f);
  res.u = map.expand(uf, up);

  const Eigen::VectorXd r = structure.internal_force(map, res.u) - f_raw;
  const auto cf = map.constraint_forces(r);
  res.reactions.assign(model.nodes.size(), Vec6::Zero());
  res.supported.assign(model.nodes.size(), 0);
  for (int p = 0; p < map.prescribed_size(); ++p) {
    const auto& d = map.prescribed()[p].dof;
    if (d.owner != DofRef::Owner::Node) continue;
    res.reactions[d.index][d.comp] = cf.prescribed[p];
    res.supported[d.index] = 1;
  }
  res.joint_forces = cf.joint;
  res.statically_indeterminate = map.redundant_constraints();
  res.end_forces.resize(model.elements.size());
  for (std::size_t e = 0; e < model.elements.size(); ++e)
    res.end_forces[e] = structure.end_forces(map, static_cast<int>(e), res.u);
  res.status = SolveStatus::Converged;
  res.message = fmt::format("linear static: {} free DOFs, max |u| = {:.6g}", map.free_size(),
                            res.u.size() ? res.u.cwiseAbs().maxCoeff() : 0.0);
  return res;
}

}  // namespace beamfea
