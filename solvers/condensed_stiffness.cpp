#include "solvers/condensed_stiffness.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/UmfPackSupport>
#include <fmt/format.h>

#include "core/assembly.hpp"
#include "core/errors.hpp"
#include "solvers/buckling.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

void CondensedStiffnessOptions::validate() const {
  if (!(rank_tolerance > 0.0 && rank_tolerance < 1.0)) throw Error("CondensedStiffnessOptions: rank_tolerance must be in (0, 1)");
}

void analyse_rank(const Mat6& K, double L, double tolerance, CondensedStiffness& out) {
  Vec6 s;
  s << 1, 1, 1, 1 / L, 1 / L, 1 / L;
  const Mat6 Ks = s.asDiagonal() * (0.5 * (K + K.transpose())) * s.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Mat6> es(Ks);
  out.eigenvalues = es.eigenvalues();
  const double big = es.eigenvalues().cwiseAbs().maxCoeff();
  out.rank = 0;
  out.null_space.clear();
  for (int i = 0; i < 6; ++i) {
    if (std::abs(es.eigenvalues()[i]) > tolerance * big && big > 0.0) {
      ++out.rank;
    } else {
      Vec6 v = s.asDiagonal() * es.eigenvectors().col(i);
      v.normalize();
      // Make the largest component positive, for reproducible output.
      Eigen::Index k;
      v.cwiseAbs().maxCoeff(&k);
      if (v[k] < 0) v = -v;
      out.null_space.push_back(v);
    }
  }
}

RawCondensation condense_to_raw_dofs(const DofMap& map, const SparseMatrix& K, const std::vector<int>& raw) {
  RawCondensation out;
  const int n = map.free_size();
  const int nd = static_cast<int>(raw.size());
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(K.nonZeros() + 12 * nd);
  for (int j = 0; j < K.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(K, j); it; ++it) t.emplace_back(static_cast<int>(it.row()), j, it.value());
  for (int k = 0; k < nd; ++k) {
    bool any = false;
    for (SparseRowMatrix::InnerIterator it(map.T_free(), raw[k]); it; ++it) {
      if (it.value() == 0.0) continue;
      t.emplace_back(n + k, static_cast<int>(it.col()), it.value());
      t.emplace_back(static_cast<int>(it.col()), n + k, it.value());
      any = true;
    }
    if (!any) {
      out.outcome = RawCondensation::Outcome::HeldDof;
      out.held = k;
      return out;
    }
  }
  SparseMatrix A(n + nd, n + nd);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  Eigen::UmfPackLU<SparseMatrix> lu(A);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n + nd, nd);
  rhs.bottomRows(nd).setIdentity();
  Eigen::MatrixXd X;
  bool ok = lu.info() == Eigen::Success;
  if (ok) {
    X = lu.solve(rhs);
    ok = lu.info() == Eigen::Success && X.allFinite();
    if (ok) {
      // A nearly singular saddle point shows as a residual far above rounding.
      const double res = (A * X - rhs).norm();
      ok = res <= 1e-8 * (Eigen::MatrixXd(A.cwiseAbs() * X.cwiseAbs()).norm() + 1.0);
    }
  }
  if (!ok) return out;
  const Eigen::MatrixXd M = X.bottomRows(nd);
  out.K = -0.5 * (M + M.transpose());
  out.outcome = RawCondensation::Outcome::Ok;
  return out;
}

CondensedStiffness condense_to_node(const Model& model, const DofMap& map, const SparseMatrix& K, int node,
                                    const CondensedStiffnessOptions& options) {
  options.validate();
  CondensedStiffness out;
  std::vector<int> raw(6);
  for (int k = 0; k < 6; ++k) raw[k] = map.raw_node(node, k);
  const RawCondensation c = condense_to_raw_dofs(map, K, raw);
  if (c.outcome == RawCondensation::Outcome::HeldDof)
    throw ModelError("node '" + model.nodes[node].id + "' dof " + kDofNames[c.held],
                     "is supported or prescribed: the stiffness there is unbounded");
  if (c.outcome == RawCondensation::Outcome::Mechanism) {
    out.modes = zero_energy_modes(model, map, K, 12);
    out.message = "holding node '" + model.nodes[node].id + "' still leaves a mechanism; " +
                  describe_mechanism(out.modes);
    return out;
  }
  out.K = c.K;
  analyse_rank(out.K, model.length_scale(), options.rank_tolerance, out);
  out.ok = true;
  out.message = fmt::format("stiffness of node '{}': rank {}", model.nodes[node].id, out.rank);
  return out;
}

CondensedStiffness linear_node_stiffness(const Model& model, int node, const CondensedStiffnessOptions& options) {
  const DofMap map(model);
  const LinearStructure structure(model);
  SystemAssembler assembler(map);
  assembler.begin();
  structure.assemble(map, assembler);
  assembler.end();
  return condense_to_node(model, map, assembler.K_ff(), node, options);
}

CondensedStiffness loaded_node_stiffness(const Model& model, int node, const CondensedStiffnessOptions& options) {
  const LinearStaticResult lin = solve_linear_static(model);
  if (lin.status != SolveStatus::Converged) {
    CondensedStiffness out;
    out.message = "loaded stiffness: the linear static solution of the preload failed: " + lin.message;
    out.modes = lin.modes;
    return out;
  }
  const DofMap map(model);
  const LinearStructure structure(model);
  SystemAssembler assembler(map);
  assembler.begin();
  structure.assemble(map, assembler);
  assembler.end();
  SparseMatrix Kg = geometric_stiffness(model, map, structure, lin);
  // Symmetric part: the skew part from applied moments is dropped, as in buckling.
  const SparseMatrix Kt = assembler.K_ff() + SparseMatrix(0.5 * (Kg + SparseMatrix(Kg.transpose())));
  return condense_to_node(model, map, Kt, node, options);
}

}  // namespace beamfea
