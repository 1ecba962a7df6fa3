#pragma once
// The bordered equilibrium system of one path step (PathSystem): an immutable description of the
// structure, its numbering, constraints and scales, set up once per path; the factorisations live in
// solvers/path/factor_cache.hpp and the Newton solve in solvers/path/corrector.hpp.
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
//               rotations; psi^2 is the path's own scale (PathSystem::with_scales, solvers/path/path_scales.hpp).
// Closed loops (solvers/nonlinear_structure.hpp, "Closed loops"): the closures' rows c(x) = 0 join the
// slave constraints, with multipliers mu_l; the residual gains B^T mu_l and the tangent the closure
// curvature contracted with mu_l. Redundant rows among the slave constraints and the closures (a
// planar loop in 3-D: three) are found rank-revealingly at the reference state (independent_rows,
// rows and coordinates scaled to lengths by the model length L) and dropped: the motion is solved
// exactly with the independent rows; the dropped rows' reactions are statically indeterminate
// (`redundant` names them) and reported as zero. The path re-decides them where the rows kept stop
// spanning the constraint rows at a pose (reselect).
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
#include "solvers/nonlinear_structure.hpp"
#include "solvers/path/path_types.hpp"

namespace beamfea {

// A raw DOF held at a value: supports or imposed values on slave nodes, or the controlled DOF; or a
// linear row of such values (the user rows of core/dof_map.hpp: a skewed support's axis, a tie, a
// linear constraint): sum_i coefficient_i value(node_i, comp_i) = target, where a node's value is
// its displacement x - X (comp 0..2) or its rotation vector log(R) (comp 3..5).
struct ConstraintDef {
  int node = -1, comp = 0;  // the held DOF (a general row: its first term's)
  double target = 0.0;
  struct Term {
    int node = -1, comp = 0;
    double coefficient = 1.0;
  };
  std::vector<Term> terms;  // a general row's terms; empty: value(node, comp) = target
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

// Whether the controlled DOF is held by a row of its own (displacement control's inertia, an
// imposed motion's vibrations) or left free.
enum class ControlDof { Free, Held };
// Whether an evaluation assembles the tangent (NonlinearStructure::evaluate's with_tangent).
enum class TangentWanted { No, Yes };

class PathSystem {
 public:
  // The controlled DOF is taken from the options under displacement control. Throws ModelError when
  // the controlled DOF is supported, or when the model has no loads and the control is not a
  // displacement. The force scale is the reference load's (load factor 1) and psi = 0 until
  // with_scales.
  // `loads`: the reference load (load factor 1), a case or combination of the model or its default
  // loads; held by reference, it must outlive the system.
  PathSystem(const Model& model, const LoadSet& loads, const PathOptions& o);
  PathSystem(const Model& model, const PathOptions& o) : PathSystem(model, model.default_loads(), o) {}
  // This system with the path's own scales (solvers/path/path_scales.hpp): the force scale of the
  // convergence test at the load factor lambda_ref (not below the round-off floor; kept when
  // lambda_ref is not positive) and the arc-length weight psi of the load factor. Set once, before
  // the steps; the structure moves into the result.
  PathSystem with_scales(double lambda_ref, double psi) &&;

  // The structure, its numbering and constraints.
  const NonlinearStructure& structure() const { return ns_; }
  const Model& model() const { return ns_.model(); }
  const LoadSet& loads() const { return *loads_; }  // the reference load
  int nf() const { return nf_; }     // free independent coordinates
  int nc() const { return nc_; }     // multipliers: independent slave constraints, then closure rows
  const std::vector<int>& free_gens() const { return free_; }      // free coordinate -> gen
  int free_index(int gen) const { return gen_to_free_[gen]; }       // gen -> free coordinate (-1: held)
  const std::vector<ConstraintDef>& constraints() const { return cons_; }  // the first ncs multipliers
  const std::vector<int>& closure_rows() const { return closure_rows_; }   // the next ones
  // The dropped rows: statically indeterminate reactions (reported as zero).
  const std::vector<std::string>& redundant() const { return redundant_; }
  // How far the dropped rows are from their targets at a state: the largest departure (translation
  // rows over L, rotation rows in radians: free of units) and the row's name (redundant()). Rows
  // dependent at the reference stay satisfied wherever the constraint rank stays that of the
  // reference (they are functions of the kept rows there); one that departs shows that the rank grew
  // away from a reference pose singular for the loops (a flat change-point four-bar: its closure's
  // row along the links vanishes to first order there, not beyond), and that a solution with the
  // reference's rows alone opens the loop.
  struct Departure {
    double value = 0.0;
    std::string row;
  };
  Departure dropped_row_departure(const NonlinearState& st) const;
  const ConstraintDef& controlled() const { return ctrl_; }
  bool has_loads() const { return has_loads_; }

  // Re-deciding the redundant rows along the path. Where the rank of the constraint rows stays that
  // of the reference, the rows kept there still span them at most poses, but not at every one: the
  // rows of a spatial over-constrained loop (a Bennett linkage: six closure rows of rank three) are
  // dependent in combinations that turn with the pose, so that a choice of three rows good at the
  // reference can lose rank where the loop itself does not. The kept rows' Jacobian is then singular
  // (Newton fails, or a singularity is reported that the linkage does not have) and beyond it they
  // no longer hold the loop closed. A fresh rank-revealing selection at the state (independent_rows
  // over all the rows) does.
  // All the rows at a state: their rank (independent_rows), the nc() rows a rank-revealing QR with
  // column pivoting leads with (a fresh choice of as many rows as are kept), and the smallest
  // singular value of the kept rows and of the fresh choice's (rows and coordinates scaled to
  // lengths, as at the reference: free of units).
  struct RowsAt {
    int rank = 0;
    RowSelection fresh;  // into all the rows: the slave constraints, then the structure's closure rows
    double kept = 0.0, best = 0.0;
    bool same_as_kept = false;  // the fresh choice is the rows kept now
  };
  RowsAt rows_at(const NonlinearState& st) const;
  // How many singular values of all the rows at a state (scaled) exceed sigma: the rank that a
  // departure of sigma from the constraints cannot have made (an open loop's rows gain rank with
  // its opening).
  int rank_above(const NonlinearState& st, double sigma) const;
  // The nc()-th singular value of all the rows at a state (scaled): zero where they lose the rank
  // of the rows kept, whichever rows are kept.
  double rank_measure(const NonlinearState& st) const;
  // All the rows at a state (RowsAt::fresh's numbering: the slave constraints, then the structure's
  // closure rows from closure_row_offset()), over the free coordinates, scaled to lengths: rotation
  // rows times L, rotation coordinates' columns over L (free of units).
  Eigen::MatrixXd scaled_rows(const NonlinearState& st) const;
  int closure_row_offset() const { return static_cast<int>(all_cons_.size()); }
  // Whether rows were dropped (only then can the selection change without the rank changing).
  bool has_dropped_rows() const { return !dropped_.empty(); }
  // Keeps `fresh`'s rows from here on (rows_at(st).fresh, of the same rank as nc()) and returns the
  // multipliers on them that transmit the same generalized forces at st as mu on the rows kept
  // until now (least squares, exact where both sets span the rows), so that a converged state stays
  // converged.
  Eigen::VectorXd reselect(const NonlinearState& st, const Eigen::VectorXd& mu, const RowSelection& fresh);

  // Scales: the model length L, the force scale of the convergence test, psi^2 of the arc length.
  double length_scale() const { return L_; }
  double force_scale() const { return F_ref_; }
  double psi2() const { return psi2_; }

  int unknowns(const StepSpec& s) const { return nf_ + nc_ + (s.kind == StepKind::Load ? 0 : 1); }
  bool extra_is_lambda(const StepSpec& s) const {
    return has_loads_ && (s.kind == StepKind::Arc || s.kind == StepKind::Control);
  }
  // Arc-length weight of a free coordinate: 1 on translations, L^2 on rotations.
  double weight(int gen) const { return ns_.is_rotation(gen) ? L_ * L_ : 1.0; }
  // sum_k W_k a_k b_k over the free coordinates of a and b (the first nf entries).
  double weighted_dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;
  // Dot product of two directions [Delta_f (nf), dlambda] in the arc-length metric (W on Delta,
  // psi^2 on dlambda).
  double arc_dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
    return weighted_dot(a, b) + psi2_ * a[nf_] * b[nf_];
  }
  // The direction [Delta_f, dlambda] of a converged step from a to b.
  Eigen::VectorXd direction(const Converged& a, const Converged& b) const;
  // Increment of the free coordinates from a to b (translations exact, spins by the logarithm).
  Eigen::VectorXd increment(const Converged& a, const Converged& b) const;
  Eigen::VectorXd increment(const NonlinearState& a, const NonlinearState& b) const;
  // The state at fraction f of the increment from a to b (a (+) f increment(a, b)): off the
  // constraints to second order in the distance.
  NonlinearState between(const NonlinearState& a, const NonlinearState& b, double f) const;

  // The value of a constrained raw DOF at a state (translation from the reference, or log R).
  double constraint_value(const NonlinearState& st, const ConstraintDef& c) const;
  double control_value(const NonlinearState& st) const { return constraint_value(st, ctrl_); }
  Eigen::VectorXd delta_gens(const Eigen::VectorXd& u) const;
  // Unknowns at the start of a step.
  Eigen::VectorXd start_unknowns(const Converged& c, const StepSpec& s) const;
  // The spec of the tangent system at a converged state (no extra row with loads; the controlled
  // DOF held, its reaction the extra unknown, under an imposed motion).
  StepSpec tangent_spec(const Converged& c) const;

  // The state, load factor and applied forces of the unknowns u of step s from start.
  struct Eval {
    NonlinearState st;
    double lambda;
    Eigen::VectorXd f_app;
    Eigen::VectorXd mu_closure;   // multipliers of all closure rows (zero on the dropped ones)
  };
  Eval state_of(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u) const;
  // The structure's evaluation there (residual, tangent when wanted, end forces).
  NonlinearStructure::Evaluation evaluate(const Eval& e, TangentWanted tangent) const;
  // The residual F(u) and Jacobian J(u) of step s from start (KINSOL's functions).
  Eigen::VectorXd residual(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u) const;
  SparseMatrix jacobian(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u) const;
  // J from the state e = state_of(start, s, u) and the structure's tangent there (jacobian's second
  // half; the factor cache's tangent system).
  SparseMatrix jacobian_from(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u, const Eval& e,
                             const SparseMatrix& tangent) const;
  // Row scales of the convergence test.
  Eigen::VectorXd fscale(const StepSpec& s) const;

  // Sparse row of a constraint over the free coordinates at a state (D applied when given).
  std::vector<std::pair<int, double>> constraint_row(const NonlinearState& st, const std::vector<Twist>& tw,
                                                     const ConstraintDef& c, const SparseMatrix* D) const;
  // The controlled DOF's row over the free coordinates at a state.
  std::vector<std::pair<int, double>> control_row(const NonlinearState& st) const {
    return constraint_row(st, ns_.twists(st), ctrl_, nullptr);
  }
  // Constraint rows (nc [+ the controlled DOF's]) over the free coordinates at a state, dense.
  Eigen::MatrixXd constraint_matrix(const NonlinearState& st, ControlDof control) const;
  // The reference load at a state over raw DOFs: f_ext with the dead member loads' consistent
  // vector following the chords (NonlinearStructure::dead_load_change).
  Eigen::VectorXd load_at(const NonlinearState& st) const;
  // Reduced load pattern T^T f_ext over the free coordinates at a state.
  Eigen::VectorXd load_pattern(const NonlinearState& st) const;
  // Multipliers of all closure rows from the unknowns' multipliers (nc of them).
  Eigen::VectorXd closure_multipliers(const Eigen::VectorXd& mu) const;
  // The state at the start of the path before its prescribed values are solved for: the reference
  // with the prescribed independent values imposed; `settled` false when a prescribed value or a
  // slave constraint's target is non-zero (solvers/path/corrector.hpp's initial_state solves then).
  struct Start {
    Converged state;
    bool settled = true;
  };
  Start reference_start() const;

 private:
  // Keeps the rows `kept` of all the rows (ascending) and drops the others.
  void keep_rows(const RowSelection& sel);
  // The generalized force over the free coordinates of each multiplier at a state (nf x nc: the
  // multipliers' columns of the Jacobian at Delta = 0).
  Eigen::MatrixXd multiplier_forces(const NonlinearState& st) const;
  // The force scale of the convergence test at the load factor lambda_ref.
  void set_load_scale(double lambda_ref);

  NonlinearStructure ns_;
  const LoadSet* loads_;
  double L_ = 1.0, F_ref_ = 1.0, psi2_ = 0.0;
  double f_max_ = 0.0;    // largest reference load component (moments / L)
  double F_floor_ = 0.0;  // round-off: kRoundOffForceRatio x the stiffest element's force for a displacement L
  std::vector<int> free_, gen_to_free_;
  std::vector<ConstraintDef> all_cons_;  // every slave constraint, kept or dropped
  std::vector<ConstraintDef> cons_;      // the kept ones
  std::vector<int> kept_;                // the kept rows, into all the rows (RowsAt::fresh's numbering)
  std::vector<int> closure_rows_;   // independent closure rows, into the structure's closure rows
  std::vector<std::string> redundant_;
  // The dropped rows, in redundant_'s order: a slave constraint (its definition) or a closure row.
  struct Dropped {
    ConstraintDef constraint;
    int closure_row = -1;  // >= 0: a closure row (structure numbering), else `constraint`
  };
  std::vector<Dropped> dropped_;
  int ncs_ = 0;
  ConstraintDef ctrl_;
  Eigen::VectorXd f_ext_;
  bool has_loads_ = false;
  int nf_ = 0, nc_ = 0;
};

}  // namespace beamfea
