#include "solvers/eigen_lowest.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseLU>
#include <Spectra/SymEigsShiftSolver.h>
#include <algorithm>

#include "core/errors.hpp"

namespace beamfea {

namespace {
// y = (A - sigma I)^-1 x; Cholesky first, sparse LU when A - sigma I is indefinite.
class ShiftInvert {
 public:
  using Scalar = double;
  explicit ShiftInvert(const SparseMatrix& A) : A_(A) { llt_.cholmod().print = 0; }
  Eigen::Index rows() const { return A_.rows(); }
  Eigen::Index cols() const { return A_.cols(); }
  void set_shift(const double& sigma) {
    SparseMatrix S = A_;
    for (int i = 0; i < S.rows(); ++i) S.coeffRef(i, i) -= sigma;
    S.makeCompressed();
    llt_.compute(S);
    use_lu_ = llt_.info() != Eigen::Success;
    if (use_lu_) {
      lu_.compute(S);
      if (lu_.info() != Eigen::Success) throw Error("eigen-solver: the shifted matrix is singular; move the shift");
    }
  }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, rows());
    y = use_lu_ ? Eigen::VectorXd(lu_.solve(x)) : Eigen::VectorXd(llt_.solve(x));
  }

 private:
  const SparseMatrix& A_;
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> llt_;
  Eigen::SparseLU<SparseMatrix> lu_;
  bool use_lu_ = false;
};
}  // namespace

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
  const int ncv = static_cast<int>(std::min<Eigen::Index>(n, std::max(2 * count + 1, 20)));
  Spectra::SymEigsShiftSolver<ShiftInvert> eigs(op, count, ncv, shift);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestMagn, 1000, 1e-10);
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

}  // namespace beamfea
