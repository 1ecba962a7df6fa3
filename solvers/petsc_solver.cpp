#include "solvers/petsc_solver.hpp"

#include <algorithm>
#include <mutex>
#include <type_traits>
#include <vector>

#include "core/errors.hpp"
#include "solvers/slepc_eigen.hpp"

#ifdef BEAMFEA_HAVE_PETSC
#include <petscksp.h>

#include "solvers/petsc_rows_matrix.hpp"
#endif

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

namespace beamfea {

void IterativeOptions::validate() const {
  if (!(rtol > 0.0 && rtol < 1.0)) throw Error("IterativeOptions: rtol must be in (0, 1)");
  if (max_iterations < 1) throw Error("IterativeOptions: max_iterations must be positive");
}

#ifdef BEAMFEA_HAVE_PETSC

static_assert(sizeof(PetscInt) == sizeof(int), "PETSc's indices must be Eigen's (Debian's PETSc: 32-bit PetscInt)");
static_assert(sizeof(PetscScalar) == sizeof(double), "the real PETSc (libpetsc-real-dev)");

// PETSc is one process-wide library without locks of its own: every call into it takes this one.
std::mutex& petsc_lock() {
  static std::mutex m;
  return m;
}

namespace {
enum class PetscState { Untouched, Initialized, Finalized };
PetscState g_state = PetscState::Untouched;  // guarded by petsc_lock()
bool g_initialized_here = false;
bool g_all_processes = false;  // PETSC_COMM_WORLD is the program's MPI_COMM_WORLD

void check(PetscErrorCode code, const char* what) {
  if (code != 0) throw Error(std::string("PETSc: ") + what + " failed (error code " + std::to_string(code) + ")");
}

// Under petsc_lock(). `all_processes`: PETSc's world is every process of the program's MPI.
void initialize_locked(bool all_processes) {
  if (g_state == PetscState::Initialized) {
    if (all_processes && !g_all_processes) throw Error("PETSc: already started on this process alone");
    return;
  }
  if (g_state == PetscState::Finalized) throw Error("PETSc: used after the program finalised it");
  PetscBool already = PETSC_FALSE;
  check(PetscInitialized(&already), "PetscInitialized");
  if (!already) {
    // PETSc's handlers of SIGINT, SIGSEGV ... would replace the program's (a sweep's Ctrl-C).
    check(PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr), "PetscOptionsSetValue");
    // Under the program's own MPI (a sweep's ranks, each solving cases of its own) PETSc's world
    // is this process alone: its initialisation is collective over that world, and the other
    // ranks may never need it. One model on many processes (all_processes) keeps MPI_COMM_WORLD.
    int mpi_started = 0;
    MPI_Initialized(&mpi_started);
    if (mpi_started && !all_processes) PETSC_COMM_WORLD = MPI_COMM_SELF;
    {
#if defined(__SANITIZE_ADDRESS__)
      // The sanitizer build's leak check ignores what MPI_Init (inside PETSc's initialisation)
      // allocates: OpenMPI opens every component it might use and closes those it does not
      // select, leaving their allocations under unloaded, unnamed modules.
      const __lsan::ScopedDisabler ignore_mpi_init;
#endif
      check(PetscInitializeNoArguments(), "PetscInitializeNoArguments");
    }
    g_initialized_here = true;
    g_all_processes = all_processes;
  }
  // Errors come back as codes (turned into outcomes or exceptions here), not printed tracebacks.
  check(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr), "PetscPushErrorHandler");
  g_state = PetscState::Initialized;
}

IterativeSolveReport::Outcome outcome_of(KSPConvergedReason reason) {
  if (reason > 0) return IterativeSolveReport::Outcome::Converged;
  if (reason == KSP_DIVERGED_ITS) return IterativeSolveReport::Outcome::MaxIterations;
  if (reason == KSP_DIVERGED_PC_FAILED) return IterativeSolveReport::Outcome::PreconditionerFailed;
  return IterativeSolveReport::Outcome::Breakdown;
}

}  // namespace

bool petsc_available() { return true; }

void set_boomeramg_defaults(const std::string& prefix) {
  // Aggressive coarsening on the first level: a beam lattice's classical coarse grids are dense
  // (operator complexity 2.3 on a 400,000-DOF cube lattice); the set-up and solve take 0.76-0.83 of
  // the default's time for one or two more CG iterations (docs/analyses/solver.md).
  const std::string name = "-" + prefix + "pc_hypre_boomeramg_agg_nl";
  PetscBool user_set = PETSC_FALSE;
  check(PetscOptionsHasName(nullptr, nullptr, name.c_str(), &user_set), "PetscOptionsHasName");
  if (!user_set) check(PetscOptionsSetValue(nullptr, name.c_str(), "1"), "PetscOptionsSetValue");
}

bool petsc_has_hypre() {
  ensure_petsc_initialized();
  const std::lock_guard<std::mutex> lock(petsc_lock());
  PetscBool has = PETSC_FALSE;
  check(PetscHasExternalPackage("hypre", &has), "PetscHasExternalPackage");
  return has == PETSC_TRUE;
}

void ensure_petsc_initialized() {
  const std::lock_guard<std::mutex> lock(petsc_lock());
  initialize_locked(false);
}

void initialize_petsc_on_all_processes() {
  const std::lock_guard<std::mutex> lock(petsc_lock());
  initialize_locked(true);
}

int petsc_processes() {
  const std::lock_guard<std::mutex> lock(petsc_lock());
  if (g_state != PetscState::Initialized) return 1;
  PetscMPIInt size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return size;
}

ProcessRows petsc_process_rows(Eigen::Index n, int block_size) {
  PetscMPIInt rank = 0, size = 1;
  {
    const std::lock_guard<std::mutex> lock(petsc_lock());
    if (g_state == PetscState::Initialized) {
      MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
      MPI_Comm_size(PETSC_COMM_WORLD, &size);
    }
  }
  // In whole blocks (nodes), so that no node straddles two processes.
  const Eigen::Index bs = block_size > 1 && n % block_size == 0 ? block_size : 1, blocks = n / bs;
  return {bs * (rank * (blocks / size) + std::min<Eigen::Index>(rank, blocks % size)),
          bs * (blocks / size + (rank < blocks % size ? 1 : 0))};
}

double sum_over_petsc_processes(double x) {
  const std::lock_guard<std::mutex> lock(petsc_lock());
  if (g_state != PetscState::Initialized) return x;
  PetscMPIInt size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size > 1) check(MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD), "MPI_Allreduce");
  return x;
}

void finalize_petsc() {
  const std::lock_guard<std::mutex> lock(petsc_lock());
  if (g_state != PetscState::Initialized) return;
  PetscPopErrorHandler();
#if defined(__SANITIZE_ADDRESS__)
  // The sanitizer build's leak check, now rather than at exit: PetscFinalize ends the MPI it
  // started, and MPI_Finalize unloads OpenMPI's components, whose allocations kept until exit
  // would then be reported from unnamed modules that no suppression can match. Here they are
  // still loaded (tests/fuzz/lsan.supp names them); what the program itself leaked is reported
  // all the same, and the check does not run again at exit.
  if (g_initialized_here) __lsan_do_leak_check();
#endif
  finalize_slepc();  // SLEPc first: it runs on this PETSc
  if (g_initialized_here) PetscFinalize();
  g_state = PetscState::Finalized;
}

struct PetscSolver::Impl {
  Mat A = nullptr;
  KSP ksp = nullptr;
  Vec b = nullptr, x = nullptr;  // this process's rows (PetscSolver::rows_) of b and x
  // On several processes: the whole x on every one (x_all), gathered by to_all after each solve.
  Vec x_all = nullptr;
  VecScatter to_all = nullptr;
  void destroy() {
    // After the program finalised PETSc (an object kept in a cache past main's end) the process
    // is exiting: its memory goes with it.
    if (g_state != PetscState::Initialized) return;
    VecScatterDestroy(&to_all);
    VecDestroy(&x_all);
    VecDestroy(&b);
    VecDestroy(&x);
    KSPDestroy(&ksp);
    MatDestroy(&A);
  }
};

PetscSolver::PetscSolver(const IterativeOptions& options) : options_(options), impl_(std::make_unique<Impl>()) {
  options_.validate();
  ensure_petsc_initialized();
}

PetscSolver::~PetscSolver() {
  const std::lock_guard<std::mutex> lock(petsc_lock());
  impl_->destroy();
}

void PetscSolver::set_near_null_space(const Eigen::MatrixXd& modes) { near_null_ = modes; }

void PetscSolver::analyze(const Sparse& A) {
  if (A.rows() != A.cols()) throw Error("PetscSolver: the matrix must be square");
  n_ = A.rows();
}

FactorStatus PetscSolver::compute(const Sparse& A_in) {
  analyze(A_in);
  if (near_null_.size() > 0 && near_null_.rows() != n_) throw Error("PetscSolver: the near null space has the wrong size");
  status_ = FactorStatus::Singular;
  rows_ = petsc_process_rows(n_, block_size_);
  // A zero or negative diagonal entry: not positive definite, and no multigrid smoother can use
  // it. Each process looks at its own rows; all take the same way out.
  int bad = 0;
  for (Eigen::Index i = rows_.first; i < rows_.first + rows_.count && !bad; ++i) bad = !(A_in.coeff(i, i) > 0.0);
  if (sum_over_petsc_processes(bad) > 0.0) return status_;
  Sparse compressed;
  const Sparse* A = &A_in;
  if (!A_in.isCompressed()) {
    compressed = A_in;
    compressed.makeCompressed();
    A = &compressed;
  }
  const std::lock_guard<std::mutex> lock(petsc_lock());
  Impl& s = *impl_;
  s.destroy();
  PetscInt n = static_cast<PetscInt>(n_);
  PetscMPIInt size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  const PetscInt bs = block_size_ > 1 && n % block_size_ == 0 ? block_size_ : 1;
  if (borrow_ && size == 1 && A == &A_in) {
    // PETSc's matrix on A's own arrays (PetscInt is A's index type: Debian's PETSc has 32-bit
    // indices; A's CSC arrays are the CSR arrays of A^T = A): no copy, as set_borrow_matrix says.
    // PETSc writes nothing into them.
    static_assert(std::is_same_v<PetscInt, Sparse::StorageIndex>);
    check(MatCreateSeqAIJWithArrays(PETSC_COMM_WORLD, n, n, const_cast<PetscInt*>(A->outerIndexPtr()),
                                    const_cast<PetscInt*>(A->innerIndexPtr()), const_cast<PetscScalar*>(A->valuePtr()),
                                    &s.A),
          "MatCreateSeqAIJWithArrays");
    if (bs > 1) check(MatSetBlockSize(s.A, bs), "MatSetBlockSize");
    check(MatSetOption(s.A, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  } else {
    symmetric_rows_aij(PETSC_COMM_WORLD, *A, rows_, bs, check, s.A);
  }
  check(MatSetOption(s.A, MAT_SPD, PETSC_TRUE), "MatSetOption");
  check(MatCreateVecs(s.A, &s.x, &s.b), "MatCreateVecs");
  if (near_null_.cols() > 0) {
    std::vector<Vec> modes(static_cast<std::size_t>(near_null_.cols()));
    for (std::size_t k = 0; k < modes.size(); ++k) {
      check(VecDuplicate(s.x, &modes[k]), "VecDuplicate");
      PetscScalar* v = nullptr;
      check(VecGetArrayWrite(modes[k], &v), "VecGetArrayWrite");
      std::copy_n(near_null_.col(static_cast<Eigen::Index>(k)).data() + rows_.first, rows_.count, v);
      check(VecRestoreArrayWrite(modes[k], &v), "VecRestoreArrayWrite");
    }
    MatNullSpace space = nullptr;
    check(MatNullSpaceCreate(PETSC_COMM_WORLD, PETSC_FALSE, static_cast<PetscInt>(modes.size()), modes.data(), &space),
          "MatNullSpaceCreate");
    check(MatSetNearNullSpace(s.A, space), "MatSetNearNullSpace");
    MatNullSpaceDestroy(&space);
    for (Vec& v : modes) VecDestroy(&v);
  }
  if (size > 1) check(VecScatterCreateToAll(s.x, &s.to_all, &s.x_all), "VecScatterCreateToAll");
  check(KSPCreate(PETSC_COMM_WORLD, &s.ksp), "KSPCreate");
  check(KSPSetOperators(s.ksp, s.A, s.A), "KSPSetOperators");
  check(KSPSetType(s.ksp, KSPCG), "KSPSetType");
  // The true (unpreconditioned) residual is what rtol bounds: ||b - A x|| <= rtol ||b||.
  check(KSPSetNormType(s.ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
  check(KSPSetTolerances(s.ksp, options_.rtol, 0.0, PETSC_DEFAULT, options_.max_iterations), "KSPSetTolerances");
  PC pc = nullptr;
  check(KSPGetPC(s.ksp, &pc), "KSPGetPC");
  if (options_.preconditioner == IterativeOptions::Preconditioner::Hypre) {
    PetscBool has = PETSC_FALSE;
    check(PetscHasExternalPackage("hypre", &has), "PetscHasExternalPackage");
    if (!has) throw Error("solver: this PETSc was built without hypre (preconditioner \"hypre\"); use \"gamg\"");
    check(PCSetType(pc, PCHYPRE), "PCSetType");
    check(PCHYPRESetType(pc, "boomeramg"), "PCHYPRESetType");
    set_boomeramg_defaults("");
  } else {
    check(PCSetType(pc, PCGAMG), "PCSetType");
  }
  // The user's PETSC_OPTIONS may tune what is above (e.g. -pc_gamg_threshold).
  check(KSPSetFromOptions(s.ksp), "KSPSetFromOptions");
  int failed = KSPSetUp(s.ksp) != 0 ? 1 : 0;
  PCFailedReason reason = PC_NOERROR;
  if (!failed) check(PCGetFailedReason(pc, &reason), "PCGetFailedReason");
  failed = failed || reason != PC_NOERROR;
  // One outcome on every process: what follows (the mechanism's diagnosis, or the solves) is
  // collective or replicated.
  if (size > 1) check(MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD), "MPI_Allreduce");
  if (failed) return status_;
  status_ = FactorStatus::Succeeded;
  return status_;
}

void PetscSolver::iterate(Eigen::Ref<const Vector> b, Eigen::Ref<Vector> x, bool from_x) const {
  if (!usable()) throw Error("PetscSolver: solve before a successful compute");
  if (b.size() != n_ || x.size() != n_) throw Error("PetscSolver: right-hand side of the wrong size");
  last_ = {};
  if (!from_x && b.isZero(0.0)) {  // x = 0 exactly: PETSc would divide by ||b|| = 0
    x.setZero();
    last_.reason = "CONVERGED_ATOL";
    return;
  }
  const std::lock_guard<std::mutex> lock(petsc_lock());
  const Impl& s = *impl_;
  PetscScalar* v = nullptr;
  check(VecGetArrayWrite(s.b, &v), "VecGetArrayWrite");
  std::copy_n(b.data() + rows_.first, rows_.count, v);
  check(VecRestoreArrayWrite(s.b, &v), "VecRestoreArrayWrite");
  if (from_x) {
    check(VecGetArrayWrite(s.x, &v), "VecGetArrayWrite");
    std::copy_n(x.data() + rows_.first, rows_.count, v);
    check(VecRestoreArrayWrite(s.x, &v), "VecRestoreArrayWrite");
  }
  check(KSPSetInitialGuessNonzero(s.ksp, from_x ? PETSC_TRUE : PETSC_FALSE), "KSPSetInitialGuessNonzero");
  PetscErrorCode code = KSPSolve(s.ksp, s.b, s.x);
  if (s.to_all) {  // one outcome on every process, and the whole answer on each
    check(MPI_Allreduce(MPI_IN_PLACE, &code, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD), "MPI_Allreduce");
    check(VecScatterBegin(s.to_all, s.x, s.x_all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
    check(VecScatterEnd(s.to_all, s.x, s.x_all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  }
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
  PetscInt its = 0;
  check(KSPGetConvergedReason(s.ksp, &reason), "KSPGetConvergedReason");
  check(KSPGetIterationNumber(s.ksp, &its), "KSPGetIterationNumber");
  last_.iterations = static_cast<int>(its);
  if (code != 0) {
    last_.outcome = IterativeSolveReport::Outcome::PreconditionerFailed;
    last_.reason = "error " + std::to_string(code);
  } else {
    last_.outcome = outcome_of(reason);
    last_.reason = KSPConvergedReasons[reason];
  }
  const Vec whole = s.to_all ? s.x_all : s.x;
  const PetscScalar* r = nullptr;
  check(VecGetArrayRead(whole, &r), "VecGetArrayRead");
  std::copy_n(r, n_, x.data());
  check(VecRestoreArrayRead(whole, &r), "VecRestoreArrayRead");
}

void PetscSolver::solve(Eigen::Ref<const Vector> b, Eigen::Ref<Vector> x) const { iterate(b, x, false); }

void PetscSolver::refine(Eigen::Ref<const Vector> b, Eigen::Ref<Vector> x) const { iterate(b, x, true); }

void PetscSolver::solve(const Matrix& B, Matrix& X) const {
  X.resize(B.rows(), B.cols());
  IterativeSolveReport worst;
  for (Eigen::Index j = 0; j < B.cols(); ++j) {
    iterate(B.col(j), X.col(j), false);
    worst.iterations = std::max(worst.iterations, last_.iterations);
    if (!last_.converged() && worst.converged()) {
      worst.outcome = last_.outcome;
      worst.reason = last_.reason;
    }
  }
  last_ = worst;
}

#else  // built without PETSc (-DBEAMFEA_WITH_PETSC=OFF)

namespace {
[[noreturn]] void unavailable() {
  throw Error("solver: the iterative solver needs PETSc; this beamfea was built without it "
              "(install libpetsc-real-dev and configure with -DBEAMFEA_WITH_PETSC=ON)");
}
}  // namespace

bool petsc_available() { return false; }
bool petsc_has_hypre() { return false; }
void set_boomeramg_defaults(const std::string&) {}
void ensure_petsc_initialized() { unavailable(); }
void initialize_petsc_on_all_processes() { unavailable(); }
int petsc_processes() { return 1; }
ProcessRows petsc_process_rows(Eigen::Index n, int) { return {0, n}; }
double sum_over_petsc_processes(double x) { return x; }
void finalize_petsc() {}
std::mutex& petsc_lock() {
  static std::mutex m;
  return m;
}

struct PetscSolver::Impl {};
PetscSolver::PetscSolver(const IterativeOptions& options) : options_(options) { unavailable(); }
PetscSolver::~PetscSolver() = default;
void PetscSolver::set_near_null_space(const Eigen::MatrixXd& modes) { near_null_ = modes; }
void PetscSolver::analyze(const Sparse&) { unavailable(); }
FactorStatus PetscSolver::compute(const Sparse&) { unavailable(); }
void PetscSolver::iterate(Eigen::Ref<const Vector>, Eigen::Ref<Vector>, bool) const { unavailable(); }
void PetscSolver::solve(Eigen::Ref<const Vector>, Eigen::Ref<Vector>) const { unavailable(); }
void PetscSolver::refine(Eigen::Ref<const Vector>, Eigen::Ref<Vector>) const { unavailable(); }
void PetscSolver::solve(const Matrix&, Matrix&) const { unavailable(); }

#endif

}  // namespace beamfea
