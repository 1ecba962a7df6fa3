#include "solvers/slepc_eigen.hpp"

#include <fmt/format.h>

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <vector>

#include "core/errors.hpp"
#include "solvers/blas_threads.hpp"
#include "solvers/petsc_solver.hpp"
#include "solvers/solver_choice.hpp"

#ifdef BEAMFEA_HAVE_SLEPC
#include <slepceps.h>

#include "solvers/petsc_rows_matrix.hpp"
#endif

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

namespace beamfea {

void SlepcEigenOptions::validate() const {
  if (count < 1) throw Error("SlepcEigenOptions: count must be at least 1");
  if (!(rtol > 0.0 && rtol < 1.0)) throw Error("SlepcEigenOptions: rtol must lie in (0, 1)");
  if (max_linear_iterations < 1) throw Error("SlepcEigenOptions: max_linear_iterations must be at least 1");
}

bool slepc_available() {
#ifdef BEAMFEA_HAVE_SLEPC
  return true;
#else
  return false;
#endif
}

bool eigen_solver_iterative(const SolverChoice& choice, Eigen::Index free_dofs) {
  switch (choice.type) {
    case SolverChoice::Type::Direct: return false;
    case SolverChoice::Type::Iterative:
      if (!slepc_available())
        throw Error("solver: type \"iterative\" needs SLEPc for the eigen-analyses, and this beamfea was built without it "
                    "(BEAMFEA_WITH_SLEPC=OFF)");
      return true;
    case SolverChoice::Type::Auto: return slepc_available() && free_dofs >= kIterativeEigenDofs;
  }
  return false;
}

SlepcEigenOptions slepc_options(const SolverChoice& choice, int count) {
  SlepcEigenOptions o;
  o.count = count;
  o.rtol = choice.rtol;
  o.max_linear_iterations = choice.max_iterations;
  o.preconditioner = resolve_preconditioner(choice.preconditioner);
  return o;
}

double relative_eigen_residual(const SparseMatrix& A, const SparseMatrix& B, const Eigen::VectorXd& lambda,
                               const Eigen::MatrixXd& X) {
  const Eigen::VectorXd d = A.diagonal().cwiseAbs();
  double worst = 0.0;
  for (Eigen::Index k = 0; k < X.cols(); ++k) {
    const Eigen::VectorXd x = X.col(k);
    const Eigen::VectorXd Ax = A * x;
    const double r = (Ax - lambda[k] * (B * x)).norm();
    const double scale = std::max(Ax.norm(), kZeroActionRelative * d.cwiseProduct(x).norm());
    if (scale > 0.0) worst = std::max(worst, r / scale);
  }
  return worst;
}

#ifdef BEAMFEA_HAVE_SLEPC

namespace {

// The inner (linear) solves run this much tighter than the eigen tolerance, so that the
// Krylov-Schur residual is not limited by inexact solves of the spectral transformation.
constexpr double kInnerRtolFactor = 1e-2;
constexpr double kMinInnerRtol = 1e-14;  // below this a double-precision residual is noise
// Buckling: a mu = 1/lambda below this fraction of the largest |mu| is no load factor (as the
// dense path of solvers/buckling.cpp).
constexpr double kPositiveMuRelative = 1e-12;

void check(PetscErrorCode ierr, const char* what) {
  if (ierr == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(ierr, &text, nullptr);
  throw Error(fmt::format("SLEPc: {} failed ({})", what, text ? text : "unknown error"));
}

// PETSc first, by the iterative back end's one initialisation (solvers/petsc_solver.hpp: its
// signal handlers off, its world this process under a sweep's MPI, errors returned as codes),
// then SLEPc on it.
bool g_slepc_initialized = false;  // guarded by petsc_lock()
void ensure_slepc() {
  ensure_petsc_initialized();
  const std::lock_guard<std::mutex> lock(petsc_lock());
  if (g_slepc_initialized) return;
  check(SlepcInitializeNoArguments(), "initialisation");
  g_slepc_initialized = true;
}

// Owners of PETSc objects (destroyed in reverse order of creation by scope).
template <class T, PetscErrorCode (*Destroy)(T*)>
struct Owned {
  T h = nullptr;
  Owned() = default;
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  ~Owned() {
    if (h) Destroy(&h);
  }
};
using OwnedMat = Owned<Mat, MatDestroy>;
using OwnedVec = Owned<Vec, VecDestroy>;
using OwnedEps = Owned<EPS, EPSDestroy>;

// Where the eigen-problem lives: this process alone, or (one model on several processes, the
// multigrid path) all of PETSc's processes, each owning a block of rows (petsc_process_rows).
struct Layout {
  MPI_Comm comm = PETSC_COMM_SELF;
  ProcessRows rows;
};

// Computed before petsc_lock() is taken (petsc_process_rows takes it). The factorised path stays
// on this process: PETSc's own Cholesky and LU are sequential, and the systems it takes are small.
Layout layout_for(Eigen::Index n, bool factor) {
  if (factor || petsc_processes() == 1) return {PETSC_COMM_SELF, {0, n}};
  return {PETSC_COMM_WORLD, petsc_process_rows(n, 1)};
}

// An AIJ copy of this process's rows of a symmetric Eigen matrix (held whole by every process): its
// CSC arrays of those columns are the CSR arrays of those rows, the matrix being its transpose.
void petsc_matrix(const SparseMatrix& A, bool spd, const Layout& at, OwnedMat& out) {
  const SparseMatrix* C = &A;
  SparseMatrix compressed;
  if (!A.isCompressed()) {
    compressed = A;
    compressed.makeCompressed();
    C = &compressed;
  }
  symmetric_rows_aij(at.comm, *C, at.rows, 1, check, out.h);
  if (spd) check(MatSetOption(out.h, MAT_SPD, PETSC_TRUE), "MatSetOption");
}

// The multigrid's near null space: the columns of Z, orthonormalised (PETSc requires it).
void attach_near_null_space(Mat P, const Eigen::MatrixXd* Z, const Layout& at) {
  if (!Z || Z->cols() == 0) return;
  PetscInt n = 0;
  check(MatGetSize(P, &n, nullptr), "MatGetSize");
  if (Z->rows() != n) throw Error("SLEPc: rigid_body_modes must have one row per free DOF");
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(*Z);
  const Eigen::Index rank = qr.rank();
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(n, rank);
  std::vector<Vec> vecs(static_cast<std::size_t>(rank), nullptr);
  PetscErrorCode ierr = 0;
  for (Eigen::Index c = 0; c < rank && !ierr; ++c) {
    Vec& v = vecs[static_cast<std::size_t>(c)];
    ierr = MatCreateVecs(P, &v, nullptr);
    PetscScalar* a = nullptr;
    if (!ierr) ierr = VecGetArray(v, &a);
    if (!ierr) std::copy_n(Q.col(c).data() + at.rows.first, at.rows.count, a);
    if (!ierr) ierr = VecRestoreArray(v, &a);
  }
  MatNullSpace ns = nullptr;
  if (!ierr) ierr = MatNullSpaceCreate(at.comm, PETSC_FALSE, static_cast<PetscInt>(rank), vecs.data(), &ns);
  if (!ierr) ierr = MatSetNearNullSpace(P, ns);
  if (ns) MatNullSpaceDestroy(&ns);
  for (Vec& v : vecs)
    if (v) VecDestroy(&v);
  check(ierr, "setting the near null space");
}

// The ST's linear solver: a factorisation, or a Krylov method with algebraic multigrid.
bool factorises(const SlepcEigenOptions& o, Eigen::Index n) {
  return o.linear == SlepcEigenOptions::Linear::Factor || (o.linear == SlepcEigenOptions::Linear::Auto && n <= kFactorDofs);
}

void configure_linear_solve(ST st, const SlepcEigenOptions& o, Eigen::Index n, bool indefinite) {
  KSP ksp = nullptr;
  PC pc = nullptr;
  check(STGetKSP(st, &ksp), "STGetKSP");
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  if (factorises(o, n)) {
    check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
    check(PCSetType(pc, indefinite ? PCLU : PCCHOLESKY), "PCSetType");
    check(PCFactorSetMatOrderingType(pc, MATORDERINGND), "PCFactorSetMatOrderingType");
    return;
  }
  check(KSPSetType(ksp, indefinite ? KSPGMRES : KSPCG), "KSPSetType");
  if (o.preconditioner == SolverChoice::Preconditioner::Hypre) {
    check(PCSetType(pc, PCHYPRE), "PCSetType hypre");
    check(PCHYPRESetType(pc, "boomeramg"), "PCHYPRESetType");
    // Aggressive coarsening on the first level, as the linear solver's BoomerAMG (solvers/petsc_solver.cpp):
    // 0.60-0.84x the eigen-solve's time on a 52,920-DOF lattice (docs/performance.md). The ST's
    // options carry its prefix (-st_), as the user's do (read by read_user_options).
    const char* prefix = nullptr;
    check(PCGetOptionsPrefix(pc, &prefix), "PCGetOptionsPrefix");
    set_boomeramg_defaults(prefix ? prefix : "");
  } else {
    check(PCSetType(pc, PCGAMG), "PCSetType gamg");
  }
  const double inner = std::max(kMinInnerRtol, kInnerRtolFactor * o.rtol);
  check(KSPSetTolerances(ksp, inner, PETSC_DEFAULT, PETSC_DEFAULT, o.max_linear_iterations), "KSPSetTolerances");
}

// The largest error estimate over the wanted pairs at the last outer iteration: the residual
// reached when the solve stops short.
struct Progress {
  int wanted = 0;
  double error = 0.0;
};
PetscErrorCode record_progress(EPS, PetscInt, PetscInt, PetscScalar*, PetscScalar*, PetscReal* errest, PetscInt nest,
                               void* ctx) {
  auto* p = static_cast<Progress*>(ctx);
  double e = 0.0;
  for (PetscInt i = 0; i < std::min<PetscInt>(nest, p->wanted); ++i) e = std::max(e, static_cast<double>(errest[i]));
  p->error = e;
  return 0;
}

// Runs `eps` (operators and ST set) and reads its converged pairs: the `count` nearest `target`
// (every converged one when `target` is not finite), ascending.
SlepcEigenPairs solve_and_collect(EPS eps, Mat A, int count, const char* what, double target) {
  SlepcEigenPairs out;
  Progress progress{count, 0.0};
  check(EPSMonitorSet(eps, record_progress, &progress, nullptr), "EPSMonitorSet");
  const PetscErrorCode solved = [&] {
#if defined(__SANITIZE_ADDRESS__)
    // SLEPc 3.18's EPSSolve, in shift-and-invert with an iterative inner solve (CG with multigrid),
    // creates one work vector (BVCreateVec) that it never destroys, although the EPS is destroyed:
    // the sanitizer build's leak check ignores what EPSSolve allocates (it is SLEPc's alone).
    const __lsan::ScopedDisabler slepc_owns_these;
#endif
    return EPSSolve(eps);
  }();
  PetscInt its = 0, nconv = 0, linear = 0;
  EPSGetIterationNumber(eps, &its);
  ST st = nullptr;
  KSP ksp = nullptr;
  KSPType type = nullptr;
  if (!EPSGetST(eps, &st) && !STGetKSP(st, &ksp) && !KSPGetType(ksp, &type) && type &&
      std::string(type) != KSPPREONLY)
    KSPGetTotalIterations(ksp, &linear);
  out.iterations = static_cast<int>(its);
  out.linear_iterations = linear;
  if (solved) {
    const char* text = nullptr;
    PetscErrorMessage(solved, &text, nullptr);
    out.message = fmt::format("{}: SLEPc's Krylov-Schur stopped after {} iterations ({}); error estimate reached {:.3g}",
                              what, its, text ? text : "error", progress.error);
    return out;
  }
  check(EPSGetConverged(eps, &nconv), "EPSGetConverged");
  if (nconv < count) {
    out.message = fmt::format("{}: SLEPc's Krylov-Schur converged {} of {} eigenpairs in {} iterations; "
                              "relative error estimate reached {:.3g}",
                              what, nconv, count, its, progress.error);
    return out;
  }
  OwnedVec xr, whole;
  check(MatCreateVecs(A, &xr.h, nullptr), "MatCreateVecs");
  PetscInt n = 0;
  check(MatGetSize(A, &n, nullptr), "MatGetSize");
  // On several processes each vector is gathered whole on every one (what follows is replicated).
  PetscMPIInt processes = 1;
  check(MPI_Comm_size(PetscObjectComm(reinterpret_cast<PetscObject>(A)), &processes), "MPI_Comm_size");
  VecScatter to_all = nullptr;
  if (processes > 1) check(VecScatterCreateToAll(xr.h, &to_all, &whole.h), "VecScatterCreateToAll");
  std::vector<std::pair<double, Eigen::VectorXd>> pairs;
  for (PetscInt i = 0; i < nconv; ++i) {
    PetscScalar kr = 0.0;
    check(EPSGetEigenpair(eps, i, &kr, nullptr, xr.h, nullptr), "EPSGetEigenpair");
    if (to_all) {
      check(VecScatterBegin(to_all, xr.h, whole.h, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
      check(VecScatterEnd(to_all, xr.h, whole.h, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
    }
    const Vec v = to_all ? whole.h : xr.h;
    const PetscScalar* a = nullptr;
    check(VecGetArrayRead(v, &a), "VecGetArrayRead");
    pairs.emplace_back(kr, Eigen::Map<const Eigen::VectorXd>(a, n));
    check(VecRestoreArrayRead(v, &a), "VecRestoreArrayRead");
  }
  if (to_all) VecScatterDestroy(&to_all);
  if (std::isfinite(target)) {
    std::sort(pairs.begin(), pairs.end(), [&](const auto& a, const auto& b) {
      return std::abs(a.first - target) < std::abs(b.first - target);
    });
    if (pairs.size() > static_cast<std::size_t>(count)) pairs.resize(static_cast<std::size_t>(count));
  }
  std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  out.values.resize(static_cast<Eigen::Index>(pairs.size()));
  out.vectors.resize(n, static_cast<Eigen::Index>(pairs.size()));
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    out.values[static_cast<Eigen::Index>(i)] = pairs[i].first;
    out.vectors.col(static_cast<Eigen::Index>(i)) = pairs[i].second;
  }
  out.converged = true;
  return out;
}

// The user's PETSC_OPTIONS, read last so that they tune what beamfea set: -eps_* for the
// eigen-solver, -st_ksp_* and -st_pc_* for its inner linear solve (EPSSetFromOptions reads the
// ST's, which reads its KSP's and PC's).
void read_user_options(EPS eps) { check(EPSSetFromOptions(eps), "EPSSetFromOptions"); }

void configure_eps(EPS eps, Mat A, Mat B, int count, const SlepcEigenOptions& o) {
  check(EPSSetOperators(eps, A, B), "EPSSetOperators");
  check(EPSSetProblemType(eps, EPS_GHEP), "EPSSetProblemType");
  check(EPSSetType(eps, EPSKRYLOVSCHUR), "EPSSetType");
  check(EPSSetDimensions(eps, count, PETSC_DEFAULT, PETSC_DEFAULT), "EPSSetDimensions");
  check(EPSSetTolerances(eps, o.rtol, PETSC_DEFAULT), "EPSSetTolerances");
}

}  // namespace

SlepcEigenPairs slepc_vibration_pairs(const SparseMatrix& K, const SparseMatrix& M, const SlepcEigenOptions& options,
                                      const Eigen::MatrixXd* rigid_body_modes) {
  options.validate();
  // SLEPc's BLAS calls (the basis's orthogonalisation) are small, one after each inner solve: the
  // BLAS's second thread spins between them (sched_yield) and slows the solve (docs/performance.md).
  const SingleBlasThread one_blas_thread;
  const Eigen::Index n = K.rows();
  const int count = static_cast<int>(std::min<Eigen::Index>(options.count, n));
  try {
    ensure_slepc();
    const Layout at = layout_for(n, factorises(options, n));
    const std::lock_guard<std::mutex> lock(petsc_lock());  // held until the PETSc objects are gone
    OwnedMat A, B, P;
    petsc_matrix(K, false, at, A);
    petsc_matrix(M, false, at, B);
    // The preconditioner's matrix: K - sigma M itself, carrying the near null space.
    petsc_matrix(SparseMatrix(K - options.target * M), !options.indefinite, at, P);
    attach_near_null_space(P.h, rigid_body_modes, at);
    OwnedEps eps;
    check(EPSCreate(at.comm, &eps.h), "EPSCreate");
    configure_eps(eps.h, A.h, B.h, count, options);
    check(EPSSetWhichEigenpairs(eps.h, EPS_TARGET_MAGNITUDE), "EPSSetWhichEigenpairs");
    check(EPSSetTarget(eps.h, options.target), "EPSSetTarget");
    ST st = nullptr;
    check(EPSGetST(eps.h, &st), "EPSGetST");
    check(STSetType(st, STSINVERT), "STSetType");
    check(STSetPreconditionerMat(st, P.h), "STSetPreconditionerMat");
    configure_linear_solve(st, options, n, options.indefinite);
    read_user_options(eps.h);
    SlepcEigenPairs out = solve_and_collect(eps.h, A.h, count, "modal", options.target);
    for (Eigen::Index k = 0; k < out.vectors.cols(); ++k) {
      const double m = out.vectors.col(k).dot(M * out.vectors.col(k));
      if (m > 0.0) out.vectors.col(k) /= std::sqrt(m);
    }
    return out;
  } catch (const Error& e) {
    SlepcEigenPairs out;
    out.message = std::string("modal: ") + e.what();
    return out;
  }
}

SlepcEigenPairs slepc_buckling_pairs(const SparseMatrix& K, const SparseMatrix& KG, const SlepcEigenOptions& options,
                                     const Eigen::MatrixXd* rigid_body_modes) {
  options.validate();
  // SLEPc's BLAS calls (the basis's orthogonalisation) are small, one after each inner solve: the
  // BLAS's second thread spins between them (sched_yield) and slows the solve (docs/performance.md).
  const SingleBlasThread one_blas_thread;
  const Eigen::Index n = K.rows();
  const int count = static_cast<int>(std::min<Eigen::Index>(options.count, n));
  try {
    ensure_slepc();
    const Layout at = layout_for(n, factorises(options, n));
    const std::lock_guard<std::mutex> lock(petsc_lock());  // held until the PETSc objects are gone
    OwnedMat A, B;
    petsc_matrix(KG, false, at, A);
    petsc_matrix(K, true, at, B);
    attach_near_null_space(B.h, rigid_body_modes, at);
    OwnedEps eps;
    check(EPSCreate(at.comm, &eps.h), "EPSCreate");
    configure_eps(eps.h, A.h, B.h, count, options);
    check(EPSSetWhichEigenpairs(eps.h, EPS_LARGEST_REAL), "EPSSetWhichEigenpairs");
    ST st = nullptr;
    check(EPSGetST(eps.h, &st), "EPSGetST");
    check(STSetType(st, STSHIFT), "STSetType");
    configure_linear_solve(st, options, n, false);
    read_user_options(eps.h);
    SlepcEigenPairs mu = solve_and_collect(eps.h, A.h, count, "buckling", std::numeric_limits<double>::infinity());
    if (!mu.converged) return mu;
    // mu = 1/lambda: the positive ones, as load factors, ascending.
    const double mu_max = mu.values.size() > 0 ? mu.values.cwiseAbs().maxCoeff() : 0.0;
    std::vector<std::pair<double, Eigen::Index>> factors;
    for (Eigen::Index i = 0; i < mu.values.size(); ++i)
      if (mu.values[i] > kPositiveMuRelative * mu_max && mu.values[i] > 0.0) factors.emplace_back(1.0 / mu.values[i], i);
    std::sort(factors.begin(), factors.end());
    if (factors.size() > static_cast<std::size_t>(count)) factors.resize(static_cast<std::size_t>(count));
    SlepcEigenPairs out = mu;
    out.values.resize(static_cast<Eigen::Index>(factors.size()));
    out.vectors.resize(n, static_cast<Eigen::Index>(factors.size()));
    for (std::size_t i = 0; i < factors.size(); ++i) {
      out.values[static_cast<Eigen::Index>(i)] = factors[i].first;
      out.vectors.col(static_cast<Eigen::Index>(i)) = mu.vectors.col(factors[i].second).normalized();
    }
    return out;
  } catch (const Error& e) {
    SlepcEigenPairs out;
    out.message = std::string("buckling: ") + e.what();
    return out;
  }
}

void finalize_slepc() {
  if (g_slepc_initialized) SlepcFinalize();
  g_slepc_initialized = false;
}

#else  // no SLEPc: eigen_solver_iterative never selects these

void finalize_slepc() {}

SlepcEigenPairs slepc_vibration_pairs(const SparseMatrix&, const SparseMatrix&, const SlepcEigenOptions&,
                                      const Eigen::MatrixXd*) {
  throw Error("modal: beamfea was built without SLEPc (BEAMFEA_WITH_SLEPC=OFF)");
}
SlepcEigenPairs slepc_buckling_pairs(const SparseMatrix&, const SparseMatrix&, const SlepcEigenOptions&,
                                     const Eigen::MatrixXd*) {
  throw Error("buckling: beamfea was built without SLEPc (BEAMFEA_WITH_SLEPC=OFF)");
}

#endif

}  // namespace beamfea
