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
// with_control: the controlled DOF is held too.
StabilityAnalysis constrained_tangent(const PathEquilibrium& P, const Converged& c, bool with_control);

// Up to this size the lowest eigenpairs of the stability matrix are computed densely (a few
// milliseconds, and no Lanczos restarts on the clustered lowest eigenvalues of slender structures).
inline constexpr int kStabilityDenseLimit = 400;

class StabilityAnalyzer {
 public:
  // dense_limit: the size up to which the inertia is an LDL^T and the lowest eigenvalue dense;
  // above it, CHOLMOD's supernodal LL^T first (tests lower it to compare both on small models).
  explicit StabilityAnalyzer(const PathEquilibrium& eq, int dense_limit = kStabilityDenseLimit);
  StabilityAnalyzer(const StabilityAnalyzer&) = delete;
  StabilityAnalyzer& operator=(const StabilityAnalyzer&) = delete;
  // with_control: the controlled DOF is held too (displacement control). want_mode: the critical
  // mode (the eigenvector of the eigenvalue nearest zero) is returned in info.mode.
  StabilityAnalysis analyse(const Converged& c, bool with_control, bool want_mode);
  // Loaded Cartesian stiffness and compliance of a node (not ok when holding it leaves a mechanism).
  CondensedStiffness node_stiffness(const Converged& c, const StabilityAnalysis& st, int node) const;

 private:
  const PathEquilibrium& eq_;
  // The lowest eigenpair of a positive definite state from the factorisation that decided its
  // inertia (false when the Lanczos iterations did not converge: the caller falls back to a shifted
  // solve).
  // shared: the factor is the path tangent's LL^T (PathEquilibrium::tangent_is_cholesky).
  bool lowest_from_factor(const Eigen::VectorXd& sc, bool cholesky, bool shared, StabilityInfo& info);
  const int dense_limit_;
  LltFactor llt_;                   // CHOLMOD's supernodal LL^T, symbolic analysis kept
  bool last_indefinite_ = false;    // the last state had a negative eigenvalue: LDL^T directly
  LdltFactor inertia_ldlt_;         // inertia count: symbolic analysis kept along the path
  double last_min_ = 0.0;           // the last lowest eigenvalue found (the next shift's guess)
  Eigen::VectorXd last_vector_;     // its eigenvector (scaled coordinates): the next Lanczos start
  Eigen::VectorXd work_, z_;        // workspaces of the inverse operator
};

}  // namespace beamfea
