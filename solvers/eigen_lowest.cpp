#include "solvers/eigen_lowest.hpp"

#include <Eigen/Eigenvalues>
#include <Spectra/SymEigsShiftSolver.h>
#include <algorithm>

#include "core/errors.hpp"
#include "solvers/linear_solver.hpp"

namespace beamfea {

namespace {
// y = (A - sigma I)^-1 x by the solver contract's Cholmod back end (solvers/linear_solver.hpp):
// CHOLMOD's LL^T first, UMFPACK's LU when A - sigma I is indefinite.
class ShiftInvert {
 public:
  using Scalar = double;
  explicit ShiftInvert(const SparseMatrix& A)
      : A_(A), factor_(make_linear_solver(SolverOptions{.backend = SolverBackend::Cholmod})) {}
  Eigen::Index rows() const { return A_.rows(); }
  Eigen::Index cols() const { return A_.cols(); }
  void set_shift(const double& sigma) {
    SparseMatrix S = A_;
    for (int i = 0; i < S.rows(); ++i) S.coeffRef(i, i) -= sigma;
    S.makeCompressed();
    factor_->compute(S);
    if (!factor_->usable()) throw Error("eigen-solver: the shifted matrix is singular; move the shift");
  }
  void perform_op(const double* x_in, double* y_out) const {
    factor_->solve(Eigen::Map<const Eigen::VectorXd>(x_in, rows()), Eigen::Map<Eigen::VectorXd>(y_out, rows()));
  }

 private:
  const SparseMatrix& A_;
  std::unique_ptr<LinearSolver> factor_;
};
// The operator of lowest_eigenpairs_of_inverse: A^-1 as given (the shift is always zero).
class GivenInverse {
 public:
  using Scalar = double;
  GivenInverse(Eigen::Index n, const InverseOp& f) : n_(n), f_(f) {}
  Eigen::Index rows() const { return n_; }
  Eigen::Index cols() const { return n_; }
  void set_shift(const double& sigma) {
    if (sigma != 0.0) throw Error("eigen-solver: a given inverse takes no shift");
  }
  void perform_op(const double* x_in, double* y_out) const { f_(x_in, y_out); }

 private:
  Eigen::Index n_;
  const InverseOp& f_;
};

// Eigenpairs of the solver sorted by ascending eigenvalue.
template <class Solver>
EigenPairs ascending(Solver& eigs, Eigen::Index n) {
  EigenPairs out;
  out.converged = eigs.info() == Spectra::CompInfo::Successful;
  Eigen::VectorXd v = eigs.eigenvalues();
  Eigen::MatrixXd V = eigs.eigenvectors();
  std::vector<int> idx(v.size());
  for (int i = 0; i < v.size(); ++i) idx[i] = i;
  std::sort(idx.begin(), idx.end(), [&](int a, int b) { return v[a] < v[b]; });
  out.values.resize(v.size());
  out.vectors.resize(n, v.size());
  for (int i = 0; i < v.size(); ++i) {
    out.values[i] = v[idx[i]];
    out.vectors.col(i) = V.col(idx[i]);
  }
  return out;
}

// Lanczos basis size: twice the wanted count plus one, at least 20 (Spectra's advice), at most n.
int lanczos_size(Eigen::Index n, int count) {
  return static_cast<int>(std::min<Eigen::Index>(n, std::max(2 * count + 1, 20)));
}
constexpr int kMaxRestarts = 1000;
constexpr double kEigenTolerance = 1e-10;  // Spectra's relative tolerance on the Ritz values
}  // namespace

EigenPairs lowest_eigenpairs_of_inverse(Eigen::Index n, const InverseOp& inverse, int count, const Eigen::VectorXd* start) {
  count = static_cast<int>(std::min<Eigen::Index>(count, n - 1));
  if (count <= 0) return {};
  GivenInverse op(n, inverse);
  Spectra::SymEigsShiftSolver<GivenInverse> eigs(op, count, lanczos_size(n, count), 0.0);
  if (start && start->size() == n && start->squaredNorm() > 0.0) {
    eigs.init(start->data());
  } else {
    eigs.init();
  }
  eigs.compute(Spectra::SortRule::LargestMagn, kMaxRestarts, kEigenTolerance);
  return ascending(eigs, n);
}

EigenPairs lowest_eigenpairs(const SparseMatrix& A, int count, double shift) {
  EigenPairs out;
  const Eigen::Index n = A.rows();
  count = static_cast<int>(std::min<Eigen::Index>(count, n));
  if (count <= 0) return out;
  if (n <= 200 || count >= n - 1) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es{Eigen::MatrixXd(A)};
    out.values = es.eigenvalues().head(count);
    out.vectors = es.eigenvectors().leftCols(count);
    return out;
  }
  ShiftInvert op(A);
  Spectra::SymEigsShiftSolver<ShiftInvert> eigs(op, count, lanczos_size(n, count), shift);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestMagn, kMaxRestarts, kEigenTolerance);
  return ascending(eigs, n);
}

}  // namespace beamfea
