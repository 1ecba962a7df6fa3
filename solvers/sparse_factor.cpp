#include "solvers/sparse_factor.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>
#include <algorithm>
#include <cmath>
#include <mutex>

#include "core/errors.hpp"
#include "core/huge_pages.hpp"
#include "solvers/dense_condensation.hpp"
#include "solvers/fill_ordering.hpp"

namespace beamfea {

struct SparseFactor::Impl {
  // Gives access to CHOLMOD's factor for the reciprocal condition estimate.
  class Cholesky : public Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> {
   public:
    double rcond() { return m_cholmodFactor ? cholmod_rcond(m_cholmodFactor, &this->cholmod()) : 0.0; }
    // CHOLMOD's default trials (nmethods = 0: AMD, then METIS if AMD's fill is poor), undoing what
    // analyze_two_orderings set.
    void default_orderings() {
      cholmod_common& c = this->cholmod();
      c.nmethods = 0;
      c.method[0].ordering = CHOLMOD_GIVEN;  // cholmod_defaults' value
      c.postorder = 1;
    }
    // From kOrderedMinDofs to kNesdisTrialMaxDofs: two orderings of the compressed graph, NESDIS
    // and METIS (solvers/fill_ordering.hpp), and the one whose factor has fewer nonzeros (the rule
    // CHOLMOD applies between its own trials; NESDIS on a tie; counted on the compressed graph,
    // factor_nonzeros) analysed by CHOLMOD as the given permutation (cholmod_analyze_p); CHOLMOD's
    // METIS on the whole graph above kNesdisTrialMaxDofs or when neither ordering could be made.
    // Eigen's analyzePattern, with the permutation passed.
    void analyze_two_orderings(const SparseMatrix& A, bool try_supervariables, std::string& summary) {
      cholmod_common& c = this->cholmod();
      const SupervariableOrderings orders = try_supervariables ? orderings_by_supervariables(A, c) : SupervariableOrderings{};
      if (m_cholmodFactor) cholmod_free_factor(&m_cholmodFactor, &c);
      cholmod_sparse a = Eigen::viewAsCholmod(A.selfadjointView<Eigen::Lower>());
      c.postorder = 1;
      auto analyse = [&](const std::vector<int>& perm) -> cholmod_factor* {
        c.nmethods = 1;
        c.method[0].ordering = perm.empty() ? CHOLMOD_METIS : CHOLMOD_GIVEN;
        return cholmod_analyze_p(&a, perm.empty() ? nullptr : const_cast<int*>(perm.data()), nullptr, 0, &c);
      };
      const bool has_nesdis = !orders.nesdis.empty(), has_metis = !orders.metis.empty();
      if (has_nesdis && has_metis) {
        const bool nesdis = orders.lnz_nesdis <= orders.lnz_metis;
        m_cholmodFactor = analyse(nesdis ? orders.nesdis : orders.metis);
        summary = fmt::format("{} (nnz(L): NESDIS of supervariables {:.3g}, METIS of supervariables {:.3g})",
                              nesdis ? "NESDIS" : "METIS", orders.lnz_nesdis, orders.lnz_metis);
      } else if (has_nesdis || has_metis) {
        m_cholmodFactor = analyse(has_nesdis ? orders.nesdis : orders.metis);
        summary = has_nesdis ? "NESDIS of supervariables" : "METIS of supervariables";
      } else {
        m_cholmodFactor = analyse({});  // CHOLMOD's METIS on the whole graph
        summary = "METIS";
      }
      this->m_isInitialized = true;
      m_analysisIsOk = m_cholmodFactor != nullptr;
      m_factorizationIsOk = false;
      this->m_info = m_cholmodFactor ? Eigen::Success : Eigen::NumericalIssue;
    }
  };

  // The dense factor (solvers/dense_condensation.hpp), kept between factorisations: no
  // allocation while the size stays.
  Eigen::MatrixXd dense_l;
  std::vector<int> dense_last;
  Cholesky llt;
  Eigen::UmfPackLU<SparseMatrix> lu;
  SparseMatrix lu_matrix;  // S K S, which lu refers to
  Eigen::Index rows = -1, nnz = -1;
  std::string ordering;  // SparseFactor::ordering()
  bool analysed = false, lu_analysed = false;
};

namespace {
// CHOLMOD allocates its factor itself (83 MB at 21,504 DOFs), through SuiteSparse's process-wide
// allocation functions: set once to malloc, calloc and realloc followed by huge-page advice for a
// large block (core/huge_pages.hpp). Freeing stays std::free, so a block allocated before the
// change, or by another CHOLMOD user in the process, is freed correctly.
void advise_cholmod_allocations() {
  static std::once_flag once;
  std::call_once(once, [] {
    SuiteSparse_config.malloc_func = &malloc_advised;
    SuiteSparse_config.calloc_func = &calloc_advised;
    SuiteSparse_config.realloc_func = &realloc_advised;
  });
}
}  // namespace

SparseFactor::SparseFactor(const SolverOptions& options)
    : impl_((advise_cholmod_allocations(), std::make_unique<Impl>())), options_(options) {
  options_.validate();
  impl_->llt.cholmod().print = 0;  // failures are outcomes here, reported by the caller
}
SparseFactor::~SparseFactor() = default;

SparseMatrix scaled(const SparseMatrix& K, const Eigen::VectorXd& s) {
  SparseMatrix A = K;
  for (int j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) it.valueRef() *= s[it.row()] * s[j];
  return A;
}

SparseMatrix scaled_lower(const SparseMatrix& K, const Eigen::VectorXd& s) {
  const Eigen::Index n = K.outerSize();
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  const double* value = K.valuePtr();
  const int* nnz = K.innerNonZeroPtr();  // null when K is compressed
  // Rows are sorted within a column: the lower part of column j starts at the first row >= j.
  std::vector<int> first(n), count(n);
  Eigen::Index total = 0;
  for (Eigen::Index j = 0; j < n; ++j) {
    const int* b = inner + outer[j];
    const int* e = b + (nnz ? nnz[j] : outer[j + 1] - outer[j]);
    first[j] = static_cast<int>(std::lower_bound(b, e, static_cast<int>(j)) - inner);
    count[j] = static_cast<int>(e - inner) - first[j];
    total += count[j];
  }
  SparseMatrix A(K.rows(), K.cols());
  A.resizeNonZeros(total);
  int* a_outer = A.outerIndexPtr();
  int* a_inner = A.innerIndexPtr();
  double* a_value = A.valuePtr();
  a_outer[0] = 0;
  for (Eigen::Index j = 0; j < n; ++j) {
    const int start = a_outer[j];
    for (int k = 0; k < count[j]; ++k) {
      const int p = first[j] + k;
      a_inner[start + k] = inner[p];
      a_value[start + k] = value[p] * s[inner[p]] * s[j];
    }
    a_outer[j + 1] = start + count[j];
  }
  return A;
}

FactorStatus SparseFactor::factorize(const SparseMatrix& K, const FactorOptions& options) {
  status_ = factorize_scaled(K, options);
  return status_;
}

FactorStatus SparseFactor::factorize_scaled(const SparseMatrix& K, const FactorOptions& options) {
  options.validate();
  const Eigen::Index n = K.rows();
  s_.resize(n);
  unrestrained_.clear();
  const Eigen::VectorXd d = K.diagonal();
  for (Eigen::Index i = 0; i < n; ++i) {
    if (d[i] > 0.0) {
      s_[i] = 1.0 / std::sqrt(d[i]);
    } else {
      s_[i] = 1.0;
      unrestrained_.push_back(static_cast<int>(i));
    }
  }
  cholesky_ok_ = dense_ok_ = lu_ok_ = false;
  rcond_ = 0.0;
  // A DOF with no stiffness at all (zero diagonal): singular, whatever a factorisation would say;
  // the caller diagnoses it (and CHOLMOD is never handed an empty column).
  if (!unrestrained_.empty()) return FactorStatus::NotPositiveDefinite;
  if (n > 0 && n <= options.dense_max_dofs) {
    // Small system: dense Cholesky of S K S (lower triangle, as CHOLMOD reads it), skipping the
    // zeros of the matrix (solvers/dense_condensation.hpp). A failure falls through to the sparse
    // path below, which decides (CHOLMOD, then LU).
    Eigen::MatrixXd& D = impl_->dense_l;
    D.setZero(n, n);
    for (int j = 0; j < K.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(K, j); it; ++it)
        if (it.row() >= j) D(it.row(), j) = it.value() * s_[it.row()] * s_[j];
    if (cholesky_in_place(D, impl_->dense_last)) {
      rcond_ = cholesky_rcond(D);
      cholesky_ok_ = dense_ok_ = true;
      return rcond_ >= options.singular_rcond ? FactorStatus::Succeeded : FactorStatus::NotPositiveDefinite;
    }
  }
  // CHOLMOD reads the lower triangle only (Eigen::Lower): the scaled copy is of that half.
  const SparseMatrix A = scaled_lower(K, s_);
  if (!analyse(A)) return FactorStatus::TooLarge;
  if (n == 0) {
    cholesky_ok_ = true;
    rcond_ = 1.0;
    return FactorStatus::Succeeded;
  }
  impl_->llt.factorize(A);
  if (impl_->llt.info() == Eigen::Success) {
    rcond_ = impl_->llt.rcond();
    cholesky_ok_ = true;
    if (rcond_ >= options.singular_rcond && unrestrained_.empty()) return FactorStatus::Succeeded;
    return FactorStatus::NotPositiveDefinite;
  }
  if (!options.allow_lu) return FactorStatus::NotPositiveDefinite;
  // UMFPACK needs both triangles, and keeps a reference to the matrix for the iterative
  // refinement of its solves: the scaled copy lives as long as the factor.
  SparseMatrix& full = impl_->lu_matrix;
  full = scaled(K, s_);
  if (!impl_->lu_analysed) {
    impl_->lu.analyzePattern(full);
    impl_->lu_analysed = true;
  }
  impl_->lu.factorize(full);
  lu_ok_ = impl_->lu.info() == Eigen::Success;
  return lu_ok_ ? FactorStatus::NotPositiveDefinite : FactorStatus::Singular;
}

bool SparseFactor::analyse(const SparseMatrix& A) {
  const Eigen::Index n = A.rows();
  if (impl_->analysed && impl_->rows == n && impl_->nnz == A.nonZeros()) return true;
  if (n >= kOrderedMinDofs) {
    impl_->llt.analyze_two_orderings(A, n <= kNesdisTrialMaxDofs, impl_->ordering);
  } else {
    impl_->llt.default_orderings();
    impl_->llt.analyzePattern(A);
    impl_->ordering = "CHOLMOD's choice";
  }
  if (impl_->llt.info() != Eigen::Success) {
    impl_->analysed = false;
    return false;
  }
  impl_->analysed = true;
  impl_->lu_analysed = false;
  impl_->rows = n;
  impl_->nnz = A.nonZeros();
  return true;
}

void SparseFactor::analyze(const SparseMatrix& K, const FactorOptions& options) {
  options.validate();
  const Eigen::Index n = K.rows();
  if (n == 0 || n <= options.dense_max_dofs) return;
  if (!K.isCompressed()) throw Error("SparseFactor::analyze: the matrix must be compressed");
  // A DOF without any stiffness (an empty column): factorize stops before its analysis.
  for (Eigen::Index j = 0; j < n; ++j)
    if (K.outerIndexPtr()[j] == K.outerIndexPtr()[j + 1]) return;
  // The lower triangle's pattern, K's values unread (an assembly may be writing them meanwhile).
  const int* outer = K.outerIndexPtr();
  const int* inner = K.innerIndexPtr();
  std::vector<int> first(static_cast<std::size_t>(n));
  Eigen::Index total = 0;
  for (Eigen::Index j = 0; j < n; ++j) {
    first[j] = static_cast<int>(std::lower_bound(inner + outer[j], inner + outer[j + 1], static_cast<int>(j)) - inner);
    total += outer[j + 1] - first[j];
  }
  SparseMatrix A(n, n);
  A.resizeNonZeros(total);
  int* a_outer = A.outerIndexPtr();
  a_outer[0] = 0;
  for (Eigen::Index j = 0; j < n; ++j) {
    a_outer[j + 1] = a_outer[j] + (outer[j + 1] - first[j]);
    std::copy(inner + first[j], inner + outer[j + 1], A.innerIndexPtr() + a_outer[j]);
  }
  std::fill(A.valuePtr(), A.valuePtr() + total, 1.0);  // read by no ordering or analysis
  analyse(A);
}

std::string SparseFactor::ordering() const { return impl_->ordering; }

void SparseFactor::solve(Eigen::Ref<const Eigen::VectorXd> b, Eigen::Ref<Eigen::VectorXd> x) const {
  if (s_.size() == 0) return;
  if (!cholesky_ok_ && !lu_ok_) throw Error("SparseFactor::solve: no valid factorisation");
  if (b.size() != s_.size() || x.size() != s_.size()) throw Error("SparseFactor::solve: sizes differ");
  x = s_.cwiseProduct(b);  // S b
  if (dense_ok_) {
    cholesky_solve_in_place(impl_->dense_l, impl_->dense_last, x);
    x.array() *= s_.array();
    return;
  }
  const Eigen::VectorXd y = cholesky_ok_ ? Eigen::VectorXd(impl_->llt.solve(x)) : Eigen::VectorXd(impl_->lu.solve(x));
  x = s_.cwiseProduct(y);
}

void SparseFactor::solve(const Eigen::MatrixXd& B, Eigen::MatrixXd& X) const {
  if (s_.size() == 0) {
    X.resize(0, B.cols());
    return;
  }
  if (!cholesky_ok_ && !lu_ok_) throw Error("SparseFactor::solve: no valid factorisation");
  X = s_.asDiagonal() * B;
  if (dense_ok_) {
    for (Eigen::Index c = 0; c < X.cols(); ++c) cholesky_solve_in_place(impl_->dense_l, impl_->dense_last, X.col(c));
  } else {
    X = cholesky_ok_ ? Eigen::MatrixXd(impl_->llt.solve(X)) : Eigen::MatrixXd(impl_->lu.solve(X));
  }
  X = s_.asDiagonal() * X;
}

std::optional<Inertia> SparseFactor::inertia() const {
  if (status_ != FactorStatus::Succeeded || !cholesky_ok_) return std::nullopt;
  return Inertia{0, 0, static_cast<int>(s_.size())};
}

}  // namespace beamfea
