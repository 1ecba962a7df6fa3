#pragma once
// The iterative back end of the solver contract (solvers/linear_solver.hpp): PETSc's conjugate
// gradients (KSPCG; the reduced stiffness K_ff is symmetric positive definite once the supports,
// joints and rigid links are eliminated) preconditioned by algebraic multigrid, PETSc's own
// smoothed aggregation (PCGAMG) or hypre's BoomerAMG (PCHYPRE).
//
//   analyze(A)   nothing beyond A's size (the preconditioner's structure needs A's values)
//   compute(A)   copies A (or borrows its arrays: set_borrow_matrix) into a PETSc matrix (MATAIJ
//                on PETSC_COMM_WORLD), gives it the near null space and sets up the preconditioner once; every later solve reuses it
//   solve(b, x)  iterates from x = 0 until ||b - A x|| <= rtol ||b|| (the unpreconditioned
//                residual norm, the contract's figure) or the outcome says why not (last_solve())
//   inertia()    none: an iterative method does not factorise
//
// The near null space (set_near_null_space) is what smoothed aggregation builds its coarse
// spaces from: for a frame, the six rigid-body modes of every node restricted to the free DOFs
// (solvers/near_null_space.hpp). Without it GAMG assumes the constant vector, which is the null
// space of a scalar Laplacian, not of a beam.
//
// One process or many. PETSC_COMM_WORLD is this process alone unless the program started PETSc on
// all its MPI processes (initialize_petsc_on_all_processes: `beamfea run` under mpirun). Then
// every process holds the same b and near null space (the model is replicated), and A's columns
// of its own rows at least (a distributed assembly makes no others: set_owned_columns_only), and
// the solver distributes them: each process owns a contiguous block of A's rows
// (petsc_process_rows), inserts only those rows into a MATMPIAIJ and the same rows of b and of the
// near null space, and every process gets the whole answer x back (a gather to all), so that what
// follows a solve stays replicated. b need only be right in this process's rows. Every call is collective: all
// processes must make the same calls in the same order, which they do when they run the same
// analyses of the same model.
//
// PETSc is initialised the first time a PetscSolver is made (ensure_petsc_initialized), with its
// signal handlers off, and finalised by the program at exit (finalize_petsc, in cli/ and in the
// Python module). PETSc is not thread-safe: the calls of all PetscSolvers of a process take one
// lock, so that a sweep's worker threads may each hold one.
#include <memory>
#include <mutex>
#include <string>

#include "solvers/linear_solver.hpp"

namespace beamfea {

struct IterativeOptions {
  enum class Preconditioner { Gamg, Hypre };
  double rtol = 1e-10;          // relative residual ||b - A x|| / ||b|| a solve must reach
  int max_iterations = 10000;   // iterations of one solve (each restart counts its own)
  Preconditioner preconditioner = Preconditioner::Gamg;
  void validate() const;
};

// How the last solve ended.
struct IterativeSolveReport {
  enum class Outcome {
    Converged,       // reached rtol
    MaxIterations,   // stopped at max_iterations above rtol
    Breakdown,       // CG found the operator or the preconditioner indefinite or singular (a
                     // direction of zero or negative energy), or a non-finite residual
    PreconditionerFailed,  // the multigrid set-up or application failed (a zero pivot)
  };
  Outcome outcome = Outcome::Converged;
  int iterations = 0;             // of the last solve (summed over its restarts)
  std::string reason;             // PETSc's converged reason, e.g. "DIVERGED_INDEFINITE_MAT"
  bool converged() const { return outcome == Outcome::Converged; }
};

// Whether this build has the iterative back end (BEAMFEA_WITH_PETSC).
bool petsc_available();
// Whether this PETSc has hypre's BoomerAMG (Debian's has).
bool petsc_has_hypre();
// beamfea's defaults for a BoomerAMG whose options carry `prefix` ("" for the linear solver's,
// "st_" for SLEPc's shift-and-invert), set in PETSc's options database where the user's
// PETSC_OPTIONS did not set them: aggressive coarsening on the first level (agg_nl 1). Call
// before the PC reads its options.
void set_boomeramg_defaults(const std::string& prefix);
// PETSc's one-time initialisation, idempotent and thread-safe: after MPI_Init where the program
// made one (a sweep under mpirun), else PETSc starts MPI itself. Its signal handlers are off
// (-no_signal_handler), so that Ctrl-C reaches the program's. Throws Error when unavailable.
void ensure_petsc_initialized();
// PETSc's initialisation over all the processes of the program's MPI (MPI_COMM_WORLD), so that
// every PetscSolver distributes its system over them; collective: every process calls it, after
// MPI_Init and before any other PETSc call. For a program that runs one model on many processes
// (`beamfea run` under mpirun); a sweep's processes solve cases of their own and keep
// ensure_petsc_initialized's one-process world.
void initialize_petsc_on_all_processes();
// The number of processes PETSc's solves run on (1 unless initialize_petsc_on_all_processes ran
// on several).
int petsc_processes();
// The rows of an n x n system that this process owns in a PetscSolver's distributed solve: PETSc's
// split of the n rows, in whole blocks of `block_size` when n is a multiple of it (n / size
// blocks, one more on the first n % size processes); all n on one process. A caller may assemble
// only these columns of a symmetric A (PetscSolver::set_owned_columns_only).
struct ProcessRows {
  Eigen::Index first = 0, count = 0;
  bool contains(Eigen::Index i) const { return i >= first && i < first + count; }
};
ProcessRows petsc_process_rows(Eigen::Index n, int block_size);
// The sum of `x` over PETSc's processes (collective; `x` itself on one process).
double sum_over_petsc_processes(double x);
// PetscFinalize where ensure_petsc_initialized ran it, once; nothing otherwise. Before
// MPI_Finalize where the program made its own MPI_Init.
void finalize_petsc();
// PETSc (and SLEPc) are not thread-safe: every call into them in this process, the iterative
// linear solves and the SLEPc eigen-solvers alike, takes this one lock.
std::mutex& petsc_lock();

class PetscSolver final : public LinearSolver {
 public:
  explicit PetscSolver(const IterativeOptions& options = {});
  ~PetscSolver() override;
  PetscSolver(const PetscSolver&) = delete;
  PetscSolver& operator=(const PetscSolver&) = delete;

  // The near null space of the next compute(): orthonormal columns (rows: A's size); an empty
  // matrix: none (GAMG then assumes the constant vector).
  void set_near_null_space(const Eigen::MatrixXd& modes);
  // The block size of the next compute(): 6 where the rows come in whole nodes
  // (solvers/near_null_space.hpp's node_block_size), for multigrid to aggregate nodes; 1: none.
  void set_block_size(int block_size) { block_size_ = block_size; }
  // On one process, let the next compute(A) use A's arrays instead of copying them (a gigabyte
  // less at 2e6 DOFs): A, compressed, must then stay alive and unchanged until the solver is
  // destroyed or computes again. Under MPI the rows are copied as always.
  void set_borrow_matrix(bool borrow) { borrow_ = borrow; }
  // Tells the solver that the A of the next compute() holds only this process's columns
  // (petsc_process_rows with its block size; the others empty), as a distributed assembly makes
  // it: a process reads only those anyway. What a caller computes from A itself (the residual:
  // solvers/solver_choice.hpp) must then be summed over the processes.
  void set_owned_columns_only(bool only) { owned_columns_only_ = only; }
  bool owned_columns_only() const { return owned_columns_only_; }
  // This process's rows of the last compute()'s system.
  ProcessRows process_rows() const { return rows_; }

  void analyze(const Sparse& A) override;
  // Sets up the preconditioner of A (A square, symmetric, both triangles stored). Singular when
  // A has a zero or negative diagonal entry or the preconditioner's set-up fails.
  FactorStatus compute(const Sparse& A) override;
  FactorStatus status() const override { return status_; }
  bool usable() const override { return status_ == FactorStatus::Succeeded; }
  void solve(Eigen::Ref<const Vector> b, Eigen::Ref<Vector> x) const override;
  void solve(const Matrix& B, Matrix& X) const override;
  std::optional<Inertia> inertia() const override { return std::nullopt; }
  Eigen::Index rows() const override { return n_; }

  // Continues the last solve from x (not zero) for b: one restart of CG, which corrects the
  // drift of its recursive residual from the true one.
  void refine(Eigen::Ref<const Vector> b, Eigen::Ref<Vector> x) const;
  const IterativeSolveReport& last_solve() const { return last_; }
  const IterativeOptions& options() const { return options_; }

 private:
  struct Impl;
  void iterate(Eigen::Ref<const Vector> b, Eigen::Ref<Vector> x, bool from_x) const;

  IterativeOptions options_;
  std::unique_ptr<Impl> impl_;
  Eigen::MatrixXd near_null_;
  int block_size_ = 1;
  bool borrow_ = false;
  bool owned_columns_only_ = false;
  ProcessRows rows_;
  Eigen::Index n_ = 0;
  FactorStatus status_ = FactorStatus::Singular;
  mutable IterativeSolveReport last_;
};

}  // namespace beamfea
