#include "solvers/kinsol_solver.hpp"

#include <fmt/format.h>
#include <kinsol/kinsol.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <cmath>
#include <exception>

#include "core/errors.hpp"
#include "solvers/pattern_factor.hpp"

namespace beamfea {

void KinsolOptions::validate() const {
  if (max_iterations < 1) throw Error("KinsolOptions: max_iterations must be at least 1");
  if (!(function_tolerance > 0.0)) throw Error("KinsolOptions: function_tolerance must be positive");
  if (!(step_tolerance > 0.0)) throw Error("KinsolOptions: step_tolerance must be positive");
}

const char* to_string(KinsolStatus s) {
  switch (s) {
    case KinsolStatus::Succeeded: return "converged";
    case KinsolStatus::StepTooSmall: return "step too small";
    case KinsolStatus::TooManyIterations: return "too many iterations";
    case KinsolStatus::LinearSolverFailed: return "linear solver failed";
    case KinsolStatus::Failed: return "failed";
  }
  return "?";
}

std::string KinsolSummary::report() const {
  return fmt::format("KINSOL: {} after {} iterations, |F| = {:.3e} (flag {})", to_string(status), iterations,
                     residual_norm, flag);
}

namespace {

void check_flag(int flag, const char* what) {
  if (flag < 0) throw Error(fmt::format("KINSOL: {} failed with flag {}", what, flag));
}

template <class T>
T* check_ptr(T* p, const char* what) {
  if (!p) throw Error(fmt::format("KINSOL: {} returned null", what));
  return p;
}

Eigen::Map<Eigen::VectorXd> view(N_Vector v) {
  return {N_VGetArrayPointer(v), static_cast<Eigen::Index>(N_VGetLength(v))};
}

}  // namespace

struct KinsolSolver::Impl {
  // Persisting between solves: the Jacobian (assembled in place) and its LU, with the symbolic
  // analysis kept while the pattern stays.
  LuFactor lu;

  // Per solve.
  const ResidualFn* residual = nullptr;
  const JacobianFn* jacobian = nullptr;
  std::exception_ptr error;
  Eigen::VectorXd u_tmp, f_tmp;
  // The last residual evaluated (the returned iterate's, unless KINSOL stopped elsewhere): the final
  // report reuses it instead of evaluating the residual once more.
  Eigen::VectorXd last_u, last_f;
  bool last_valid = false;

  // 1 when the LU fails: recoverable, KINSOL may try again (with a fresh analysis).
  int factorize() { return lu.factorize() ? 0 : 1; }

  // C callbacks.
  static int func(N_Vector u, N_Vector f, void* data) {
    auto* self = static_cast<Impl*>(data);
    try {
      self->u_tmp = view(u);
      self->f_tmp.resize(self->u_tmp.size());
      (*self->residual)(self->u_tmp, self->f_tmp);
      if (!self->f_tmp.allFinite()) return 1;  // recoverable: KINSOL backtracks where it can
      view(f) = self->f_tmp;
      self->last_u = self->u_tmp;
      self->last_f = self->f_tmp;
      self->last_valid = true;
      return 0;
    } catch (...) {
      self->error = std::current_exception();
      return -1;
    }
  }
  static int jac(N_Vector u, N_Vector fu, SUNMatrix, void* data, N_Vector, N_Vector) {
    auto* self = static_cast<Impl*>(data);
    try {
      self->u_tmp = view(u);
      self->f_tmp = view(fu);
      (*self->jacobian)(self->u_tmp, self->f_tmp, self->lu.matrix());
      return 0;
    } catch (...) {
      self->error = std::current_exception();
      return -1;
    }
  }
  // SUNMatrix ops: the content points at Impl; the matrix itself lives in Impl::lu.matrix().
  static SUNMatrix_ID mat_id(SUNMatrix) { return SUNMATRIX_CUSTOM; }
  static int mat_zero(SUNMatrix) { return 0; }
  static void mat_destroy(SUNMatrix A) {
    if (!A) return;
    A->content = nullptr;
    SUNMatFreeEmpty(A);
  }
  // SUNLinearSolver ops.
  static SUNLinearSolver_Type ls_type(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }
  static SUNLinearSolver_ID ls_id(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }
  static int ls_init(SUNLinearSolver) { return 0; }
  static int ls_setup(SUNLinearSolver S, SUNMatrix) {
    auto* self = static_cast<Impl*>(S->content);
    try {
      return self->factorize();
    } catch (...) {
      self->error = std::current_exception();
      return -1;
    }
  }
  static int ls_solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, realtype) {
    auto* self = static_cast<Impl*>(S->content);
    try {
      const Eigen::VectorXd rhs = view(b);
      Eigen::VectorXd sol = self->lu.solver().solve(rhs);
      if (!sol.allFinite()) return 1;
      view(x) = sol;
      return 0;
    } catch (...) {
      self->error = std::current_exception();
      return -1;
    }
  }
  static int ls_free(SUNLinearSolver S) {
    if (!S) return 0;
    S->content = nullptr;
    SUNLinSolFreeEmpty(S);
    return 0;
  }
};

namespace {
// RAII owners of the SUNDIALS objects of one solve.
struct Context {
  SUNContext ctx = nullptr;
  Context() { check_flag(SUNContext_Create(nullptr, &ctx), "SUNContext_Create"); }
  ~Context() { SUNContext_Free(&ctx); }
};
struct Vector {
  N_Vector v = nullptr;
  Vector(Eigen::Index n, SUNContext ctx) { v = check_ptr(N_VNew_Serial(n, ctx), "N_VNew_Serial"); }
  ~Vector() { N_VDestroy(v); }
};
struct Memory {
  void* kmem = nullptr;
  explicit Memory(SUNContext ctx) { kmem = check_ptr(KINCreate(ctx), "KINCreate"); }
  ~Memory() { KINFree(&kmem); }
};
}  // namespace

KinsolSolver::KinsolSolver(KinsolOptions options) : impl_(std::make_unique<Impl>()), options_(options) {
  options_.validate();
}
KinsolSolver::~KinsolSolver() = default;

long KinsolSolver::symbolic_analyses() const { return impl_->lu.symbolic_analyses(); }
long KinsolSolver::factorizations() const { return impl_->lu.factorizations(); }

KinsolSummary KinsolSolver::solve(Eigen::VectorXd& u, const Eigen::VectorXd& fscale, const ResidualFn& residual,
                                  const JacobianFn& jacobian) {
  KinsolSummary sum;
  const Eigen::Index n = u.size();
  if (fscale.size() != n) throw Error("KinsolSolver: fscale has the wrong size");
  Impl& im = *impl_;
  im.residual = &residual;
  im.jacobian = &jacobian;
  im.error = nullptr;
  im.last_valid = false;

  Context ctx;
  Vector vu(n, ctx.ctx), vus(n, ctx.ctx), vfs(n, ctx.ctx);
  view(vu.v) = u;
  view(vus.v).setOnes();
  view(vfs.v) = fscale;
  Memory mem(ctx.ctx);
  void* kmem = mem.kmem;
  check_flag(KINInit(kmem, &Impl::func, vu.v), "KINInit");
  check_flag(KINSetUserData(kmem, &im), "KINSetUserData");

  SUNMatrix A = check_ptr(SUNMatNewEmpty(ctx.ctx), "SUNMatNewEmpty");
  A->content = &im;
  A->ops->getid = &Impl::mat_id;
  A->ops->zero = &Impl::mat_zero;
  A->ops->destroy = &Impl::mat_destroy;
  SUNLinearSolver LS = SUNLinSolNewEmpty(ctx.ctx);
  if (!LS) {
    SUNMatDestroy(A);
    throw Error("KINSOL: SUNLinSolNewEmpty returned null");
  }
  LS->content = &im;
  LS->ops->gettype = &Impl::ls_type;
  LS->ops->getid = &Impl::ls_id;
  LS->ops->initialize = &Impl::ls_init;
  LS->ops->setup = &Impl::ls_setup;
  LS->ops->solve = &Impl::ls_solve;
  LS->ops->free = &Impl::ls_free;
  struct Guard {
    SUNMatrix A;
    SUNLinearSolver LS;
    ~Guard() {
      SUNLinSolFree(LS);
      SUNMatDestroy(A);
    }
  } guard{A, LS};

  check_flag(KINSetLinearSolver(kmem, LS, A), "KINSetLinearSolver");
  check_flag(KINSetJacFn(kmem, &Impl::jac), "KINSetJacFn");
  check_flag(KINSetMaxSetupCalls(kmem, 1), "KINSetMaxSetupCalls");
  check_flag(KINSetNumMaxIters(kmem, options_.max_iterations), "KINSetNumMaxIters");
  check_flag(KINSetFuncNormTol(kmem, options_.function_tolerance), "KINSetFuncNormTol");
  check_flag(KINSetScaledStepTol(kmem, options_.step_tolerance), "KINSetScaledStepTol");
  check_flag(KINSetMaxNewtonStep(kmem, 1e300), "KINSetMaxNewtonStep");
  check_flag(KINSetErrHandlerFn(kmem, [](int, const char*, const char*, char*, void*) {}, nullptr),
             "KINSetErrHandlerFn");

  const int flag = KINSol(kmem, vu.v, options_.line_search ? KIN_LINESEARCH : KIN_NONE, vus.v, vfs.v);
  if (im.error) std::rethrow_exception(im.error);
  sum.flag = flag;
  long nni = 0, nfe = 0;
  realtype fnorm = 0.0;
  check_flag(KINGetNumNonlinSolvIters(kmem, &nni), "KINGetNumNonlinSolvIters");
  check_flag(KINGetNumFuncEvals(kmem, &nfe), "KINGetNumFuncEvals");
  if (KINGetFuncNorm(kmem, &fnorm) < 0) fnorm = NAN;
  sum.iterations = nni;
  sum.residual_evaluations = nfe;
  u = view(vu.v);
  // The max norm of the scaled residual at the returned point.
  Eigen::VectorXd F(n);
  if (im.last_valid && im.last_u.size() == n && im.last_u == u) F = im.last_f;
  else residual(u, F);
  sum.residual_norm = F.size() ? (F.cwiseProduct(fscale)).cwiseAbs().maxCoeff() : 0.0;
  switch (flag) {
    case KIN_SUCCESS:
    case KIN_INITIAL_GUESS_OK: sum.status = KinsolStatus::Succeeded; break;
    case KIN_STEP_LT_STPTOL:
      // Stalled at round-off just above the tolerance: accept within a factor of 100.
      sum.status = sum.residual_norm <= 100.0 * options_.function_tolerance ? KinsolStatus::Succeeded : KinsolStatus::StepTooSmall;
      break;
    case KIN_MAXITER_REACHED: sum.status = KinsolStatus::TooManyIterations; break;
    case KIN_LSETUP_FAIL:
    case KIN_LSOLVE_FAIL:
    case KIN_LINSOLV_NO_RECOVERY: sum.status = KinsolStatus::LinearSolverFailed; break;
    default: sum.status = KinsolStatus::Failed; break;
  }
  return sum;
}

}  // namespace beamfea
