#pragma once
// Stability of a converged path state (the FEA form of Pashkevich et al. 2010, eqs. 18-23), and
// the loaded Cartesian stiffness of a node (their eq. 28).
//
// The tangent over the free coordinates is restricted to the null space Z of the constraint
// Jacobian (eqs. 19-21; Z by exact elimination), symmetrised, and its inertia counted by a sparse
// LDL^T (Sylvester's law of inertia): stable when it has no negative eigenvalue (eq. 23: the second
// variation of the energy is positive on all admissible variations). Above kStabilityDenseLimit a
// CHOLMOD supernodal LL^T is tried first: its success proves positive definiteness (no negative
// eigenvalue; Golub & Van Loan 2013, sec. 4.2), and the LDL^T counts the negative pivots only when
// it fails (or when the last state had some). min_eigenvalue is the lowest eigenvalue of the
// Jacobi-scaled matrix (dimensionless). A stable state's comes from the factorisation that proved it
// stable (Lanczos on the inverse, started from the last state's eigenvector): one factorisation per
// state; past a critical point (negative eigenvalues) a shifted solve finds it. The loaded Cartesian stiffness of a node
// is the condensed tangent [ K_t  T_n^T ; T_n  0 ] [X; M] = [0; I],  K_c = -M, on the directions the
// node can move (node_compliance, solvers/condensed_stiffness.hpp): any node, held or restricted by
// supports, closed loops or the controlled DOF, gets its compliance (zero where it cannot move),
// rigid directions and free directions.
#include <Eigen/Core>
#include <optional>

#include "solvers/condensed_stiffness.hpp"
#include "solvers/path/equilibrium.hpp"
#include "solvers/path/factor_cache.hpp"
#include "solvers/pattern_factor.hpp"

namespace beamfea {

// Stability of a state: inertia and lowest eigenvalue of the constrained symmetrised tangent.
struct StabilityInfo {
  int negative = 0;                 // -1 when the LDL^T failed
  double min_eigenvalue = 0.0;
  Eigen::VectorXd mode;             // over the free independent coordinates (Z applied), when asked
};

struct StabilityAnalysis {
  StabilityInfo info;
  SparseMatrix Z;                   // null-space basis of the constraint rows
  SparseMatrix K;                   // Z^T K_ff Z (not symmetrised)
  Eigen::VectorXd p;                // Z^T p_free
};

// Null-space basis Z (n x (n - rank)) of C by Gauss-Jordan elimination with full pivoting.
SparseMatrix null_space(const Eigen::MatrixXd& C, int n);

// The converged tangent restricted to the admissible variations (eqs. 19-21): Z, Z^T K_ff Z (not
// symmetrised) and Z^T p_free, at the state's load factor (closures' multipliers included). What
// the stability analysis and the frequencies along a path (solvers/path/vibration.hpp) work on.
// control: whether the controlled DOF is held too. The tangent is the evaluation `factors` keeps.
StabilityAnalysis constrained_tangent(const PathSystem& sys, FactorCache& factors, const Converged& c,
                                      ControlDof control);

// Up to this size the lowest eigenpairs of the stability matrix are computed densely (a few
// milliseconds, and no Lanczos restarts on the clustered lowest eigenvalues of slender structures).
inline constexpr int kStabilityDenseLimit = 400;

// What a stability analysis is asked: whether the controlled DOF is held too (displacement control),
// and whether the critical mode (the eigenvector of the eigenvalue nearest zero) is wanted in
// info.mode.
enum class CriticalMode { NotWanted, Wanted };
struct StabilityRequest {
  ControlDof control = ControlDof::Free;
  CriticalMode mode = CriticalMode::NotWanted;
};

class StabilityAnalyzer {
 public:
  // dense_limit: the size up to which the inertia is an LDL^T and the lowest eigenvalue dense;
  // above it, CHOLMOD's supernodal LL^T first (tests lower it to compare both on small models).
  // factors: the path's factor cache, whose LL^T of the tangent it shares where it can.
  StabilityAnalyzer(const PathSystem& sys, FactorCache& factors, int dense_limit = kStabilityDenseLimit);
  StabilityAnalyzer(const StabilityAnalyzer&) = delete;
  StabilityAnalyzer& operator=(const StabilityAnalyzer&) = delete;
  StabilityAnalysis analyse(const Converged& c, const StabilityRequest& request = {});
  // Loaded Cartesian stiffness and compliance of a node (not ok when holding it leaves a mechanism).
  CondensedStiffness node_stiffness(const Converged& c, const StabilityAnalysis& st, int node) const;

 private:
  // The factorisation that decided a state's inertia: the path tangent's LL^T (FactorCache::
  // is_cholesky), this analyser's own LL^T, or its LDL^T.
  enum class InertiaFactor { SharedLlt, OwnLlt, Ldlt };
  // The lowest eigenvalue of a state with `negative` negative eigenvalues from the factorisation
  // that decided its inertia (none when the Lanczos iterations did not converge or disagree with the
  // inertia: the caller falls back to a shifted solve).
  std::optional<double> lowest_from_factor(const Eigen::VectorXd& sc, InertiaFactor factor, int negative);
  const PathSystem& sys_;
  FactorCache& factors_;
  const int dense_limit_;
  LltFactor llt_;                   // CHOLMOD's supernodal LL^T, symbolic analysis kept
  bool last_indefinite_ = false;    // the last state had a negative eigenvalue: LDL^T directly
  LdltFactor inertia_ldlt_;         // inertia count: symbolic analysis kept along the path
  double last_min_ = 0.0;           // the last lowest eigenvalue found (the next shift's guess)
  Eigen::VectorXd last_vector_;     // its eigenvector (scaled coordinates): the next Lanczos start
  Eigen::VectorXd work_, z_;        // workspaces of the inverse operator
};

}  // namespace beamfea
