#include "solvers/condensation.hpp"

#include <algorithm>
#include <array>
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
// complement of the rows; false where it declines.
bool condense_dense_route(const Eigen::MatrixXd& K, const Eigen::MatrixXd& A, Eigen::MatrixXd& Kz,
                          const SolverOptions& options, CondensationWorkspace* w) {
  std::array<int, kMaxPickedColumns> cols;
  std::array<double, kMaxPickedColumns> coef;
  const std::size_t r = static_cast<std::size_t>(A.rows());
  if (picked_columns(A, cols, coef) &&
      dense_static_condensation(K, std::span<const int>(cols.data(), r), std::span<const double>(coef.data(), r), Kz,
                                options, w))
    return true;
  return dense_schur_condensation(K, A, Kz, options, w);
}

// K_z = -M of the saddle point by the Umfpack back end; false when singular or nearly so.
bool condense_saddle_point(const SparseMatrix& K, const Eigen::MatrixXd& A, Eigen::MatrixXd& Kz) {
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
  if ((S * X - rhs).norm() > kSaddleResidualRelative * (Eigen::MatrixXd(S.cwiseAbs() * X.cwiseAbs()).norm() + 1.0))
    return false;
  const Eigen::MatrixXd M = X.bottomRows(r);
  Kz = -0.5 * (M + M.transpose());
  return true;
}

}  // namespace

template <class Matrix>
Condensation::Outcome condense(const Matrix& K, const Eigen::MatrixXd& A, Eigen::MatrixXd& Kz,
                               const SolverOptions& options, CondensationWorkspace* workspace) {
  options.validate();
  const Eigen::Index n = K.rows();
  if (K.cols() != n || A.cols() != n || A.rows() == 0) throw Error("condense: K must be square and A have its columns");
  for (Eigen::Index k = 0; k < A.rows(); ++k)
    if ((A.row(k).array() == 0.0).all()) return Condensation::Outcome::HeldDof;
  const bool dense_only = dense_backend(options.backend);
  if (dense_only || (options.backend == SolverBackend::Automatic && n <= options.dense_max_dofs)) {
    SolverOptions o = options;
    if (dense_only) o.dense_max_dofs = std::numeric_limits<int>::max();  // the caller chose dense
    bool done;
    if constexpr (std::is_same_v<Matrix, SparseMatrix>) done = condense_dense_route(Eigen::MatrixXd(K), A, Kz, o, workspace);
    else done = condense_dense_route(K, A, Kz, o, workspace);
    if (done) return Condensation::Outcome::Succeeded;
    if (dense_only) return Condensation::Outcome::Mechanism;
  }
  bool done;
  if constexpr (std::is_same_v<Matrix, SparseMatrix>) done = condense_saddle_point(K, A, Kz);
  else done = condense_saddle_point(SparseMatrix(K.sparseView()), A, Kz);
  return done ? Condensation::Outcome::Succeeded : Condensation::Outcome::Mechanism;
}

template Condensation::Outcome condense(const SparseMatrix&, const Eigen::MatrixXd&, Eigen::MatrixXd&, const SolverOptions&,
                                        CondensationWorkspace*);
template Condensation::Outcome condense(const Eigen::MatrixXd&, const Eigen::MatrixXd&, Eigen::MatrixXd&,
                                        const SolverOptions&, CondensationWorkspace*);

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
