#pragma once
// A sparse factorisation whose symbolic analysis is kept while the sparsity pattern does not change
// (KINSOL's Newton LU, the path's tangent LU or LL^T and its inertia LDL^T refactor the same pattern at
// every iteration or step), with counts of the symbolic analyses and numeric factorisations.
//
// Each is a back end of the solver contract (solvers/linear_solver.hpp), unscaled: LuFactor is
// SolverBackend::Umfpack, LdltFactor SolverBackend::SimplicialLdlt (inertia from the signs of D),
// LltFactor CHOLMOD's LL^T of SolverBackend::Cholmod (inertia when positive definite). Besides
// the contract, factorize() answers whether Eigen's factorisation succeeded and solver() gives
// the Eigen object itself (its solve options, its D), as the path solver reads them.
#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <Eigen/UmfPackSupport>

#include <type_traits>

#include "core/errors.hpp"
#include "solvers/linear_solver.hpp"
#include "solvers/sparse_factor.hpp"

namespace beamfea {

template <class Solver>
class PatternFactor : public LinearSolver {
 public:
  using EigenSolver = Solver;
  static constexpr bool kLdlt = std::is_same_v<Solver, Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>>>;
  static constexpr bool kLlt = std::is_same_v<Solver, Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>>;
  static constexpr bool kUmfpack = std::is_same_v<Solver, Eigen::UmfPackLU<SparseMatrix>>;

  // The contract (solvers/linear_solver.hpp).
  void analyze(const SparseMatrix& A0) override {
    A_ = A0;
    A_.makeCompressed();
    if (pattern_.same_or_remember(A_)) return;
    solver_.analyzePattern(A_);
    ++symbolic_;
    if (solver_.info() != Eigen::Success) pattern_.forget();
  }
  FactorStatus compute(const SparseMatrix& A0) override {
    factorize(A0);
    return status_;
  }
  FactorStatus status() const override { return status_; }
  bool usable() const override { return ok_; }
  using LinearSolver::solve;
  void solve(Eigen::Ref<const Eigen::VectorXd> b, Eigen::Ref<Eigen::VectorXd> x) const override {
    if (!ok_) throw Error("PatternFactor::solve: no valid factorisation");
    if constexpr (kUmfpack) x = solver_.solve(Eigen::VectorXd(b));  // UMFPACK reads b as writable
    else x = solver_.solve(b);
  }
  void solve(const Eigen::MatrixXd& B, Eigen::MatrixXd& X) const override {
    if (!ok_) throw Error("PatternFactor::solve: no valid factorisation");
    X = solver_.solve(B);
  }
  // LDL^T: the signs of D (Sylvester), a pivot below kZeroPivotRelative of the largest zero.
  // LL^T: positive definite when it succeeded. LU: none.
  std::optional<Inertia> inertia() const override {
    if (!ok_) return std::nullopt;
    if constexpr (kLdlt) {
      return count_inertia(solver_.vectorD());
    } else if constexpr (kLlt) {
      return Inertia{0, 0, static_cast<int>(A_.rows())};
    } else {
      return std::nullopt;
    }
  }
  // Factorises a copy of A0. Returns false when the numeric factorisation fails.
  bool factorize(const SparseMatrix& A0) {
    A_ = A0;
    return factorize();
  }
  // The matrix the next factorize() reads: a caller may assemble into it (no copy).
  SparseMatrix& matrix() { return A_; }
  // Factorises matrix(). Returns false when the numeric factorisation fails (the next call then
  // analyses the pattern afresh).
  bool factorize() {
    A_.makeCompressed();
    if (!pattern_.same_or_remember(A_)) {
      solver_.analyzePattern(A_);
      ++symbolic_;
      if (solver_.info() != Eigen::Success) {  // no factorisation on a failed analysis
        pattern_.forget();
        ok_ = false;
        status_ = FactorStatus::TooLarge;
        return false;
      }
    }
    solver_.factorize(A_);
    ++numeric_;
    ok_ = solver_.info() == Eigen::Success;
    if (!ok_) {
      pattern_.forget();
      status_ = kLlt ? FactorStatus::NotPositiveDefinite : FactorStatus::Singular;
      return false;
    }
    status_ = FactorStatus::Succeeded;
    if constexpr (kLdlt) {
      if (count_inertia(solver_.vectorD()).zero > 0) status_ = FactorStatus::Singular;
    }
    return true;
  }
  const Solver& solver() const { return solver_; }
  Solver& solver() { return solver_; }  // (its solve options; the factor stays as it is)
  Eigen::Index rows() const override { return A_.rows(); }
  // Symbolic analyses and numeric factorisations so far.
  long symbolic_analyses() const { return symbolic_; }
  long factorizations() const { return numeric_; }

 private:
  SparseMatrix A_;
  Solver solver_;
  PatternMemory pattern_;
  long symbolic_ = 0, numeric_ = 0;
  bool ok_ = false;
  FactorStatus status_ = FactorStatus::Singular;
};
using LdltFactor = PatternFactor<Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>>>;
using LuFactor = PatternFactor<Eigen::UmfPackLU<SparseMatrix>>;
// CHOLMOD's supernodal LL^T of a lower triangle, silent: an indefinite matrix is an outcome for its
// callers (the path's symmetric tangent, the stability analysis' proof of positive definiteness).
class LltFactor : public PatternFactor<Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>> {
 public:
  LltFactor() { solver().cholmod().print = 0; }
};

}  // namespace beamfea
