#pragma once
// The top-level "solver" of a model (core/model.hpp, SolverChoice) turned into a back end: the
// direct sparse factorisation (solvers/sparse_factor.hpp) or PETSc's preconditioned conjugate
// gradients (solvers/petsc_solver.hpp), and what a solve reports (results.json's
// analyses.<id>.solver; docs/analyses/solver.md).
#include <string>

#include "core/model.hpp"
#include "solvers/petsc_solver.hpp"

namespace beamfea {

// "auto" solves iteratively from this many free DOFs, directly below. Measured on the generated
// cube frames of bench_frame_solve (docs/analyses/solver.md, "auto"): from about 2e4 free DOFs CG
// with hypre's BoomerAMG is faster than CHOLMOD's factorisation and solve of one load case, 5x at
// 1e5; below 1e5 the direct solve takes seconds at most, its factor fits comfortably in memory,
// it serves many load cases and the six solves of a node's stiffness at one factorisation, and it
// diagnoses a mechanism whatever the loads and estimates the conditioning.
inline constexpr int kAutoIterativeMinDofs = 100'000;

// The preconditioner that runs: Default resolved to hypre's BoomerAMG where this PETSc has it,
// GAMG otherwise.
SolverChoice::Preconditioner resolve_preconditioner(SolverChoice::Preconditioner p);

// Whether `choice` solves a system of `free_dofs` unknowns iteratively (a build without PETSc
// solves "auto" directly; "iterative" then fails when the system is made).
bool solves_iteratively(const SolverChoice& choice, int free_dofs);

IterativeOptions iterative_options(const SolverChoice& choice);

// Which solver ran and how well: results.json's {"type", "iterations", "residual"}.
struct SolverReport {
  bool iterative = false;
  int iterations = 0;     // 1 for a direct solve; of an iterative one, the most any solve took
  double residual = 0.0;  // ||F - K u|| / ||F|| of the answer, computed with K (the largest over
                          // the solves; 0 when F = 0)
  // Takes in another solve's figures (the larger residual and iteration count).
  void add(const SolverReport& other);
};

// The relative residual ||f - K u|| / ||f|| (0 when f = 0), with r as scratch.
double relative_residual(const SparseMatrix& K, const Eigen::VectorXd& f, const Eigen::VectorXd& u, Eigen::VectorXd& r);

// One iterative solve of K u = f into u to the true relative residual: CG from zero, then up to
// kMaxRestarts restarts from its answer while ||f - K u|| / ||f|| (computed, r as scratch) is
// above rtol though CG's recursive residual reached it (their drift grows with K's condition).
// The report sums the iterations of the restarts; cg.last_solve() says how the last one ended.
// Where K holds only this process's columns (cg.owned_columns_only(): a distributed assembly), f
// is right in this process's rows only, and the residual of those rows (r: them alone) is summed
// over the processes.
inline constexpr int kMaxRestarts = 3;
SolverReport solve_to_rtol(const PetscSolver& cg, const SparseMatrix& K, const Eigen::VectorXd& f, Eigen::VectorXd& u,
                           Eigen::VectorXd& r);

// "CG with GAMG (rtol 1e-10)", for messages.
std::string describe_iterative(const IterativeOptions& options);

}  // namespace beamfea
