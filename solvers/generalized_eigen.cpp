#include "solvers/generalized_eigen.hpp"

#include <Eigen/Eigenvalues>
#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/errors.hpp"
#include "solvers/linear_solver.hpp"

namespace beamfea {

namespace {

// Lanczos settings: Spectra's relative tolerance on the Ritz values, iteration cap (restarts).
constexpr double kLanczosTolerance = 1e-10;
constexpr int kLanczosMaxIterations = 1000;
constexpr int kMinSubspace = 20;  // ncv at least this (a few modes need room to converge)
// Dense: a theta = 1/(lambda - sigma) below this fraction of the largest is an infinite lambda
// (a massless direction), not a mode.
constexpr double kMasslessRelative = 1e-12;

// y = (K - sigma M)^{-1} x by the solver contract's Cholmod back end (solvers/linear_solver.hpp):
// CHOLMOD's supernodal LL^T, or UMFPACK's LU when K - sigma M is indefinite (a preload beyond
// buckling). The interface Spectra's shift-invert modes expect.
class ShiftedSolve {
 public:
  using Scalar = double;
  ShiftedSolve(const SparseMatrix& K, const SparseMatrix& M)
      : K_(K), M_(M), factor_(make_linear_solver(SolverOptions{.backend = SolverBackend::Cholmod})) {}
  Eigen::Index rows() const { return K_.rows(); }
  Eigen::Index cols() const { return K_.cols(); }
  void set_shift(const double& sigma) {
    SparseMatrix S = K_ - sigma * M_;
    S.makeCompressed();
    factor_->compute(S);
    if (!factor_->usable()) throw Error("eigen-solver: K - sigma M is singular (a massless mechanism?)");
  }
  void perform_op(const double* x_in, double* y_out) const {
    factor_->solve(Eigen::Map<const Eigen::VectorXd>(x_in, rows()), Eigen::Map<Eigen::VectorXd>(y_out, rows()));
  }

 private:
  const SparseMatrix& K_;
  const SparseMatrix& M_;
  std::unique_ptr<LinearSolver> factor_;
};

GeneralizedEigenPairs dense_pairs(const SparseMatrix& K, const SparseMatrix& M, int count, double sigma) {
  GeneralizedEigenPairs out;
  const Eigen::MatrixXd S = Eigen::MatrixXd(K) - sigma * Eigen::MatrixXd(M);
  const Eigen::MatrixXd Md(M);
  // Definite S = L L^T: the symmetric problem C y = theta y, C = L^{-1} M L^{-T}, phi = L^{-T} y.
  // Indefinite S (beyond buckling): the unsymmetric eigen-problem of S^{-1} M.
  Eigen::LLT<Eigen::MatrixXd> llt(S);
  std::vector<std::pair<double, Eigen::VectorXd>> pairs;
  if (llt.info() == Eigen::Success) {
    const Eigen::MatrixXd Linv = llt.matrixL().solve(Eigen::MatrixXd::Identity(S.rows(), S.cols()));
    const Eigen::MatrixXd C = Linv * Md * Linv.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (C + C.transpose()));
    const Eigen::VectorXd& th = es.eigenvalues();
    const double th_max = th.cwiseAbs().maxCoeff();
    for (Eigen::Index i = th.size() - 1; i >= 0; --i) {
      if (!(th[i] > kMasslessRelative * th_max)) break;
      // phi = L^{-T} y
      pairs.emplace_back(sigma + 1.0 / th[i], llt.matrixU().solve(es.eigenvectors().col(i)));
    }
  } else {
    Eigen::EigenSolver<Eigen::MatrixXd> es(S.lu().solve(Md));
    const Eigen::VectorXcd th = es.eigenvalues();
    const double th_max = th.cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < th.size(); ++i) {
      if (!(std::abs(th[i]) > kMasslessRelative * th_max)) continue;
      pairs.emplace_back(sigma + 1.0 / th[i].real(), es.eigenvectors().col(i).real());
    }
  }
  // nearest to sigma first
  std::sort(pairs.begin(), pairs.end(),
            [&](const auto& a, const auto& b) { return std::abs(a.first - sigma) < std::abs(b.first - sigma); });
  if (pairs.size() > static_cast<std::size_t>(count)) pairs.resize(count);
  std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  out.values.resize(static_cast<Eigen::Index>(pairs.size()));
  out.vectors.resize(K.rows(), static_cast<Eigen::Index>(pairs.size()));
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    Eigen::VectorXd v = pairs[i].second;
    v /= std::sqrt(v.dot(Md * v));
    out.values[static_cast<Eigen::Index>(i)] = pairs[i].first;
    out.vectors.col(static_cast<Eigen::Index>(i)) = v;
  }
  out.converged = true;
  return out;
}

}  // namespace

GeneralizedEigenPairs nearest_generalized_eigenpairs(const SparseMatrix& K, const SparseMatrix& M, int count,
                                                     double sigma) {
  const Eigen::Index n = K.rows();
  count = static_cast<int>(std::min<Eigen::Index>(count, n));
  if (count <= 0) return {Eigen::VectorXd(), Eigen::MatrixXd(n, 0), true, ""};
  if (n <= kDenseLimit || count >= n - 1) return dense_pairs(K, M, count, sigma);

  GeneralizedEigenPairs out;
  using BOp = Spectra::SparseSymMatProd<double>;
  ShiftedSolve op(K, M);
  BOp bop(M);
  const int ncv = static_cast<int>(std::min<Eigen::Index>(n, std::max(2 * count + 1, kMinSubspace)));
  Spectra::SymGEigsShiftSolver<ShiftedSolve, BOp, Spectra::GEigsMode::ShiftInvert> eigs(op, bop, count, ncv, sigma);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestMagn, kLanczosMaxIterations, kLanczosTolerance);
  if (eigs.info() != Spectra::CompInfo::Successful) {
    out.message = "shift-invert Lanczos did not converge";
    return out;
  }
  const Eigen::VectorXd v = eigs.eigenvalues();
  const Eigen::MatrixXd V = eigs.eigenvectors();
  std::vector<int> idx(static_cast<std::size_t>(v.size()));
  std::iota(idx.begin(), idx.end(), 0);
  std::sort(idx.begin(), idx.end(), [&](int a, int b) { return v[a] < v[b]; });
  out.values.resize(v.size());
  out.vectors.resize(n, v.size());
  // The operator is factorised already (set_shift in the solver's constructor).
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    const double lambda = v[idx[static_cast<std::size_t>(i)]];
    const Eigen::VectorXd Mx = M * V.col(idx[static_cast<std::size_t>(i)]);
    Eigen::VectorXd phi(n);
    op.perform_op(Mx.data(), phi.data());
    phi *= (lambda - sigma);  // purification (Ericsson & Ruhe 1980)
    phi /= std::sqrt(phi.dot(M * phi));
    out.values[i] = lambda;
    out.vectors.col(i) = phi;
  }
  out.converged = true;
  return out;
}

}  // namespace beamfea
