#pragma once
// A sparse factorisation whose symbolic analysis is kept while the sparsity pattern does not change
// (KINSOL's Newton LU, the path's tangent LU or LL^T and its inertia LDL^T refactor the same pattern at
// every iteration or step), with counts of the symbolic analyses and numeric factorisations.
#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <Eigen/UmfPackSupport>

#include "solvers/sparse_factor.hpp"

namespace beamfea {

template <class Solver>
class PatternFactor {
 public:
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
        return false;
      }
    }
    solver_.factorize(A_);
    ++numeric_;
    if (solver_.info() != Eigen::Success) {
      pattern_.forget();
      return false;
    }
    return true;
  }
  const Solver& solver() const { return solver_; }
  Solver& solver() { return solver_; }  // (its solve options; the factor stays as it is)
  Eigen::Index rows() const { return A_.rows(); }
  // Symbolic analyses and numeric factorisations so far.
  long symbolic_analyses() const { return symbolic_; }
  long factorizations() const { return numeric_; }

 private:
  SparseMatrix A_;
  Solver solver_;
  PatternMemory pattern_;
  long symbolic_ = 0, numeric_ = 0;
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
