#pragma once
// SUNDIALS KINSOL (Newton's method) with beamfea's own sparse LU as its linear solver.
//
// One RAII owner of the SUNDIALS context, the KINSOL memory and the vectors; the residual and
// the Jacobian are std::function callbacks over Eigen vectors; an exception thrown by a callback
// is captured, KINSOL is told to stop (unrecoverable failure) and the exception is rethrown after
// KINSol returns. Every SUNDIALS return code is checked.
//
// Linear solver: a custom SUNMatrix whose content is an Eigen sparse matrix filled by the
// Jacobian callback (KINSetJacFn), and a custom "direct" SUNLinearSolver that factorises it with
// UMFPACK (LU: the tangents of beams under moments are non-symmetric). The symbolic analysis is
// kept between factorisations while the sparsity pattern is unchanged. The Jacobian is refreshed
// at every Newton iteration (KINSetMaxSetupCalls = 1): full Newton.
//
// Non-convergence is an outcome (KinsolStatus), never an exception; bad options are.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>

#include "core/dof_map.hpp"

namespace beamfea {

struct KinsolOptions {
  int max_iterations = 25;
  double function_tolerance = 1e-9;   // on max |fscale_i F_i|
  double step_tolerance = 1e-15;      // scaled step below which KINSOL stops
  bool line_search = false;           // KIN_LINESEARCH instead of plain Newton
  void validate() const;
};

enum class KinsolStatus { Succeeded, StepTooSmall, TooManyIterations, LinearSolverFailed, Failed };
const char* to_string(KinsolStatus s);

struct KinsolSummary {
  KinsolStatus status = KinsolStatus::Failed;
  long iterations = 0;
  long residual_evaluations = 0;
  double residual_norm = 0.0;  // scaled max norm at the end
  int flag = 0;                // KINSol's return flag
  std::string report() const;
};

class KinsolSolver {
 public:
  using ResidualFn = std::function<void(const Eigen::VectorXd& u, Eigen::VectorXd& F)>;
  // Fills J = dF/du at u (F is the residual there).
  using JacobianFn = std::function<void(const Eigen::VectorXd& u, const Eigen::VectorXd& F, SparseMatrix& J)>;

  explicit KinsolSolver(KinsolOptions options = {});
  ~KinsolSolver();
  KinsolSolver(const KinsolSolver&) = delete;
  KinsolSolver& operator=(const KinsolSolver&) = delete;

  // Solves F(u) = 0 from the initial guess u (overwritten). fscale: residual scaling (> 0).
  KinsolSummary solve(Eigen::VectorXd& u, const Eigen::VectorXd& fscale, const ResidualFn& residual,
                      const JacobianFn& jacobian);

  // Number of symbolic analyses and numeric factorisations so far (pattern reuse check).
  long symbolic_analyses() const;
  long factorizations() const;
  const KinsolOptions& options() const { return options_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  KinsolOptions options_;
};

}  // namespace beamfea
