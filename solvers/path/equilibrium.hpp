#pragma once
// The bordered equilibrium system of one path step, solved by KINSOL (solvers/kinsol_solver.hpp).
//
// Unknowns u = [Delta over the free independent coordinates (nf), mu over the slave constraints
// (nc), extra], the state being start (+) Delta (solvers/nonlinear_structure.hpp's retraction):
//   r(x, lambda) = T^T (f_int - lambda f_ext - sum mu_c e_c [- extra e_ctrl]) = 0   (nf rows)
//   c(x) - c_0 = 0                                 supports/imposed values on slave nodes (nc rows)
//   the step's extra equation (StepKind):
//     Load      none (lambda given);
//     Control   u_ctrl(x) - s = 0, extra = lambda (with loads) or the controlled DOF's reaction
//               (imposed motion, no loads);
//     Arc       Crisfield's spherical constraint (Crisfield 1981; Crisfield 1991, vol. 1, eq. 9.13)
//               (|Delta|_W^2 + psi^2 dlambda^2 - ds^2) / (2 ds) = 0, W: 1 on translations, L^2 on
//               rotations; psi^2 is set by the step control (solvers/path/step_control.hpp).
// Closed loops (solvers/nonlinear_structure.hpp, "Closed loops"): the closures' rows c(x) = 0 join the
// slave constraints, with multipliers mu_l; the residual gains B^T mu_l and the tangent the closure
// curvature contracted with mu_l. Redundant rows among the slave constraints and the closures (a
// planar loop in 3-D: three) are found once, rank-revealingly, at the reference state (independent_rows,
// rows and coordinates scaled to lengths by the model length L) and dropped: the motion is solved
// exactly with the independent rows; the dropped rows' reactions are statically indeterminate
// (`redundant` names them) and reported as zero.
// The Jacobian is K_t D(Delta) bordered by the constraint rows and columns, D the derivative of the
// retraction. The convergence test scales the rows (fscale) so that KINSOL's tolerance is relative
// to the problem: forces by F_ref (the reference load at the structure's own load scale lambda_ref,
// so the same for a reference load of 1 or 1000; not below a round-off floor tied to the stiffest
// element), constraint rows by L (translations: a displacement error relative to the model size),
// the arc row by ds.
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "core/model.hpp"
#include "solvers/kinsol_solver.hpp"
#include "solvers/nonlinear_structure.hpp"
#include "solvers/path/path_types.hpp"
#include "solvers/pattern_factor.hpp"

namespace beamfea {

// A raw DOF held at a value: supports or imposed values on slave nodes, or the controlled DOF.
struct ConstraintDef {
  int node = -1, comp = 0;
  double target = 0.0;
};

enum class StepKind { Load, Control, Arc };

// What one step solves for.
struct StepSpec {
  StepKind kind = StepKind::Load;
  double lambda = 0.0;        // Load: the load factor; otherwise the start value
  double control = 0.0;       // Control: the target of the controlled DOF
  double ds = 0.0;            // Arc
};

// A converged equilibrium state.
struct Converged {
  NonlinearState state;
  double lambda = 0.0;
  Eigen::VectorXd mu;         // slave constraint multipliers
  double extra_mu = 0.0;      // controlled DOF's reaction (imposed motion)
  long iterations = 0;        // the step's Newton iterations (KINSOL's; 0 when the chord converged)
  long chord_iterations = 0;  // chord iterations of the step (solvers/path/corrector.hpp)
  bool by_chord = false;      // found by the chord corrector (no factorisation of its own)
};

// Free coordinates above which a symmetric tangent is factorised by LL^T (PathEquilibrium::
// tangent_is_cholesky): the stability analysis' own size for its LL^T (kStabilityDenseLimit,
// solvers/path/stability.hpp); below it UMFPACK's LU and a dense eigen-solve cost little.
inline constexpr int kSymmetricTangentMinDofs = 400;
// Largest |J - J^T| / max |J| of a tangent factorised as symmetric: rounding, and the residual's
// imbalance of internal moments at a converged state (far below this), not an applied moment's skew part.
inline constexpr double kSymmetricTangentSkew = 1e-9;

class PathEquilibrium {
 public:
  // The controlled DOF is taken from the options under displacement control. Throws ModelError when
  // the controlled DOF is supported, or when the model has no loads and the control is not a
  // displacement.
  PathEquilibrium(const Model& model, const PathOptions& o);

  int unknowns(const StepSpec& s) const { return nf + nc + (s.kind == StepKind::Load ? 0 : 1); }
  bool extra_is_lambda(const StepSpec& s) const {
    return s.kind == StepKind::Arc || (s.kind == StepKind::Control && has_loads);
  }
  // Arc-length weight of a free coordinate: 1 on translations, L^2 on rotations.
  double weight(int gen) const { return ns.is_rotation(gen) ? L * L : 1.0; }
  // sum_k W_k a_k b_k over the free coordinates of a and b (the first nf entries).
  double weighted_dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;

  // The value of a constrained raw DOF at a state (translation from the reference, or log R).
  double cvalue(const NonlinearState& st, const ConstraintDef& c) const;
  double control_value(const NonlinearState& st) const { return cvalue(st, ctrl); }
  Eigen::VectorXd delta_gens(const Eigen::VectorXd& u) const;
  // Unknowns at the start of a step.
  Eigen::VectorXd start_unknowns(const Converged& c, const StepSpec& s) const;

  struct Eval {
    NonlinearState st;
    double lambda;
    Eigen::VectorXd f_app;
    Eigen::VectorXd mu_closure;   // multipliers of all closure rows (zero on the dropped ones)
  };
  Eval state_of(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u) const;
  void residual(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u, Eigen::VectorXd& F) const;
  void jacobian(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u, SparseMatrix& J) const;
  Eigen::VectorXd fscale(const StepSpec& s) const;
  // Solves one step from `start` with initial guess u (the predictor). False on failure, with the
  // solver's report. With the chord corrector on (PathOptions::chord_corrector) and the start state's
  // tangent factorised (tangent(start), as the predictor leaves it), chord iterations on that factor
  // first (solvers/path/corrector.hpp); when they give up, full Newton (KINSOL) from the same u.
  bool solve(KinsolSolver& kin, const Converged& start, const StepSpec& s, Eigen::VectorXd u, Converged& out,
             std::string& report) const;
  // Tangent direction at a converged state: [dDelta (nf), dmu (nc), dextra] per unit lambda (loads)
  // or per unit control (imposed motion). Empty when the tangent is singular. Factorised once per
  // state (kept with evaluation_at's).
  const Eigen::VectorXd& tangent(const Converged& c) const;
  // The size of the factorised tangent system at c when c is the state kept and its tangent was
  // computed (by tangent(c)) and factorised successfully; -1 otherwise. No computation.
  int tangent_factor_rows(const Converged& c) const;
  // x = A^-1 b with that factor, b of its size: the LU without UMFPACK's iterative refinement (each
  // chord iteration is itself a refinement step against the true residual,
  // solvers/path/corrector.hpp), or the symmetric tangent's LL^T (below).
  Eigen::VectorXd solve_with_tangent_factor(const Eigen::VectorXd& b) const;
  // The symmetric tangent. Above kSymmetricTangentMinDofs free coordinates, where the tangent system
  // is the tangent over the free coordinates alone (no slave constraints or closures, no imposed
  // motion's row) and symmetric to rounding at the state (forces alone: elements/corotational_beam.hpp,
  // "Symmetry"), its symmetric part is factorised by CHOLMOD's supernodal LL^T instead of UMFPACK's LU.
  // That one factor then serves the tangent direction, the chord iterations and the stability
  // analysis (its success proves the state stable; Lanczos on its inverse gives the lowest
  // eigenvalue): one factorisation per converged state (issue 15). Where the LL^T fails (past a
  // critical point) or the tangent is not symmetric, the LU as before.
  bool tangent_is_cholesky(const Converged& c) const;
  // x = S^-1 b with that LL^T (when tangent_is_cholesky(c) for the kept state), b over the free
  // coordinates.
  void solve_with_symmetric_tangent(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  // Numeric factorisations of converged states' tangent systems so far (the predictor's factor:
  // LU or LL^T), and symbolic analyses.
  long tangent_factorizations() const { return predictor_lu_.factorizations() + symmetric_llt_.factorizations(); }
  long tangent_symbolic_analyses() const {
    return predictor_lu_.symbolic_analyses() + symmetric_llt_.symbolic_analyses();
  }
  // Steps solved by the chord corrector, and those where it gave up (full Newton then), so far.
  long chord_steps() const { return chord_steps_; }
  long chord_fallbacks() const { return chord_fallbacks_; }
  // The evaluation at a converged state (Delta = 0, the state's load factor, multipliers and
  // reaction): residual, tangent over gens, end forces. Computed once per state and kept while the
  // state is the last one asked for: the predictor of the next step, the stability analysis, the
  // frequencies and the record of the step share it (one assembly per converged state).
  const NonlinearStructure::Evaluation& evaluation_at(const Converged& c) const;
  // Displacement control: the slope of the controlled DOF's conjugate along the path, dlambda/du_c
  // (with loads) or dR/du_c (imposed motion, R the controlled DOF's reaction), from the tangent.
  // A change of its sign between two states is an extremum of the load factor (or the reaction): a
  // limit point. NaN when the tangent is singular.
  double conjugate_slope(const Converged& c) const;
  // Increment of the free coordinates from a to b (translations exact, spins by the logarithm).
  Eigen::VectorXd increment(const Converged& a, const Converged& b) const;
  // Reduced load pattern T^T f_ext over the free coordinates at a state.
  Eigen::VectorXd load_pattern(const NonlinearState& st) const;

  // Sparse row of a constraint over free gens at a state (D applied when given).
  std::vector<std::pair<int, double>> crow(const NonlinearState& st, const std::vector<Twist>& tw,
                                           const ConstraintDef& c, const SparseMatrix* D) const;
  // The reference load at a state over raw DOFs: f_ext with the dead member loads' consistent
  // vector following the chords (NonlinearStructure::dead_load_change).
  Eigen::VectorXd load_at(const NonlinearState& st) const;
  // Constraint rows (nc [+ control]) over the free gens at a state, dense.
  Eigen::MatrixXd constraint_matrix(const NonlinearState& st, bool with_control) const;
  // The state at the start of the path: the reference with the prescribed independent values
  // imposed (and the slave constraints solved for when any is non-zero). False on failure.
  bool initial_state(KinsolSolver& kin, Converged& out, std::string& report) const;

  // The force scale of the convergence test: the reference load at the load factor lambda_ref
  // (solvers/path/path_scales.hpp), not below the round-off floor F_floor.
  void set_load_scale(double lambda_ref);

  NonlinearStructure ns;
  double L = 1.0, F_ref = 1.0, psi2 = 0.0;
  double f_max = 0.0;     // largest reference load component (moments / L)
  double F_floor = 0.0;   // round-off: kRoundOffForceRatio x the stiffest element's force for a displacement L
  std::vector<int> free, gen_to_free;
  std::vector<ConstraintDef> cons;       // independent slave constraints (the first ncs multipliers)
  std::vector<int> closure_rows;         // independent closure rows (the next ones), into the closure rows
  std::vector<std::string> redundant;    // the dropped rows: statically indeterminate reactions
  int ncs = 0;
  // Multipliers of all closure rows from the unknowns' multipliers (nc of them).
  Eigen::VectorXd closure_multipliers(const Eigen::VectorXd& mu) const;
  ConstraintDef ctrl;
  Eigen::VectorXd f_ext;
  bool has_loads = false;
  int nf = 0, nc = 0;
  bool chord = true;   // PathOptions::chord_corrector

 private:
  void select_independent_constraints();
  // The spec of the tangent system at a converged state (no extra row with loads; the controlled
  // DOF held, its reaction the extra unknown, under an imposed motion).
  StepSpec tangent_spec(const Converged& c) const;
  // J from an evaluation at state_of(start, s, u) (jacobian's second half).
  void jacobian_from(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u, const Eval& e,
                     const SparseMatrix& tangent, SparseMatrix& J) const;
  mutable LuFactor predictor_lu_;   // tangent predictor: symbolic analysis kept along the path
  mutable LltFactor symmetric_llt_; // the symmetric tangent's (tangent_is_cholesky), its matrix() S
  // The last converged state evaluated (see evaluation_at), its evaluation and tangent direction.
  struct StateCache {
    bool valid = false, has_tangent = false;
    Converged key;
    NonlinearStructure::Evaluation ev;
    Eigen::VectorXd t;
    SparseMatrix J;  // workspace of the tangent system (its storage kept between states)
    bool cholesky = false;  // t and the factor are the symmetric tangent's LL^T's
  };
  mutable StateCache cache_;
  mutable long chord_steps_ = 0, chord_fallbacks_ = 0;
};

}  // namespace beamfea
