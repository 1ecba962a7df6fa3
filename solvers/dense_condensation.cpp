#include "solvers/dense_condensation.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

namespace beamfea {

bool cholesky_in_place(Eigen::MatrixXd& A, std::vector<int>& last) {
  return cholesky_in_place(A, last, static_cast<int>(A.rows()));
}

bool cholesky_in_place(Eigen::MatrixXd& A, std::vector<int>& last, int columns) {
  const int n = static_cast<int>(A.rows());
  last.assign(n, 0);
  double* a = A.data();
  const Eigen::Index ld = A.rows();
  for (int k = 0; k < columns; ++k) {
    double* ak = a + ld * k;
    const double d = ak[k];
    if (!(d > 0.0) || !std::isfinite(d)) return false;
    const double r = std::sqrt(d);
    ak[k] = r;
    const double inv = 1.0 / r;
    int lk = k;
    for (int i = k + 1; i < n; ++i) {
      ak[i] *= inv;
      if (ak[i] != 0.0) lk = i;
    }
    last[k] = lk;
    // Right-looking update of the trailing columns that row k reaches: A_jj.. -= L_jk L_.k
    for (int j = k + 1; j <= lk; ++j) {
      const double ljk = ak[j];
      if (ljk == 0.0) continue;
      double* __restrict aj = a + ld * j;
      const double* __restrict akk = ak;
      for (int i = j; i <= lk; ++i) aj[i] -= ljk * akk[i];
    }
  }
  return true;
}

void cholesky_solve_in_place(const Eigen::MatrixXd& L, const std::vector<int>& last, Eigen::Ref<Eigen::VectorXd> x) {
  const Eigen::Index n = L.rows();
  for (Eigen::Index k = 0; k < n; ++k) {  // L y = x
    const double* lk = L.col(k).data();
    const double xk = x[k] / lk[k];
    x[k] = xk;
    if (xk != 0.0)
      for (Eigen::Index i = k + 1; i <= last[k]; ++i) x[i] -= lk[i] * xk;
  }
  for (Eigen::Index k = n; k-- > 0;) {  // L^T x = y
    const double* lk = L.col(k).data();
    double xk = x[k];
    for (Eigen::Index i = k + 1; i <= last[k]; ++i) xk -= lk[i] * x[i];
    x[k] = xk / lk[k];
  }
}

double cholesky_rcond(const Eigen::MatrixXd& L) {
  if (L.rows() == 0) return 1.0;
  const auto d = L.diagonal().cwiseAbs();
  const double lo = d.minCoeff(), hi = d.maxCoeff();
  return hi > 0.0 ? (lo / hi) * (lo / hi) : 0.0;
}

bool dense_schur_condensation(const Eigen::MatrixXd& K, const Eigen::MatrixXd& A, Eigen::MatrixXd& Kz, const FactorOptions& options,
                    DenseCondensationWorkspace* workspace) {
  const Eigen::Index n = K.rows(), r = A.rows();
  if (n == 0 || n > options.dense_max_dofs || K.cols() != n || A.cols() != n || r == 0) return false;
  DenseCondensationWorkspace local;
  DenseCondensationWorkspace& w = workspace ? *workspace : local;
  // Jacobi scaling as in SparseFactor::factorize: S K S, so that the condition estimate does not
  // depend on units; A K^-1 A^T = (A S) (S K S)^-1 (A S)^T.
  w.s.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!(K(i, i) > 0.0)) return false;
    w.s[i] = 1.0 / std::sqrt(K(i, i));
  }
  w.L.resize(n, n);
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = j; i < n; ++i) w.L(i, j) = K(i, j) * w.s[i] * w.s[j];
  if (!cholesky_in_place(w.L, w.last) || cholesky_rcond(w.L) < options.singular_rcond) return false;
  // C = (A S) L^-T L^-1 (A S)^T = W^T W with W = L^-1 (A S)^T: forward substitution column by
  // column, skipping the zeros of W (the rows of one node touch few DOFs) and of L.
  w.W = (A * w.s.asDiagonal()).transpose();
  for (Eigen::Index c = 0; c < r; ++c) {
    double* x = w.W.col(c).data();
    for (Eigen::Index k = 0; k < n; ++k) {
      if (x[k] == 0.0) continue;
      const double* lk = w.L.col(k).data();
      const double xk = x[k] / lk[k];
      x[k] = xk;
      for (Eigen::Index i = k + 1; i <= w.last[k]; ++i) x[i] -= lk[i] * xk;
    }
  }
  w.C.noalias() = w.W.transpose().lazyProduct(w.W);  // r x r, r <= a few: no GEMM blocking
  const Eigen::LLT<Eigen::MatrixXd>& lc = w.llt.compute(w.C);
  if (lc.info() != Eigen::Success || cholesky_rcond(lc.matrixLLT()) < options.singular_rcond) return false;
  Kz = lc.solve(Eigen::MatrixXd::Identity(r, r));
  // Symmetric part, in place (each off-diagonal pair 0.5 (a + b); the diagonal is its
  // own mirror; no temporary).
  for (Eigen::Index j = 0; j < r; ++j)
    for (Eigen::Index i = j + 1; i < r; ++i) Kz(i, j) = Kz(j, i) = 0.5 * (Kz(i, j) + Kz(j, i));
  return Kz.allFinite();
}

bool dense_static_condensation(const Eigen::MatrixXd& K, std::span<const int> cols, std::span<const double> a,
                           Eigen::MatrixXd& Kz, const FactorOptions& options, DenseCondensationWorkspace* workspace) {
  const Eigen::Index n = K.rows();
  const Eigen::Index r = static_cast<Eigen::Index>(cols.size());
  if (n == 0 || n > options.dense_max_dofs || K.cols() != n || r == 0 || r > n ||
      static_cast<Eigen::Index>(a.size()) != r)
    return false;
  DenseCondensationWorkspace local;
  DenseCondensationWorkspace& w = workspace ? *workspace : local;
  const Eigen::Index m = n - r;  // the condensed DOFs, first in the new order
  // The new order: the other DOFs as they come, then the picked ones (`order` maps new to old).
  std::vector<int>& order = w.order;
  order.assign(n, 0);
  {
    std::vector<int>& picked = w.last;  // scratch here; cholesky_in_place sets it afresh below
    picked.assign(n, -1);
    for (Eigen::Index k = 0; k < r; ++k) {
      const int c = cols[k];
      if (c < 0 || c >= n || picked[c] >= 0 || !(a[k] != 0.0) || !std::isfinite(a[k])) return false;
      picked[c] = static_cast<int>(k);
    }
    Eigen::Index next = 0;
    for (Eigen::Index j = 0; j < n; ++j)
      if (picked[j] < 0) order[next++] = static_cast<int>(j);
    for (Eigen::Index k = 0; k < r; ++k) order[m + k] = cols[k];
  }
  // Jacobi scaling of the condensed block as in dense_schur_condensation (the condition estimate then does
  // not depend on units); a picked DOF is scaled too where its diagonal is positive (it is not a
  // pivot: a mechanism may leave it zero).
  w.s.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double d = K(order[i], order[i]);
    if (i < m && !(d > 0.0)) return false;
    w.s[i] = d > 0.0 ? 1.0 / std::sqrt(d) : 1.0;
  }
  // The lower triangle of the reordered, scaled matrix (K's lower triangle read). The order is
  // increasing over the condensed DOFs, so there row i >= j is old row order[i] >= order[j].
  w.L.resize(n, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const int oj = order[j];
    const double* kj = K.col(oj).data();
    double* lj = w.L.col(j).data();
    const double sj = w.s[j];
    Eigen::Index i = j;
    for (; i < m; ++i) lj[i] = kj[order[i]] * w.s[i] * sj;
    for (; i < n; ++i) {
      const int oi = order[i];
      lj[i] = (oi >= oj ? kj[oi] : K(oj, oi)) * w.s[i] * sj;
    }
  }
  // The first m columns of the factor; their right-looking updates leave the Schur complement
  // K_22 - K_21 K_11^-1 K_12 (scaled) in the trailing r x r block.
  if (!cholesky_in_place(w.L, w.last, static_cast<int>(m))) return false;
  // K itself positive definite and well-conditioned, as dense_schur_condensation asks (the trailing block's
  // own factor completes K's: the same reciprocal condition estimate over both diagonals); a
  // mechanism or an ill-posed condensation is left to dense_schur_condensation and the saddle point.
  {
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6> T;
    if (r > 6) return false;
    T = w.L.bottomRightCorner(r, r).template triangularView<Eigen::Lower>();
    Eigen::LLT<decltype(T), Eigen::Lower> llt(T);
    if (llt.info() != Eigen::Success) return false;
    const auto dt = llt.matrixLLT().diagonal().cwiseAbs();
    double lo = dt.minCoeff(), hi = dt.maxCoeff();
    if (m > 0) {
      const auto d = w.L.diagonal().head(m).cwiseAbs();
      lo = std::min(lo, d.minCoeff());
      hi = std::max(hi, d.maxCoeff());
    }
    if (!(hi > 0.0) || (lo / hi) * (lo / hi) < options.singular_rcond) return false;
  }
  // K_z = D^-1 S_2^-1 (trailing block) S_2^-1 D^-1 with D = diag(a), S_2 the picked DOFs' scales;
  // symmetric by construction (the lower triangle mirrored).
  Kz.resize(r, r);
  for (Eigen::Index l = 0; l < r; ++l)
    for (Eigen::Index k = l; k < r; ++k)
      Kz(k, l) = Kz(l, k) = w.L(m + k, m + l) / (w.s[m + k] * a[k]) / (w.s[m + l] * a[l]);
  return Kz.allFinite();
}

}  // namespace beamfea
