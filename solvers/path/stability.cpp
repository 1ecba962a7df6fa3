#include "solvers/path/stability.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <Eigen/UmfPackSupport>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "solvers/eigen_lowest.hpp"

namespace beamfea {

namespace {
// Pivots below this fraction of the largest constraint coefficient are zero (a dependent row).
constexpr double kNullSpacePivotTolerance = 1e-12;
// Shift of the shift-invert eigen-solver just below a positive definite (Jacobi-scaled, so O(1))
// spectrum: fast convergence to the lowest eigenvalue.
constexpr double kEigenShiftMargin = 1e-6;
// Up to this size the lowest eigenpairs of the stability matrix are computed densely.
constexpr int kDenseEigenLimit = 400;
// Below zero, the shift is this factor times the last lowest eigenvalue (a little below it: the
// eigenvalue nearest the shift is the lowest one while it moves by less than half its value).
constexpr double kNegativeShiftFactor = 1.5;
// The shift when the first negative eigenvalue appears (just past a critical point the lowest
// eigenvalue of the Jacobi-scaled matrix is small).
constexpr double kFirstNegativeShift = 1e-3;
}  // namespace

SparseMatrix null_space(const Eigen::MatrixXd& C0, int n) {
  std::vector<Eigen::Triplet<double>> t;
  if (C0.rows() == 0) {
    SparseMatrix Z(n, n);
    Z.setIdentity();
    return Z;
  }
  Eigen::MatrixXd C = C0;
  std::vector<int> pivot_col;
  std::vector<char> is_pivot(n, 0);
  const double scale = C.cwiseAbs().maxCoeff();
  int r = 0;
  for (; r < C.rows(); ++r) {
    Eigen::Index pr, pc;
    const double best = C.bottomRows(C.rows() - r).cwiseAbs().maxCoeff(&pr, &pc);
    if (!(best > kNullSpacePivotTolerance * scale)) break;
    pr += r;
    C.row(r).swap(C.row(pr));
    C.row(r) /= C(r, pc);
    for (Eigen::Index i = 0; i < C.rows(); ++i)
      if (i != r && C(i, pc) != 0.0) C.row(i) -= C(i, pc) * C.row(r);
    pivot_col.push_back(static_cast<int>(pc));
    is_pivot[pc] = 1;
  }
  int col = 0;
  for (int j = 0; j < n; ++j) {
    if (is_pivot[j]) continue;
    t.emplace_back(j, col, 1.0);
    for (int i = 0; i < r; ++i)
      if (C(i, j) != 0.0) t.emplace_back(pivot_col[i], col, -C(i, j));
    ++col;
  }
  SparseMatrix Z(n, col);
  Z.setFromTriplets(t.begin(), t.end());
  return Z;
}

StabilityAnalysis constrained_tangent(const PathEquilibrium& P, const Converged& c, bool with_control) {
  StabilityAnalysis out;
  StepSpec s;
  s.kind = StepKind::Load;
  s.lambda = c.lambda;
  const PathEquilibrium::Eval e = P.state_of(c, s, P.start_unknowns(c, s));
  Eigen::VectorXd f_app = e.f_app;
  if (P.ctrl.node >= 0 && !P.has_loads) f_app[P.ns.reference_map().raw_node(P.ctrl.node, P.ctrl.comp)] += c.extra_mu;
  const auto ev = P.ns.evaluate(c.state, f_app, true, e.mu_closure, c.lambda);
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < ev.tangent.outerSize(); ++j) {
    if (P.gen_to_free[j] < 0) continue;
    for (SparseMatrix::InnerIterator it(ev.tangent, j); it; ++it)
      if (P.gen_to_free[it.row()] >= 0) t.emplace_back(P.gen_to_free[it.row()], P.gen_to_free[j], it.value());
  }
  SparseMatrix Kff(P.nf, P.nf);
  Kff.setFromTriplets(t.begin(), t.end());
  out.Z = null_space(P.constraint_matrix(c.state, with_control), P.nf);
  out.K = SparseMatrix(out.Z.transpose() * Kff * out.Z);
  out.p = out.Z.transpose() * P.load_pattern(c.state);
  return out;
}

StabilityAnalysis StabilityAnalyzer::analyse(const Converged& c, bool with_control, bool want_mode) {
  StabilityAnalysis out = constrained_tangent(eq_, c, with_control);
  SparseMatrix S = SparseMatrix(0.5 * (out.K + SparseMatrix(out.K.transpose())));
  const int n = static_cast<int>(S.rows());
  if (n == 0) return out;
  // Inertia by LDL^T (Sylvester): the number of negative pivots.
  if (inertia_ldlt_.factorize(S)) {
    out.info.negative = static_cast<int>((inertia_ldlt_.solver().vectorD().array() < 0.0).count());
  } else {
    out.info.negative = -1;
  }
  // Lowest eigenvalue of the Jacobi-scaled matrix.
  Eigen::VectorXd sc(n);
  for (int i = 0; i < n; ++i) {
    const double d = std::abs(S.coeff(i, i));
    sc[i] = d > 0.0 ? 1.0 / std::sqrt(d) : 1.0;
  }
  const SparseMatrix A = SparseMatrix(sc.asDiagonal() * S * sc.asDiagonal());
  const auto gershgorin_shift = [&] {  // below the Gershgorin lower bound of the spectrum
    double g = 0.0;
    for (int j = 0; j < A.outerSize(); ++j) {
      double diag = 0.0, off = 0.0;
      for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
        if (it.row() == j) diag += it.value();
        else off += std::abs(it.value());
      }
      g = std::min(g, diag - off);
    }
    return g - kEigenShiftMargin;
  };
  // Shift-invert converges fast only with the shift near the wanted eigenvalue. Along a path the
  // lowest eigenvalue moves continuously: below zero, the shift is a little below the last one found
  // (kNegativeShiftFactor), which the Gershgorin bound (far below, slow) only backs up.
  double shift = -kEigenShiftMargin;
  if (out.info.negative != 0)
    shift = last_min_ < 0.0 ? kNegativeShiftFactor * last_min_ - kEigenShiftMargin : -kFirstNegativeShift;
  const int want = out.info.negative != 0 || want_mode ? std::max(1, out.info.negative) + 1 : 1;
  for (int attempt = 0; attempt < 2; ++attempt) {
    try {
      EigenPairs ep;
      if (n <= kDenseEigenLimit) {
        // Dense: a few milliseconds at this size, and no Lanczos restarts on the clustered lowest
        // eigenvalues of slender structures (bending next to axial stiffness).
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es{Eigen::MatrixXd(A)};
        ep.values = es.eigenvalues().head(std::min(want, n));
        ep.vectors = es.eigenvectors().leftCols(std::min(want, n));
      } else {
        ep = lowest_eigenpairs(A, std::min(want, n), shift);
      }
      const int found_negative = static_cast<int>((ep.values.array() < 0.0).count());
      if (attempt == 0 && out.info.negative > 0 && found_negative == 0) {
        shift = gershgorin_shift();  // the continuation shift missed the negative eigenvalue
        continue;
      }
      if (ep.values.size() > 0) {
        out.info.min_eigenvalue = ep.values[0];
        last_min_ = ep.values[0];
        if (want_mode) {
          Eigen::Index best = 0;
          ep.values.cwiseAbs().minCoeff(&best);
          out.info.mode = out.Z * Eigen::VectorXd(sc.cwiseProduct(ep.vectors.col(best)));
        }
      }
      break;
    } catch (const Error&) {
      out.info.min_eigenvalue = NAN;
      if (attempt == 0) shift = gershgorin_shift();
    }
  }
  return out;
}

CondensedStiffness StabilityAnalyzer::node_stiffness(const Converged& c, const StabilityAnalysis& st, int node) const {
  const PathEquilibrium& P = eq_;
  const auto tw = P.ns.twists(c.state);
  const int n = static_cast<int>(st.K.rows());
  // The node's six rows over the constrained coordinates: T_n Z.
  Eigen::MatrixXd Tn = Eigen::MatrixXd::Zero(6, n);
  for (int k = 0; k < 6 && n > 0; ++k) {
    Eigen::VectorXd r = Eigen::VectorXd::Zero(P.nf);
    for (const auto& [g, v] : P.ns.raw_row(c.state, tw, node, k))
      if (P.gen_to_free[g] >= 0) r[P.gen_to_free[g]] += v;
    Tn.row(k) = (st.Z.transpose() * r).transpose();
  }
  // The coordinates of Z mix translations and rotations: no per-column scale (the range of T_n Z,
  // what the node can move, does not depend on it).
  return node_compliance(st.K, Tn, Eigen::VectorXd::Ones(n), P.L);
}

}  // namespace beamfea
