#pragma once
// Linear static analysis: K_ff u_f = T_f^T f - K_fp u_p, then reactions, end forces and joint
// forces by back-substitution. A singular K is diagnosed (zero-energy modes named), never solved.
#include <memory>
#include <string>
#include <vector>

#include "core/dof_map.hpp"
#include "core/model.hpp"
#include "core/parallel_tasks.hpp"
#include "elements/beam.hpp"
#include "elements/span_loads.hpp"
#include "solvers/mechanism.hpp"
#include "solvers/solver_choice.hpp"

namespace beamfea {

enum class SolveStatus {
  Succeeded,   // a solution was found
  Mechanism,   // the structure has zero-energy modes (see modes)
  Failed,      // the factorisation failed for another reason
  NotConverged,  // the iterative solver stopped above its rtol (message: the residual reached)
};
const char* to_string(SolveStatus s);

struct LinearStaticOptions {
  double singular_rcond = 1e-13;  // reciprocal condition (Jacobi-scaled) below which K is checked for mechanisms
  double zero_energy_tolerance = 1e-10;  // eigenvalue (Jacobi-scaled) of a zero-energy mode
  // Runs the element matrices beside the ordering and symbolic analysis of K_ff's pattern
  // (core/parallel_tasks.hpp; the program's: app/thread_tasks.hpp); empty: one after the other,
  // on the calling thread. The result is the same either way.
  ParallelTasks parallel;
  void validate() const;
};

struct LinearStaticResult {
  SolveStatus status = SolveStatus::Failed;
  std::string message;                 // one line: outcome and key figures
  int free_dofs = 0;
  SolverReport solver;                 // which solver ran, its iterations, the computed residual
  Eigen::VectorXd u;                   // raw displacements (node components, joint coordinates)
  std::vector<Vec6> reactions;         // per node (zero where unsupported)
  std::vector<char> supported;         // per node: has at least one support or prescribed DOF
  std::vector<Vec12> end_forces;       // per element, local, forces on the element at its ends
                                       // (k u + fixed-end forces of the member loads)
  std::vector<ElementLoads> element_loads;  // per element: the loads between its nodes (local)
  std::vector<Vec6> joint_forces;      // per joint: force and moment from body 1 on body 2, global
  // Per node, where the model has skewed supports (both empty otherwise): whether the node has one,
  // and its reaction in that support's axes (`reactions` has it in global axes).
  std::vector<char> skewed;
  std::vector<Vec6> reactions_local;
  std::vector<Vec6> tie_forces;        // per tie: force (moment) on nodes[1] along each tied DOF
  std::vector<double> constraint_forces;  // per linear constraint: its multiplier lambda (the
                                          // force coefficient * lambda on each term's DOF)
  std::vector<ZeroEnergyMode> modes;   // when status == Mechanism
  // Redundant constraint rows (over-constrained loops, supports on one rigid body), e.g. "joint 'jC'
  // uz": their reactions are statically indeterminate; the reported ones are the minimum-norm split.
  std::vector<std::string> statically_indeterminate;
};

// The arrays of a solution besides its result, kept by a caller that solves case after case (a
// sweep worker), with the result it writes over (LinearSystem::solve's second overload).
struct LinearSolveScratch {
  Eigen::VectorXd f_raw, f, u_free, residual;  // external force, reduced, K_ff^-1 f, r
  Eigen::VectorXd free_residual;               // f - K_ff u_free
  DofMap::ConstraintForces constraint_forces;
  DofMap::ConstraintForceScratch constraint_scratch;
};

// The results that the constraint forces `cf` of a solution give (DofMap::constraint_forces of its
// residual f_int - f_ext): reactions (global; in a skewed support's axes too), tie forces and the
// multipliers of linear constraints, written into `res`. Shared by every static solver.
void set_constraint_results(const Model& model, const DofMap& map, const DofMap::ConstraintForces& cf, LinearStaticResult& res);

// The linear system of a model, assembled and factorised once; every load case solves against the
// same factorisation (`factorizations()` counts them: 1, or 0 when the stiffness is singular).
// The model's "solver" (Model::solver, solves_iteratively) may choose PETSc's conjugate gradients
// instead: the multigrid preconditioner is then set up once (counted as the factorisation) and
// every load case iterates with it; a mechanism is diagnosed when CG breaks down or the
// preconditioner cannot be made (zero_energy_modes, as for the direct solver).
class LinearSystem {
 public:
  explicit LinearSystem(const Model& model, const LinearStaticOptions& options = {});
  ~LinearSystem();
  LinearSystem(const LinearSystem&) = delete;
  LinearSystem& operator=(const LinearSystem&) = delete;

  // The solution for one load case (end forces include the member loads' fixed-end forces).
  LinearStaticResult solve(const LoadSet& loads) const;
  // The same written over `into`: afterwards equal, field for field, to what the overload above
  // returns, but its vectors and message keep their storage (with `scratch`'s), so that a sweep's
  // case of a small model (dense factor) allocates nothing once they have their sizes.
  void solve(const LoadSet& loads, LinearStaticResult& into, LinearSolveScratch& scratch) const;
  int factorizations() const { return factorizations_; }
  // The reciprocal condition estimate of the Jacobi-scaled K_ff's Cholesky factor L, (min L_ii /
  // max L_ii)^2 (CHOLMOD's estimate, and the dense factor's the same way); NaN when K_ff was not
  // factorised by Cholesky (a mechanism, an indefinite K). Unit-free: the scaling takes the units out.
  double rcond() const;
  // Whether the system is solved iteratively (PETSc), and then its back end.
  bool iterative() const;
  const Model& model() const { return *model_; }
  int solves() const { return solves_; }
  // Points the system at `model`, which must equal the model it was built from in everything the
  // constructor reads, joint springs included (solvers/structure_cache.hpp's LinearSystemCache
  // checks that before it reuses a system for a sweep's next case): solves then read the loads,
  // masses and ids of `model`.
  void rebind(const Model& model);

 private:
  struct Impl;
  // The iterative solve of K_ff u_free = f into scratch.u_free (restarted while the true residual
  // is above rtol); false, with `res` saying why (mechanism or not converged), when it failed.
  bool solve_iteratively(const Eigen::VectorXd& f, LinearStaticResult& res, LinearSolveScratch& scratch) const;
  const Model* model_;
  std::unique_ptr<Impl> impl_;
  double zero_energy_tolerance_;
  int factorizations_ = 0;
  mutable int solves_ = 0;
};

// The default load case (one system, one solve).
LinearStaticResult solve_linear_static(const Model& model, const LinearStaticOptions& options = {});

}  // namespace beamfea
