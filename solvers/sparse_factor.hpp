#pragma once
// Factorisation of the reduced stiffness matrix, with the symbolic analysis reused.
//
// The matrix is Jacobi-scaled (S K S, S = diag(K)^-1/2) so that decisions about singularity
// do not depend on units. CHOLMOD's supernodal Cholesky is used for positive definite systems;
// UMFPACK's LU otherwise. A zero-energy mode (mechanism) shows as a failed Cholesky or as a
// reciprocal condition estimate below `singular_rcond`.
#include <Eigen/Core>
#include <algorithm>
#include <memory>
#include <vector>
#include <string>

#include "core/dof_map.hpp"
#include "solvers/linear_solver.hpp"

namespace beamfea {

// From kOrderedMinDofs, CHOLMOD's default (AMD, then METIS when AMD's fill looks poor) is
// replaced: on the frames measured from 2e4 DOFs up it always ended with METIS, so its AMD trial
// was spent for nothing. Up to kNesdisTrialMaxDofs two orderings of the graph compressed by
// supervariables (solvers/fill_ordering.hpp), NESDIS and METIS, are each analysed by CHOLMOD and
// the one of fewer nonzeros in L kept (METIS of the compressed graph instead of
// CHOLMOD's METIS of the whole one, 3-6 % more fill for less time, and NESDIS kept on every frame
// measured in this band); above, CHOLMOD's METIS alone. Measured on cube frames (docs/performance.md, "Orderings"): NESDIS's factor has 13 % and 21 % fewer nonzeros at
// 21,504 and 34,992 DOFs (process CPU 0.82x at 21,504), but 25 %, 7 % and 1.5 % more at 69,828,
// 97,344 and 202,752, where the trial only costs (process CPU 1.06x at 97,344). Below
// kOrderedMinDofs CHOLMOD's default is kept: AMD alone, usually, cheaper than METIS there.
inline constexpr int kOrderedMinDofs = 20000;
inline constexpr int kNesdisTrialMaxDofs = 50000;

// The Automatic back end of the solver contract (solvers/linear_solver.hpp).
class SparseFactor final : public LinearSolver {
 public:
  explicit SparseFactor(const SolverOptions& options = {});
  ~SparseFactor() override;
  SparseFactor(const SparseFactor&) = delete;
  SparseFactor& operator=(const SparseFactor&) = delete;

  // Factorises K; the symbolic analysis is reused while the sparsity pattern is unchanged.
  FactorStatus factorize(const SparseMatrix& K, const FactorOptions& options);
  FactorStatus factorize(const SparseMatrix& K) { return factorize(K, options_); }
  // The symbolic analysis (ordering included) of K's pattern alone, ahead of factorize, which
  // reuses it for a matrix of that pattern: for a caller that knows the pattern before the values
  // (solvers/linear_static.cpp orders it while the element matrices are computed and assembled).
  // K's values are not read, so another thread may write them meanwhile; K must be compressed.
  // Nothing for a matrix factorize would factorise dense. Not at the same time as another call on
  // this object.
  void analyze(const SparseMatrix& K, const FactorOptions& options);

  // The contract, with the options given at construction.
  void analyze(const SparseMatrix& K) override { analyze(K, options_); }
  FactorStatus compute(const SparseMatrix& K) override { return factorize(K, options_); }
  FactorStatus status() const override { return status_; }
  bool usable() const override { return cholesky_ok_ || lu_ok_; }
  using LinearSolver::solve;
  // No allocation on the dense path (x is the scratch); CHOLMOD's and UMFPACK's solves allocate
  // their own.
  void solve(Eigen::Ref<const Eigen::VectorXd> b, Eigen::Ref<Eigen::VectorXd> x) const override;
  void solve(const Eigen::MatrixXd& B, Eigen::MatrixXd& X) const override;
  // Positive definite (0, 0, n) when the Cholesky succeeded and passed the condition test; none
  // otherwise.
  std::optional<Inertia> inertia() const override;
  Eigen::Index rows() const override { return s_.size(); }

  bool cholesky() const { return cholesky_ok_; }
  bool dense() const { return dense_ok_; }  // the last factorisation was the dense one
  double rcond() const { return rcond_; }             // of the scaled matrix (Cholesky only)
  // The fill-reducing ordering of the last sparse analysis, for reports: "NESDIS (...)" or
  // "METIS (...)" with the nonzeros of L under both where both were tried, "METIS" where METIS
  // alone was, "CHOLMOD's choice" below kOrderedMinDofs, "" before any.
  std::string ordering() const;
  const Eigen::VectorXd& scaling() const { return s_; }  // S
  // DOFs with a zero or negative diagonal (no stiffness at all), if any.
  const std::vector<int>& unrestrained() const { return unrestrained_; }

 private:
  struct Impl;
  FactorStatus factorize_scaled(const SparseMatrix& K, const FactorOptions& options);
  // The analysis of `lower` (the lower triangle CHOLMOD reads) unless the last one is of its
  // pattern; false when CHOLMOD could not make one (too large).
  bool analyse(const SparseMatrix& lower);
  std::unique_ptr<Impl> impl_;
  SolverOptions options_;
  Eigen::VectorXd s_;
  bool cholesky_ok_ = false;
  bool dense_ok_ = false;
  bool lu_ok_ = false;
  double rcond_ = 0.0;
  FactorStatus status_ = FactorStatus::Singular;
  std::vector<int> unrestrained_;
};

// The sparsity pattern of the last compressed matrix given a symbolic analysis, so that a
// factorisation reuses it while the pattern stays the same (assembly reuses its pattern too).
class PatternMemory {
 public:
  // True when A (compressed) has the remembered pattern; otherwise remembers A's and returns false.
  bool same_or_remember(const SparseMatrix& A) {
    const bool same = known_ && A.rows() + 1 == static_cast<Eigen::Index>(outer_.size()) &&
                      static_cast<Eigen::Index>(inner_.size()) == A.nonZeros() &&
                      std::equal(outer_.begin(), outer_.end(), A.outerIndexPtr()) &&
                      std::equal(inner_.begin(), inner_.end(), A.innerIndexPtr());
    if (!same) {
      outer_.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1);
      inner_.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
      known_ = true;
    }
    return same;
  }
  // Forces the next call to report a new pattern (after a failed factorisation).
  void forget() { known_ = false; }

 private:
  std::vector<int> outer_, inner_;
  bool known_ = false;
};

// S K S for S = scaling.
SparseMatrix scaled(const SparseMatrix& K, const Eigen::VectorXd& s);
// The lower triangle (diagonal included) of S K S, compressed: what CHOLMOD reads of a symmetric
// matrix, in half the memory and time of the full copy.
SparseMatrix scaled_lower(const SparseMatrix& K, const Eigen::VectorXd& s);

}  // namespace beamfea
