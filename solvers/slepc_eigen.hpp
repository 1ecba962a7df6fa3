#pragma once
// The iterative eigen-solvers of the modal and buckling analyses: SLEPc's EPS (Hernandez, Roman &
// Vidal 2005, "SLEPc: a scalable and flexible toolkit for the solution of eigenvalue problems",
// ACM TOMS 31, 351-362) on PETSc matrices copied from Eigen's, for models beyond one direct
// factorisation.
//
// Vibration, K phi = lambda M phi (M semi-definite): Krylov-Schur (Stewart 2001, SIAM J. Matrix
// Anal. Appl. 23, 601-614) with shift-and-invert about `target` (the same spectral transformation
// as solvers/generalized_eigen.hpp: theta = 1/(lambda - sigma), the eigenvalues nearest sigma
// first; Ericsson & Ruhe 1980), M-inner products and purification of the vectors (SLEPc's
// default for a generalised Hermitian problem, EPS_GHEP).
// Buckling, (K + lambda K_g) phi = 0 with K positive definite and K_g indefinite: the pencil
// (-K_g) phi = mu K phi, mu = 1/lambda, as a generalised Hermitian problem with B = K (SPD), its
// largest mu (the lowest positive load factors; negative mu are tension buckling and are dropped
// as on the direct path). SLEPc's ST "shift" applies K^{-1}: one linear solve per Krylov step, the
// same count as shift-and-invert.
//
// The linear solves (SLEPc's ST's KSP): PETSc's own sparse Cholesky (LU where the shifted matrix
// may be indefinite: modal about a loaded state) when the system has at most kFactorDofs DOFs, or
// conjugate gradients (GMRES when indefinite) preconditioned by algebraic multigrid (PETSc's GAMG
// or hypre's BoomerAMG) to a relative residual of kInnerRtolFactor * rtol, above. The multigrid
// gets the near null space when the caller gives `rigid_body_modes` (columns on the same free
// DOFs as K: the six rigid-body motions of the structure restricted to them).
//
// SLEPc is initialised on first use (SlepcInitializeNoArguments, with PETSc's signal handler off:
// the program owns signals); finalising is the program's business.
#include <string>

#include "core/dof_map.hpp"
#include "core/model.hpp"

namespace beamfea {

// How the eigen-solve of an analysis ran: under analyses.<id>.solver in the results.
// iterations: 1 for the direct solver; for SLEPc the outer (Krylov-Schur restart) iterations,
// with the total inner linear iterations in linear_iterations (0 when PETSc factorised).
// residual: the largest relative residual over the returned pairs, computed from the vectors
// (solvers/modal.hpp and solvers/buckling.hpp say which).
struct EigenSolverReport {
  bool iterative = false;
  int iterations = 1;
  long long linear_iterations = 0;
  double residual = 0.0;
};

// Auto uses SLEPc at or above this many free DOFs (docs/performance.md: CHOLMOD's shift-invert
// Lanczos is faster on one core below it, and its factor still fits in memory).
inline constexpr int kIterativeEigenDofs = 1'000'000;

// True when SLEPc is built in (BEAMFEA_WITH_SLEPC).
bool slepc_available();
// SlepcFinalize where SLEPc was initialised; called by finalize_petsc (solvers/petsc_solver.hpp)
// under petsc_lock(), before PETSc's own finalisation. Nothing otherwise.
void finalize_slepc();

// Whether an eigen-analysis of `free_dofs` unknowns runs on SLEPc under the model's "solver":
// iterative always (an Error when SLEPc is not built in), direct never, auto at or above
// kIterativeEigenDofs when SLEPc is built in.
bool eigen_solver_iterative(const SolverChoice& choice, Eigen::Index free_dofs);

struct SlepcEigenOptions {
  enum class Linear { Auto, Factor, Multigrid };
  int count = 10;                // eigenpairs wanted
  double target = 0.0;           // vibration: the shift sigma (below the spectrum of interest)
  bool indefinite = false;       // vibration: K - sigma M may be indefinite (a preload)
  double rtol = 1e-10;           // SLEPc's relative eigen-residual tolerance
  int max_linear_iterations = 10000;  // per linear solve
  SolverChoice::Preconditioner preconditioner = SolverChoice::Preconditioner::Gamg;
  Linear linear = Linear::Auto;  // Auto: Factor up to kFactorDofs, Multigrid above
  void validate() const;
};

// Factor the ST's linear systems (PETSc's Cholesky or LU) up to this many DOFs under Linear::Auto.
inline constexpr int kFactorDofs = 20'000;

struct SlepcEigenPairs {
  Eigen::VectorXd values;   // ascending: omega^2 (vibration) or load factors (buckling, positive)
  Eigen::MatrixXd vectors;  // columns; vibration: phi^T M phi = 1; buckling: unit norm
  bool converged = false;
  std::string message;      // why not, with the residual reached
  int iterations = 0;                // outer iterations
  long long linear_iterations = 0;   // total inner Krylov iterations (0 when factorised)
};

// The options of an eigen-solve from the model's "solver" choice.
SlepcEigenOptions slepc_options(const SolverChoice& choice, int count);

// The `options.count` eigenpairs of K phi = lambda M phi nearest options.target.
SlepcEigenPairs slepc_vibration_pairs(const SparseMatrix& K, const SparseMatrix& M, const SlepcEigenOptions& options,
                                      const Eigen::MatrixXd* rigid_body_modes = nullptr);

// The lowest `options.count` positive load factors of (K + lambda K_g) phi = 0, given KG = -K_g.
SlepcEigenPairs slepc_buckling_pairs(const SparseMatrix& K, const SparseMatrix& KG, const SlepcEigenOptions& options,
                                     const Eigen::MatrixXd* rigid_body_modes = nullptr);

// max_k ||A x_k - lambda_k B x_k|| / max(||A x_k||, kZeroActionRelative ||D_A x_k||), D_A = |diag A|:
// the relative eigen-residual of the pairs (columns of X). The floor stands in for ||A x_k|| where
// it is zero to round-off (a rigid-body or mechanism mode of zero frequency), whose 0/0 says nothing.
inline constexpr double kZeroActionRelative = 1e-10;  // ModalOptions::zero_tolerance's scale
double relative_eigen_residual(const SparseMatrix& A, const SparseMatrix& B, const Eigen::VectorXd& lambda,
                               const Eigen::MatrixXd& X);

}  // namespace beamfea
