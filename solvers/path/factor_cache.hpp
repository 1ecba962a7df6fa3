#pragma once
// The factor cache of a path: the mutable half of the bordered equilibrium system (the immutable
// half is PathSystem, solvers/path/equilibrium.hpp). It owns the evaluation of the last converged
// state asked for, the factorisation of that state's tangent system and its tangent direction, so
// that the predictor of the next step, the chord iterations (solvers/path/corrector.hpp), the
// stability analysis, the frequencies and the record of the step share one assembly and one
// factorisation per converged state. Its methods take the system whose states they are given; the
// key of what is kept is the state alone (a cache serves one system's numbering).
//
// The symmetric tangent. Above kSymmetricTangentMinDofs free coordinates, where the tangent system
// is the tangent over the free coordinates alone (no slave constraints or closures, no imposed
// motion's row) and symmetric to rounding at the state (forces alone: elements/corotational_beam.hpp,
// "Symmetry"), its symmetric part is factorised by CHOLMOD's supernodal LL^T instead of UMFPACK's LU.
// That one factor then serves the tangent direction, the chord iterations and the stability
// analysis (its success proves the state stable; Lanczos on its inverse gives the lowest
// eigenvalue). Where the LL^T fails (past a critical point) or the tangent is not symmetric, the LU.
#include <Eigen/Core>

#include "solvers/nonlinear_structure.hpp"
#include "solvers/path/equilibrium.hpp"
#include "solvers/pattern_factor.hpp"

namespace beamfea {

// Free coordinates above which a symmetric tangent is factorised by LL^T (FactorCache::is_cholesky):
// the stability analysis' own size for its LL^T (kStabilityDenseLimit, solvers/path/stability.hpp);
// below it UMFPACK's LU and a dense eigen-solve cost little.
inline constexpr int kSymmetricTangentMinDofs = 400;
// Largest |J - J^T| / max |J| of a tangent factorised as symmetric: rounding, and the residual's
// imbalance of internal moments at a converged state (far below this), not an applied moment's skew part.
inline constexpr double kSymmetricTangentSkew = 1e-9;

class FactorCache {
 public:
  // The evaluation at a converged state (Delta = 0, the state's load factor, multipliers and
  // reaction): residual, tangent over gens, end forces. Computed once per state and kept while the
  // state is the last one asked for.
  const NonlinearStructure::Evaluation& evaluation_at(const PathSystem& sys, const Converged& c);
  // Factors the tangent system at a converged state (once per state) and returns its tangent
  // direction: [dDelta (nf), dmu (nc), dextra] per unit lambda (loads) or per unit control (imposed
  // motion). Empty when the tangent is singular.
  const Eigen::VectorXd& tangent(const PathSystem& sys, const Converged& c);
  // The size of the factorised tangent system at c when c is the state kept and its tangent was
  // computed and factorised successfully; -1 otherwise. No computation.
  int factor_rows(const Converged& c) const;
  // Drops what is kept (the system's rows changed: PathSystem::reselect).
  void forget() { valid_ = has_tangent_ = false; }
  // The kept factor of c is the symmetric tangent's LL^T (see above).
  bool is_cholesky(const Converged& c) const { return factor_rows(c) >= 0 && cholesky_; }
  // x = A^-1 b with the kept factor, b of its size: the LU without UMFPACK's iterative refinement
  // (each chord iteration is itself a refinement step against the true residual,
  // solvers/path/corrector.hpp), or the symmetric tangent's LL^T.
  Eigen::VectorXd solve(const Eigen::VectorXd& b);
  // x = S^-1 b with the symmetric tangent's LL^T (when is_cholesky for the kept state), b over the
  // free coordinates.
  Eigen::VectorXd solve_symmetric(const Eigen::VectorXd& b) const { return llt_.solver().solve(b); }
  // Numeric factorisations of converged states' tangent systems so far (LU or LL^T), and symbolic
  // analyses.
  long factorizations() const { return lu_.factorizations() + llt_.factorizations(); }
  long symbolic_analyses() const { return lu_.symbolic_analyses() + llt_.symbolic_analyses(); }

 private:
  LuFactor lu_;    // symbolic analysis kept along the path
  LltFactor llt_;  // the symmetric tangent's (is_cholesky), its matrix() S
  // The last converged state evaluated, its evaluation and tangent direction.
  bool valid_ = false, has_tangent_ = false;
  Converged key_;
  NonlinearStructure::Evaluation ev_;
  Eigen::VectorXd t_;
  SparseMatrix J_;          // the tangent system of the kept state
  bool cholesky_ = false;   // t_ and the factor are the symmetric tangent's LL^T's
};

// Displacement control: the slope of the controlled DOF's conjugate along the path, dlambda/du_c
// (with loads) or dR/du_c (imposed motion, R the controlled DOF's reaction), from the tangent.
// A change of its sign between two states is an extremum of the load factor (or the reaction): a
// limit point. NaN when the tangent is singular.
double conjugate_slope(const PathSystem& sys, FactorCache& factors, const Converged& c);

}  // namespace beamfea
