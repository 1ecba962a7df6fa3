// DofMap, part 3: the forces its constraints carry at an equilibrium (reactions at prescribed
// values, joint forces, loop multipliers), and the check that prescribed values agree with the
// redundant rows.
#include <Eigen/QR>
#include <cmath>
#include <map>

#include "core/dof_map.hpp"

namespace beamfea {

std::string DofMap::check_consistency(const Eigen::VectorXd& u_prescribed) const {
  for (std::size_t ri = 0; ri < redundant_.size(); ++ri) {
    const auto& r = redundant_[ri];
    double s = 0.0, mag = 0.0;
    for (const auto& t : r) {
      s += t.coef * u_prescribed[t.ind];
      mag += std::abs(t.coef * u_prescribed[t.ind]);
    }
    if (std::abs(s) > 1e-9 * mag + 1e-300 && std::abs(s) > 0.0) {
      std::string names;
      for (const auto& t : r) names += (names.empty() ? "" : ", ") + model_->describe(prescribed_[t.ind].dof);
      return redundant_what_[ri] + ": the constraints cannot be satisfied (a loop that cannot close, or supports "
             "or prescribed values on one rigid body that disagree): " + names;
    }
  }
  return "";
}

DofMap::ConstraintForces DofMap::constraint_forces(const Eigen::VectorXd& r_raw) const {
  ConstraintForces out;
  ConstraintForceScratch scratch;
  constraint_forces(r_raw, out, scratch);
  return out;
}

void DofMap::constraint_forces(const Eigen::VectorXd& r_raw, ConstraintForces& out, ConstraintForceScratch& scratch) const {
  std::vector<Vec6>& acc = scratch.node;
  Eigen::VectorXd& r_ind = scratch.r_ind;
  r_ind.noalias() = Tind_.transpose() * r_raw;
  const int m = static_cast<int>(extra_.size());

  // Multipliers of the extra constraints: sum_k lambda_k C_k = r_ind on the unprescribed DOFs.
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(m);
  if (m > 0) {
    std::map<int, int> rows;  // ind -> equation
    for (const auto& row : extra_ind_)
      for (const auto& [k, v] : row)
        if (ind_prescribed_[k] < 0 && !rows.count(k)) rows.emplace(k, static_cast<int>(rows.size()));
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(rows.size()), m);
    Eigen::VectorXd b(static_cast<Eigen::Index>(rows.size()));
    for (const auto& [k, i] : rows) b[i] = r_ind[k];
    for (int c = 0; c < m; ++c)
      for (const auto& [k, v] : extra_ind_[c])
        if (auto it = rows.find(k); it != rows.end()) A(it->second, c) += v;
    if (A.rows() > 0) lambda = A.completeOrthogonalDecomposition().solve(b);
  }

  out.prescribed.assign(prescribed_.size(), 0.0);
  for (int i = 0; i < n_ind_; ++i) {
    const int p = ind_prescribed_[i];
    if (p < 0) continue;
    double v = r_ind[i];
    for (int c = 0; c < m; ++c)
      if (auto it = extra_ind_[c].find(i); it != extra_ind_[c].end()) v -= lambda[c] * it->second;
    out.prescribed[p] = v;
  }
  for (int c = 0; c < m; ++c)
    if (extra_[c].prescribed >= 0) out.prescribed[extra_[c].prescribed] = lambda[c];

  // Forces carried by the tree edges: accumulate the residual from the leaves to the roots.
  Eigen::VectorXd& r = scratch.r;
  r = r_raw;
  for (int c = 0; c < m; ++c)
    for (const auto& t : extra_[c].raw) r[t.ind] -= lambda[c] * t.coef;
  acc.resize(n_nodes_);
  for (int n = 0; n < n_nodes_; ++n) acc[n] = r.segment<6>(6 * n);
  out.joint.assign(model_->joints.size(), Vec6::Zero());
  for (auto it = tree_order_.rbegin(); it != tree_order_.rend(); ++it) {
    const auto& e = tree_edges_[*it];
    const Vec6& a = acc[e.child];
    if (e.kind == ConstraintEdge::Kind::Joint) out.joint[e.index] = e.forward ? a : Vec6(-a);
    acc[e.parent].head<3>() += a.head<3>();
    acc[e.parent].tail<3>() += a.tail<3>() + (x_[e.child] - x_[e.parent]).cross(a.head<3>());
  }
  out.loop.assign(loop_edges_.size(), Vec6::Zero());
  out.support_local.assign(model_->supports.size(), Vec6::Zero());
  out.tie.assign(model_->ties.size(), Vec6::Zero());
  out.constraint.assign(model_->constraints.size(), 0.0);
  out.user_raw.setZero(n_raw_);
  for (int c = 0; c < m; ++c) {
    const ExtraRow& x = extra_[c];
    if (x.joint >= 0) out.joint[x.joint][x.joint_row] = lambda[c];
    if (x.loop >= 0) out.loop[x.loop][x.joint_row] = lambda[c];
    if (x.support >= 0) out.support_local[x.support][x.comp] = lambda[c];
    if (x.tie >= 0) out.tie[x.tie][x.comp] = lambda[c];
    if (x.constraint >= 0) out.constraint[x.constraint] = lambda[c];
    if (is_user_row(x))
      for (const auto& t : x.raw) out.user_raw[t.ind] += lambda[c] * t.coef;
  }
}

}  // namespace beamfea
