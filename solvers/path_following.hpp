#pragma once
// Path following of the geometrically nonlinear structure (solvers/nonlinear_structure.hpp):
// load, displacement or arc-length control, stability at every converged step, critical points
// located by bisection and classified, branch switching and imperfections.
//
// Equilibrium: r(x, lambda) = T^T (f_int - lambda f_ext - reactions) = 0 over the free independent
// coordinates, with supports or imposed values on slave nodes as constraints c(x) = c_0 whose
// multipliers are the reactions. Each step solves for the increment Delta about the step's start
// state, state = start (+) Delta (x + du, exp(dw) R, q + dq), with SUNDIALS KINSOL and UMFPACK
// (solvers/kinsol_solver.hpp); the Jacobian is K_t * D(Delta), D the derivative of the retraction.
//
// Controls (the extra equation and unknown):
//   load factor    lambda prescribed per increment;
//   displacement   u_c(x) = s prescribed; unknown lambda when the model has loads (classic
//                  displacement control), otherwise the reaction of the controlled DOF (imposed
//                  motion: the lumped-model use case, e.g. the end of a chain pushed to a point);
//   arc length     Crisfield's spherical constraint |Delta|_W^2 + psi^2 Delta lambda^2 = ds^2 (W: 1 on
//                  translations, L^2 on rotations, L the model size), psi^2 = max(|t|_W^2, L^2) with t the
//                  initial tangent displacement per unit load factor; the predictor's sign follows the previous step
//                  direction (t . Delta_prev > 0); ds adapts to the Newton iteration count.
// Non-convergence: the step is cut (halved) up to max_cuts times; then the path stops with the
// reason in `termination`; every converged step is kept.
//
// Stability (the FEA form of Pashkevich et al. eqs. 18-23): at every converged state the tangent is
// restricted to the null space Z of the constraint Jacobian (eq. 19-21; Z by exact elimination),
// symmetrised, and its inertia counted by a sparse LDL^T (Sylvester's law of inertia): stable when it
// has no negative eigenvalue (eq. 23: the second variation of the energy is positive on all admissible
// variations). min_eigenvalue is the lowest eigenvalue of the Jacobi-scaled matrix (dimensionless).
// The loaded Cartesian stiffness of a node (eq. 28 in FEA form) is the condensed tangent
//   [ K_t  T_n^T ; T_n  0 ] [X; M] = [0; I],  K_c = -M.
//
// Critical points: a change of the negative-eigenvalue count between two steps; located by bisection
// of the step (arc length, load factor or control value) to `critical_tolerance` of the step; a limit
// point when the critical mode phi does work on the load pattern (|phi . p| > 1e-3 |phi| |p|), a
// bifurcation otherwise. Branch switching (arc-length control): from the last stable state before a
// bifurcation, the next predictor is the critical mode scaled to the arc length.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/model.hpp"
#include "solvers/kinsol_solver.hpp"
#include "solvers/nonlinear_structure.hpp"

namespace beamfea {

enum class PathControl { LoadFactor, Displacement, ArcLength };

struct PathOptions {
  PathControl control = PathControl::LoadFactor;
  double target = 1.0;            // load control: final load factor; displacement: final value
  int control_node = -1;          // displacement control
  int control_dof = 0;            // 0..5
  int increments = 20;            // load/displacement control: initial number of equal increments
  double arc_length = 0.05;       // arc length: initial ds
  double min_arc_length = 0.0;    // 0: arc_length * 1e-4
  double max_arc_length = 0.0;    // 0: arc_length * 10
  int desired_iterations = 5;
  int max_cuts = 10;
  int max_steps = 500;
  // Stops.
  std::optional<double> stop_load_factor;
  int stop_node = -1, stop_dof = 0;
  std::optional<double> stop_beyond;
  std::optional<int> stop_steps;
  // Stability and critical points.
  bool stability = true;
  bool locate_critical = true;
  double critical_tolerance = 1e-3;  // of the step
  bool branch_switch = false;
  int stiffness_node = -1;
  // Imperfection: seed the geometry with linear buckling mode `imperfection_mode` (1-based) with the
  // largest nodal translation equal to `imperfection_amplitude`.
  int imperfection_mode = 0;
  double imperfection_amplitude = 0.0;
  std::vector<int> track;           // nodes whose displacements are recorded
  KinsolOptions newton;
  std::function<void(const std::string&)> progress;  // may be empty
  void validate(const Model& model) const;
};

struct PathStep {
  int step = 0;
  double load_factor = 0.0;
  double control = 0.0;             // lambda (load control), the controlled DOF's value, or the path length
  double arc_length = 0.0;          // step size used
  long iterations = 0;
  std::vector<Vec6> track;          // per tracked node: (x - X, log R)
  double reaction = 0.0;            // imposed-motion control: reaction of the controlled DOF
  int negative_eigenvalues = -1;
  bool stable = false;
  double min_eigenvalue = 0.0;
  std::optional<Mat6> stiffness;
  NonlinearState state;
  std::vector<Vec12> end_forces;
};

struct CriticalPoint {
  std::string type;                 // "limit_point" or "bifurcation"
  double load_factor = 0.0;
  int step = 0;                     // the step at whose end it was detected
  double control = 0.0;
  int negative_before = 0, negative_after = 0;
  double load_work = 0.0;           // |phi . p| / (|phi| |p|)
  Eigen::VectorXd mode;             // raw displacement (largest translation 1)
  bool branch_switched = false;
};

struct PathResult {
  std::vector<PathStep> steps;      // all converged steps; steps[0] is the initial state
  std::vector<CriticalPoint> critical_points;
  std::string termination;
  bool completed = false;           // reached the target or a stop condition (not a failure)
  int free_dofs = 0;
  long factorizations = 0, symbolic_analyses = 0;
};

// The model (possibly with an imperfection applied) and the path. The returned Model copy is needed
// to interpret node displacements when an imperfection moved nodes.
PathResult follow_path(const Model& model, const PathOptions& options);

// The model with buckling mode `mode` (1-based) added to its node positions at `amplitude`.
Model imperfect_model(const Model& model, int mode, double amplitude);

// Stability of a state: inertia and lowest eigenvalue of the constrained symmetrised tangent.
struct StabilityInfo {
  int negative = 0;
  double min_eigenvalue = 0.0;
  Eigen::VectorXd mode;             // over the free independent coordinates (Z applied), when asked
};

}  // namespace beamfea
