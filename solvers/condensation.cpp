#include "solvers/condensation.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

#include "core/errors.hpp"

namespace beamfea {

namespace {

// A saddle point whose residual exceeds this multiple of |S| |X| (plus one) is nearly singular:
// rounding of a regular one leaves about eps times that.
constexpr double kSaddleResidualRelative = 1e-8;
// The static condensation handles at most this many picked coordinates (a node's six).
constexpr int kMaxPickedColumns = 6;

bool dense_backend(SolverBackend b) {
  return b == SolverBackend::DenseLlt || b == SolverBackend::DenseLdlt || b == SolverBackend::DenseLu;
}

// Whether each row of A has one nonzero, in distinct columns: then `cols` and `coef` name them.
bool picked_columns(const Eigen::MatrixXd& A, std::array<int, kMaxPickedColumns>& cols,
                    std::array<double, kMaxPickedColumns>& coef) {
  const Eigen::Index r = A.rows();
  if (r == 0 || r > kMaxPickedColumns) return false;
  std::fill(cols.begin(), cols.end(), -1);
  for (Eigen::Index j = 0; j < A.cols(); ++j)
    for (Eigen::Index k = 0; k < r; ++k) {
      if (A(k, j) == 0.0) continue;
      if (cols[k] >= 0) return false;
      cols[k] = static_cast<int>(j);
      coef[k] = A(k, j);
    }
  return std::all_of(cols.begin(), cols.begin() + r, [](int c) { return c >= 0; });
}

// The dense route (see the header): static condensation onto picked columns, else the Schur
// complement of the rows; false where it declines. `residual`: the computed relative residual of
// the route's own solve with the factor it left in w (dense_route_residual).
double dense_route_residual(const Eigen::MatrixXd& K, const Eigen::MatrixXd& A, bool picked,
                            std::span<const int> cols, std::span<const double> coef, CondensationWorkspace& w);

bool condense_dense_route(const Eigen::MatrixXd& K, const Eigen::MatrixXd& A, Eigen::MatrixXd& Kz,
                          const SolverOptions& options, CondensationWorkspace& w, double* residual) {
  std::array<int, kMaxPickedColumns> cols;
  std::array<double, kMaxPickedColumns> coef;
  const std::size_t r = static_cast<std::size_t>(A.rows());
  const std::span<const int> c(cols.data(), r);
  const std::span<const double> a(coef.data(), r);
  bool picked = picked_columns(A, cols, coef) && dense_static_condensation(K, c, a, Kz, options, &w);
  if (!picked && !dense_schur_condensation(K, A, Kz, options, &w)) return false;
  if (residual) *residual = dense_route_residual(K, A, picked, c, a, w);
  return true;
}

// ||F - K X|| / ||F|| of the dense route's solve (0 when F = 0), K's lower triangle read:
//   static condensation: the condensed DOFs o under unit motions of the picked ones p,
//     K_oo X_o = F = -K_op X_p, X_p = diag(1/a) (A X = I), by the factor of the scaled K_oo;
//   Schur complement: K X = F = A^T, by the factor of the scaled K.
double dense_route_residual(const Eigen::MatrixXd& K, const Eigen::MatrixXd& A, bool picked,
                            std::span<const int> cols, std::span<const double> coef, CondensationWorkspace& w) {
  const Eigen::Index n = K.rows(), r = A.rows();
  const auto Ks = K.selfadjointView<Eigen::Lower>();
  if (picked) {
    const Eigen::Index m = n - r;
    w.X.setZero(n, r);
    for (Eigen::Index k = 0; k < r; ++k) w.X(cols[k], k) = 1.0 / coef[k];
    w.F.noalias() = Ks * w.X;  // K_op X_p over every row; the o rows negated are F
    Eigen::MatrixXd& Y = w.W;  // the scaled o rows: S_o^-1 X_o = L^-T L^-1 S_o F_o
    Y.resize(m, r);
    for (Eigen::Index i = 0; i < m; ++i) Y.row(i) = -w.F.row(w.order[i]) * w.s[i];
    const auto L = w.L.topLeftCorner(m, m).triangularView<Eigen::Lower>();
    L.solveInPlace(Y);
    L.transpose().solveInPlace(Y);
    double fn = 0.0;
    for (Eigen::Index i = 0; i < m; ++i) {
      w.X.row(w.order[i]) = Y.row(i) * w.s[i];
      fn += w.F.row(w.order[i]).squaredNorm();
    }
    if (!(fn > 0.0)) return 0.0;
    w.F.noalias() = Ks * w.X;  // K_oo X_o + K_op X_p: the residual over the o rows
    double rn = 0.0;
    for (Eigen::Index i = 0; i < m; ++i) rn += w.F.row(w.order[i]).squaredNorm();
    return std::sqrt(rn / fn);
  }
  // W = L^-1 (A S)^T: X = S L^-T W.
  w.X = w.W;
  w.L.triangularView<Eigen::Lower>().transpose().solveInPlace(w.X);
  w.X = w.s.asDiagonal() * w.X;
  w.F = A.transpose();
  const double fn = w.F.norm();
  w.F.noalias() -= Ks * w.X;
  return fn > 0.0 ? w.F.norm() / fn : 0.0;
}

// K_z = -M of the saddle point by the Umfpack back end; false when singular or nearly so.
// `residual`: ||rhs - S X|| / ||rhs||, computed.
bool condense_saddle_point(const SparseMatrix& K, const Eigen::MatrixXd& A, Eigen::MatrixXd& Kz, double* residual) {
  const int n = static_cast<int>(K.rows()), r = static_cast<int>(A.rows());
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(K.nonZeros() + 2 * A.size());
  for (int j = 0; j < K.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(K, j); it; ++it) t.emplace_back(static_cast<int>(it.row()), j, it.value());
  for (int k = 0; k < r; ++k)
    for (int j = 0; j < n; ++j)
      if (A(k, j) != 0.0) {
        t.emplace_back(n + k, j, A(k, j));
        t.emplace_back(j, n + k, A(k, j));
      }
  SparseMatrix S(n + r, n + r);
  S.setFromTriplets(t.begin(), t.end());
  S.makeCompressed();
  const std::unique_ptr<LinearSolver> lu = make_linear_solver(SolverOptions{.backend = SolverBackend::Umfpack});
  if (lu->compute(S) != FactorStatus::Succeeded) return false;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n + r, r);
  rhs.bottomRows(r).setIdentity();
  Eigen::MatrixXd X;
  lu->solve(rhs, X);
  if (!X.allFinite()) return false;
  const double rn = (S * X - rhs).norm();
  if (rn > kSaddleResidualRelative * (Eigen::MatrixXd(S.cwiseAbs() * X.cwiseAbs()).norm() + 1.0)) return false;
  if (residual) *residual = rn / rhs.norm();
  const Eigen::MatrixXd M = X.bottomRows(r);
  Kz = -0.5 * (M + M.transpose());
  return true;
}

}  // namespace

template <class Matrix>
Condensation::Outcome condense(const Matrix& K, const Eigen::MatrixXd& A, Eigen::MatrixXd& Kz,
                               const SolverOptions& options, CondensationWorkspace* workspace, double* residual) {
  options.validate();
  const Eigen::Index n = K.rows();
  if (K.cols() != n || A.cols() != n || A.rows() == 0) throw Error("condense: K must be square and A have its columns");
  for (Eigen::Index k = 0; k < A.rows(); ++k)
    if ((A.row(k).array() == 0.0).all()) return Condensation::Outcome::HeldDof;
  const bool dense_only = dense_backend(options.backend);
  if (dense_only || (options.backend == SolverBackend::Automatic && n <= options.dense_max_dofs)) {
    SolverOptions o = options;
    if (dense_only) o.dense_max_dofs = std::numeric_limits<int>::max();  // the caller chose dense
    CondensationWorkspace local;
    CondensationWorkspace& w = workspace ? *workspace : local;
    bool done;
    if constexpr (std::is_same_v<Matrix, SparseMatrix>) done = condense_dense_route(Eigen::MatrixXd(K), A, Kz, o, w, residual);
    else done = condense_dense_route(K, A, Kz, o, w, residual);
    if (done) return Condensation::Outcome::Succeeded;
    if (dense_only) return Condensation::Outcome::Mechanism;
  }
  bool done;
  if constexpr (std::is_same_v<Matrix, SparseMatrix>) done = condense_saddle_point(K, A, Kz, residual);
  else done = condense_saddle_point(SparseMatrix(K.sparseView()), A, Kz, residual);
  return done ? Condensation::Outcome::Succeeded : Condensation::Outcome::Mechanism;
}

template Condensation::Outcome condense(const SparseMatrix&, const Eigen::MatrixXd&, Eigen::MatrixXd&, const SolverOptions&,
                                        CondensationWorkspace*, double*);
template Condensation::Outcome condense(const Eigen::MatrixXd&, const Eigen::MatrixXd&, Eigen::MatrixXd&,
                                        const SolverOptions&, CondensationWorkspace*, double*);

Condensation::Outcome condense_iteratively(const PetscSolver& cg, const SparseMatrix& K, const Eigen::MatrixXd& A,
                                           Eigen::MatrixXd& Kz, SolverReport& report) {
  const Eigen::Index n = K.rows(), r = A.rows();
  if (K.cols() != n || A.cols() != n || r == 0) throw Error("condense: K must be square and A have its columns");
  report = {.iterative = true, .iterations = 0, .residual = 0.0};
  for (Eigen::Index k = 0; k < r; ++k)
    if ((A.row(k).array() == 0.0).all()) return Condensation::Outcome::HeldDof;
  Eigen::MatrixXd X(n, r);
  Eigen::VectorXd b, x, scratch;
  for (Eigen::Index k = 0; k < r; ++k) {
    b = A.row(k).transpose();
    const SolverReport one = solve_to_rtol(cg, K, b, x, scratch);
    report.add(one);
    const IterativeSolveReport& last = cg.last_solve();
    if (!last.converged() && last.outcome != IterativeSolveReport::Outcome::MaxIterations)
      return Condensation::Outcome::Mechanism;  // CG broke down: K is not positive definite
    if (!last.converged() || one.residual > cg.options().rtol) return Condensation::Outcome::NotConverged;
    X.col(k) = x;
  }
  // C = A K^-1 A^T, symmetric positive definite when K is and the rows are independent.
  Eigen::MatrixXd C = A * X;
  C = 0.5 * (C + C.transpose()).eval();
  const Eigen::LLT<Eigen::MatrixXd> llt(C);
  if (llt.info() != Eigen::Success) return Condensation::Outcome::Mechanism;
  Kz = llt.solve(Eigen::MatrixXd::Identity(r, r));
  Kz = 0.5 * (Kz + Kz.transpose()).eval();
  return Kz.allFinite() ? Condensation::Outcome::Succeeded : Condensation::Outcome::Mechanism;
}

Condensation condense(const DofMap& map, const SparseMatrix& K, std::span<const int> raw, const SolverOptions& options) {
  Condensation out;
  const int n = map.free_size();
  const Eigen::Index nd = static_cast<Eigen::Index>(raw.size());
  if (nd == 0) {
    out.outcome = Condensation::Outcome::Succeeded;
    return out;
  }
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(nd, n);
  for (Eigen::Index k = 0; k < nd; ++k)
    for (SparseRowMatrix::InnerIterator it(map.T_free(), raw[k]); it; ++it) A(k, it.col()) += it.value();
  for (Eigen::Index k = 0; k < nd; ++k)
    if ((A.row(k).array() == 0.0).all()) {
      out.outcome = Condensation::Outcome::HeldDof;
      out.held = static_cast<int>(k);
      return out;
    }
  out.outcome = condense(K, A, out.K, options);
  return out;
}

}  // namespace beamfea
