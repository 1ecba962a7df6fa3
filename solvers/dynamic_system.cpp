#include "solvers/dynamic_system.hpp"

#include <utility>
#include <vector>

#include "core/assembly.hpp"
#include "solvers/mass_matrix.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

SparseMatrix joint_damping(const Model& model, const DofMap& map) {
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t j = 0; j < model.joints.size(); ++j) {
    const Joint& joint = model.joints[j];
    for (std::size_t c = 0; c < joint.damping.size(); ++c)
      if (joint.damping[c] > 0.0) {
        const int raw = map.raw_joint(static_cast<int>(j), static_cast<int>(c));
        t.emplace_back(raw, raw, joint.damping[c]);
      }
  }
  SparseMatrix C_raw(map.raw_size(), map.raw_size());
  C_raw.setFromTriplets(t.begin(), t.end());
  const SparseMatrix Tf = map.T_free();
  return SparseMatrix(Tf.transpose() * C_raw * Tf);
}

Eigen::VectorXd unit_free_force(const DofMap& map, int raw) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(map.free_size());
  for (SparseRowMatrix::InnerIterator it(map.T_free(), raw); it; ++it) f[it.col()] += it.value();
  return f;
}

bool raw_dof_moves(const DofMap& map, int raw) {
  for (SparseRowMatrix::InnerIterator it(map.T_free(), raw); it; ++it)
    if (it.value() != 0.0) return true;
  return false;
}

DynamicSystem dynamic_system(const Model& model, const DofMap& map, const LoadSet& preload,
                             const DynamicSystemOptions& options) {
  DynamicSystem sys;
  if (map.free_size() == 0) {
    sys.message = "no free DOFs";
    return sys;
  }
  const LinearStructure structure(model);
  SystemAssembler ka(map), ma(map);
  structure.assemble_stiffness(map, ka);
  ma.begin();
  assemble_mass(structure, map, options.mass, ma);
  ma.end();
  sys.K = ka.K_ff();
  sys.M = ma.K_ff();
  if (!(sys.M.nonZeros() > 0 && sys.M.diagonal().cwiseAbs().maxCoeff() > 0.0)) {
    sys.status = DynamicSystemStatus::NoMass;
    sys.message = "the model has no mass (give the materials a density or add point masses)";
    return sys;
  }
  if (options.preload) {
    std::optional<SparseMatrix> Kt = loaded_tangent(model, map, structure, sys.K, preload, options.about_state, sys.message);
    if (!Kt) {
      sys.status = DynamicSystemStatus::PreloadFailed;
      return sys;
    }
    sys.K = std::move(*Kt);
  }
  sys.C = joint_damping(model, map);
  const Damping& d = model.damping;
  if (d.kind == Damping::Kind::Rayleigh) {
    if (d.alpha > 0.0) sys.C += d.alpha * sys.M;
    if (d.beta > 0.0) sys.C += d.beta * sys.K;
  }
  sys.C.prune(0.0);
  sys.has_damping_matrix = sys.C.nonZeros() > 0;
  sys.status = DynamicSystemStatus::Succeeded;
  return sys;
}

}  // namespace beamfea
