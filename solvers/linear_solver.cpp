#include "solvers/linear_solver.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "core/errors.hpp"
#include "solvers/pattern_factor.hpp"
#include "solvers/sparse_factor.hpp"

namespace beamfea {

const char* to_string(FactorStatus s) {
  switch (s) {
    case FactorStatus::Succeeded: return "ok";
    case FactorStatus::NotPositiveDefinite: return "not positive definite";
    case FactorStatus::Singular: return "singular";
    case FactorStatus::TooLarge: return "too large to factorise";
  }
  return "?";
}

const char* to_string(SolverBackend b) {
  switch (b) {
    case SolverBackend::Automatic: return "automatic";
    case SolverBackend::Cholmod: return "cholmod";
    case SolverBackend::Umfpack: return "umfpack";
    case SolverBackend::SimplicialLdlt: return "simplicial_ldlt";
    case SolverBackend::DenseLlt: return "dense_llt";
    case SolverBackend::DenseLdlt: return "dense_ldlt";
    case SolverBackend::DenseLu: return "dense_lu";
  }
  return "?";
}

void SolverOptions::validate() const {
  if (!(singular_rcond > 0.0 && singular_rcond < 1.0)) throw Error("SolverOptions: singular_rcond must be in (0, 1)");
  if (dense_max_dofs < 0) throw Error("SolverOptions: dense_max_dofs must not be negative");
}

Inertia count_inertia(const Eigen::VectorXd& d) {
  Inertia in;
  const double big = d.size() ? d.cwiseAbs().maxCoeff() : 0.0;
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    if (!(std::abs(d[i]) > kZeroPivotRelative * big)) ++in.zero;
    else if (d[i] < 0.0) ++in.negative;
    else ++in.positive;
  }
  return in;
}

namespace {

void check_square(const SparseMatrix& A) {
  if (A.rows() != A.cols()) throw Error("LinearSolver: the matrix must be square");
}

// Eigen's dense LLT, LDLT (with symmetric pivoting: its D gives the inertia) or PartialPivLU of a
// dense copy. The LL^T and the LU are tested by their reciprocal condition estimates.
class DenseFactor final : public LinearSolver {
 public:
  DenseFactor(SolverBackend kind, double singular_rcond) : kind_(kind), singular_rcond_(singular_rcond) {}
  void analyze(const SparseMatrix& A) override { check_square(A); }
  FactorStatus compute(const SparseMatrix& A) override {
    check_square(A);
    n_ = A.rows();
    dense_ = A;
    ok_ = true;
    status_ = FactorStatus::Succeeded;
    if (n_ == 0) return status_;
    switch (kind_) {
      case SolverBackend::DenseLlt:
        llt_.compute(dense_);
        ok_ = llt_.info() == Eigen::Success;
        if (!ok_ || !(llt_.rcond() >= singular_rcond_)) status_ = FactorStatus::NotPositiveDefinite;
        break;
      case SolverBackend::DenseLdlt:
        ldlt_.compute(dense_);
        ok_ = ldlt_.info() == Eigen::Success;
        if (!ok_ || count_inertia(ldlt_.vectorD()).zero > 0) status_ = FactorStatus::Singular;
        break;
      default:
        lu_.compute(dense_);
        ok_ = lu_.rcond() >= singular_rcond_;
        if (!ok_) status_ = FactorStatus::Singular;
        break;
    }
    return status_;
  }
  FactorStatus status() const override { return status_; }
  bool usable() const override { return ok_; }
  using LinearSolver::solve;
  void solve(Eigen::Ref<const Eigen::VectorXd> b, Eigen::Ref<Eigen::VectorXd> x) const override {
    if (!ok_) throw Error("DenseFactor::solve: no valid factorisation");
    if (n_ == 0) return;
    if (kind_ == SolverBackend::DenseLlt) x = llt_.solve(b);
    else if (kind_ == SolverBackend::DenseLdlt) x = ldlt_.solve(b);
    else x = lu_.solve(b);
  }
  void solve(const Eigen::MatrixXd& B, Eigen::MatrixXd& X) const override {
    if (!ok_) throw Error("DenseFactor::solve: no valid factorisation");
    if (n_ == 0) X.resize(0, B.cols());
    else if (kind_ == SolverBackend::DenseLlt) X = llt_.solve(B);
    else if (kind_ == SolverBackend::DenseLdlt) X = ldlt_.solve(B);
    else X = lu_.solve(B);
  }
  std::optional<Inertia> inertia() const override {
    if (!ok_) return std::nullopt;
    if (n_ == 0) return Inertia{};
    if (kind_ == SolverBackend::DenseLdlt) return count_inertia(ldlt_.vectorD());
    if (kind_ == SolverBackend::DenseLlt && status_ == FactorStatus::Succeeded) return Inertia{0, 0, static_cast<int>(n_)};
    return std::nullopt;
  }
  Eigen::Index rows() const override { return n_; }

 private:
  SolverBackend kind_;
  double singular_rcond_;
  Eigen::Index n_ = 0;
  Eigen::MatrixXd dense_;
  Eigen::LLT<Eigen::MatrixXd, Eigen::Lower> llt_;
  Eigen::LDLT<Eigen::MatrixXd, Eigen::Lower> ldlt_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  bool ok_ = false;
  FactorStatus status_ = FactorStatus::Singular;
};

// CHOLMOD's supernodal LL^T, and UMFPACK's LU where it fails (when allowed): NotPositiveDefinite
// then, with the LU usable, as SparseFactor reports it. Both keep their symbolic analyses.
class CholeskyOrLu final : public LinearSolver {
 public:
  explicit CholeskyOrLu(bool allow_lu) : allow_lu_(allow_lu) {}
  void analyze(const SparseMatrix& A) override {
    check_square(A);
    llt_.analyze(A);
  }
  FactorStatus compute(const SparseMatrix& A) override {
    check_square(A);
    use_lu_ = false;
    if (llt_.factorize(A)) return status_ = FactorStatus::Succeeded;
    if (!allow_lu_ || llt_.status() == FactorStatus::TooLarge) return status_ = llt_.status();
    use_lu_ = true;
    return status_ = lu_.factorize(A) ? FactorStatus::NotPositiveDefinite : FactorStatus::Singular;
  }
  FactorStatus status() const override { return status_; }
  bool usable() const override { return use_lu_ ? lu_.usable() : llt_.usable(); }
  using LinearSolver::solve;
  void solve(Eigen::Ref<const Eigen::VectorXd> b, Eigen::Ref<Eigen::VectorXd> x) const override {
    if (use_lu_) lu_.solve(b, x);
    else llt_.solve(b, x);
  }
  void solve(const Eigen::MatrixXd& B, Eigen::MatrixXd& X) const override {
    if (use_lu_) lu_.solve(B, X);
    else llt_.solve(B, X);
  }
  std::optional<Inertia> inertia() const override { return use_lu_ ? std::nullopt : llt_.inertia(); }
  Eigen::Index rows() const override { return llt_.rows(); }

 private:
  bool allow_lu_;
  bool use_lu_ = false;
  LltFactor llt_;
  LuFactor lu_;
  FactorStatus status_ = FactorStatus::Singular;
};

}  // namespace

std::unique_ptr<LinearSolver> make_linear_solver(const SolverOptions& options) {
  options.validate();
  switch (options.backend) {
    case SolverBackend::Automatic: return std::make_unique<SparseFactor>(options);
    case SolverBackend::Cholmod: return std::make_unique<CholeskyOrLu>(options.allow_lu);
    case SolverBackend::Umfpack: return std::make_unique<LuFactor>();
    case SolverBackend::SimplicialLdlt: return std::make_unique<LdltFactor>();
    case SolverBackend::DenseLlt:
    case SolverBackend::DenseLdlt:
    case SolverBackend::DenseLu: return std::make_unique<DenseFactor>(options.backend, options.singular_rcond);
  }
  throw Error("make_linear_solver: unknown back end");
}

}  // namespace beamfea
