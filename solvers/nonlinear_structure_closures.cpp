// Closures of loops of rigid links and joints as nonlinear equality constraints with multipliers
// (the equations are in solvers/nonlinear_structure.hpp, "Closed loops").
#include <Eigen/QR>
#include <algorithm>
#include <map>

#include "core/errors.hpp"
#include "solvers/nonlinear_structure.hpp"

namespace beamfea {

void NonlinearStructure::build_closures() {
  loop_joint_.assign(model_->joints.size(), 0);
  for (const auto& e : map_.loop_edges()) {
    Closure c;
    c.edge = e;
    c.chain = chain_[e.parent];
    if (e.kind == ConstraintEdge::Kind::Joint) {
      loop_joint_[e.index] = 1;
      for (int k = 0; k < model_->joints[e.index].coordinates(); ++k)
        c.chain.push_back(raw_to_gen_[map_.raw_joint(e.index, k)]);
    }
    closures_.push_back(std::move(c));
  }
}

std::string NonlinearStructure::describe_closure_row(int row) const {
  const auto& e = closures_[row / 6].edge;
  const std::string what = e.kind == ConstraintEdge::Kind::Rigid ? "element '" + model_->elements[e.index].id + "'"
                                                                 : "joint '" + model_->joints[e.index].id + "'";
  return what + " " + kDofNames[row % 6];
}

std::pair<Vec3, Mat3> NonlinearStructure::closure_body(const NonlinearState& s, int k) const {
  const auto& e = closures_[k].edge;
  const int a = e.parent, b = e.child;
  if (e.kind == ConstraintEdge::Kind::Rigid)
    return {s.x[a] + s.R[a] * (model_->nodes[b].x - model_->nodes[a].x), s.R[a]};
  const Joint& j = model_->joints[e.index];
  const Mat3 P = j.type == JointType::Spherical ? s.Q[e.index] : joint_product(j, s.q[e.index]);
  return {s.x[a] + s.R[a] * joint_offset(j, s.q[e.index]), s.R[a] * P};
}

Eigen::VectorXd NonlinearStructure::closure_values(const NonlinearState& s) const {
  Eigen::VectorXd c(closure_rows());
  for (int k = 0; k < static_cast<int>(closures_.size()); ++k) {
    const int b = closures_[k].edge.child;
    const auto [y, S] = closure_body(s, k);
    c.segment<3>(6 * k) = s.x[b] - y;
    c.segment<3>(6 * k + 3) = log_so3(s.R[b] * S.transpose());
  }
  return c;
}

namespace {

// Rows 6k..6k+5 over gens: the translation of a point x and the spin of its body, per gen of chain,
// times `sign`, accumulated into dense rows (few gens per closure).
void add_point_rows(const std::vector<int>& chain, const std::vector<Twist>& tw, const Vec3& x, double sign,
                    Eigen::Matrix<double, 3, Eigen::Dynamic>& trans, Eigen::Matrix<double, 3, Eigen::Dynamic>& spin,
                    std::map<int, int>& col, std::vector<int>& gens) {
  for (int g : chain) {
    auto [it, fresh] = col.try_emplace(g, static_cast<int>(gens.size()));
    if (fresh) {
      gens.push_back(g);
      trans.conservativeResize(3, static_cast<Eigen::Index>(gens.size()));
      spin.conservativeResize(3, static_cast<Eigen::Index>(gens.size()));
      trans.col(it->second).setZero();
      spin.col(it->second).setZero();
    }
    trans.col(it->second) += sign * (tw[g].v + tw[g].w.cross(x));
    spin.col(it->second) += sign * tw[g].w;
  }
}

}  // namespace

// Both the exact gradient (exact = true) and the force rows B (exact = false) differ only in the
// rotation rows: T_s(c_r)^-1 (w_b - M w_S) against w_b - w_S.
static SparseMatrix closure_rows_impl(const NonlinearStructure& ns, const NonlinearState& s,
                                      const std::vector<Twist>& tw, bool exact) {
  std::vector<Eigen::Triplet<double>> t;
  const auto& cl = ns.closures();
  for (int k = 0; k < static_cast<int>(cl.size()); ++k) {
    const int b = cl[k].edge.child;
    const auto [y, S] = ns.closure_body(s, k);
    Eigen::Matrix<double, 3, Eigen::Dynamic> tb(3, 0), sb(3, 0), ts(3, 0), ss(3, 0);
    std::map<int, int> colb, cols;
    std::vector<int> gb, gs;
    add_point_rows(ns.chain(b), tw, s.x[b], 1.0, tb, sb, colb, gb);
    add_point_rows(cl[k].chain, tw, y, 1.0, ts, ss, cols, gs);
    Mat3 A = Mat3::Identity(), Mb = Mat3::Identity();
    if (exact) {
      const Mat3 M = s.R[b] * S.transpose();
      A = tangent_so3_inverse(log_so3(M));
      Mb = M;
    }
    for (std::size_t c = 0; c < gb.size(); ++c) {
      const Vec3 r = A * sb.col(static_cast<Eigen::Index>(c));
      for (int i = 0; i < 3; ++i) {
        t.emplace_back(6 * k + i, gb[c], tb(i, static_cast<Eigen::Index>(c)));
        t.emplace_back(6 * k + 3 + i, gb[c], r[i]);
      }
    }
    for (std::size_t c = 0; c < gs.size(); ++c) {
      const Vec3 r = A * Mb * ss.col(static_cast<Eigen::Index>(c));
      for (int i = 0; i < 3; ++i) {
        t.emplace_back(6 * k + i, gs[c], -ts(i, static_cast<Eigen::Index>(c)));
        t.emplace_back(6 * k + 3 + i, gs[c], -r[i]);
      }
    }
  }
  SparseMatrix C(ns.closure_rows(), ns.size());
  C.setFromTriplets(t.begin(), t.end());
  return C;
}

SparseMatrix NonlinearStructure::closure_jacobian(const NonlinearState& s, const std::vector<Twist>& tw) const {
  return closure_rows_impl(*this, s, tw, true);
}

SparseMatrix NonlinearStructure::closure_force_rows(const NonlinearState& s, const std::vector<Twist>& tw) const {
  return closure_rows_impl(*this, s, tw, false);
}

SparseMatrix NonlinearStructure::closure_curvature(const NonlinearState& s, const std::vector<Twist>& tw,
                                                   const Eigen::VectorXd& mu) const {
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < static_cast<int>(closures_.size()); ++k) {
    const Vec3 F = mu.segment<3>(6 * k), M = mu.segment<3>(6 * k + 3);
    const int b = closures_[k].edge.child;
    add_point_curvature(s.x[b], F, M, chain_[b], tw, t);
    add_point_curvature(closure_body(s, k).first, -F, -M, closures_[k].chain, tw, t);
  }
  SparseMatrix G(size(), size());
  G.setFromTriplets(t.begin(), t.end());
  return G;
}

RowSelection independent_rows(const Eigen::MatrixXd& C, double tolerance) {
  RowSelection out;
  const int m = static_cast<int>(C.rows());
  if (m == 0) return out;
  const double scale = C.cwiseAbs().maxCoeff();
  if (!(scale > 0.0)) {
    for (int i = 0; i < m; ++i) out.redundant.push_back(i);
    return out;
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(C.transpose() / scale);
  const Eigen::MatrixXd R = qr.matrixQR().triangularView<Eigen::Upper>();
  const int d = static_cast<int>(std::min(R.rows(), R.cols()));
  const double top = d > 0 ? std::abs(R(0, 0)) : 0.0;
  std::vector<char> keep(m, 0);
  for (int k = 0; k < d; ++k)
    if (std::abs(R(k, k)) > tolerance * top) keep[qr.colsPermutation().indices()[k]] = 1;
  for (int i = 0; i < m; ++i) (keep[i] ? out.kept : out.redundant).push_back(i);
  return out;
}

}  // namespace beamfea
