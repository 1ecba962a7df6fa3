#pragma once
// Options in, summary out, for path following (solvers/path_following.hpp): the plain options
// struct with its validate(), the per-step record, the critical points and the result with its
// termination as an enum class (PathTermination) and a one-line brief_report().
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/model.hpp"
#include "elements/beam_mass.hpp"
#include "solvers/kinsol_solver.hpp"
#include "solvers/condensed_stiffness.hpp"
#include "solvers/nonlinear_structure.hpp"

namespace beamfea {

enum class PathControl { LoadFactor, Displacement, ArcLength };

struct PathOptions {
  PathControl control = PathControl::LoadFactor;
  double target = 1.0;            // load control: final load factor; displacement: final value
  int control_node = -1;          // displacement control
  int control_dof = 0;            // 0..5
  int increments = 20;            // load/displacement control: initial number of equal increments
  double arc_length = 0.05;       // arc length: initial ds (a length, solvers/path/path_scales.hpp)
  bool arc_length_auto = false;   // "arc_length": "auto": the first ds from the structure's scales
  double min_arc_length = 0.0;    // 0: first ds * kDefaultMinStepRatio
  double max_arc_length = 0.0;    // 0: first ds * kDefaultMaxArcRatio
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
  // Natural frequencies about every converged state (solvers/path/vibration.hpp): the lowest
  // `frequency_modes` (0: none) with the mass `frequency_mass`.
  int frequency_modes = 0;
  MassKind frequency_mass = MassKind::Consistent;
  KinsolOptions newton;
  // Correct each step by chord iterations on the start state's factor first, full Newton only when
  // they give up (solvers/path/corrector.hpp); false: full Newton at every step.
  bool chord_corrector = true;
  std::function<void(const std::string&)> progress;  // may be empty
  void validate(const Model& model) const;
};

struct PathStep {
  int step = 0;
  double load_factor = 0.0;
  double control = 0.0;             // lambda (load control), the controlled DOF's value, or the path length
  double arc_length = 0.0;          // step size used
  PathControl step_control = PathControl::LoadFactor;  // the kind of step (arc length in a snap-back fall-back)
  long iterations = 0;              // Newton iterations of the step (each an assembly + LU; 0 by chord)
  long chord_iterations = 0;        // chord iterations (solvers/path/corrector.hpp: residual + solves)
  std::vector<Vec6> track;          // per tracked node: (x - X, log R)
  double reaction = 0.0;            // imposed-motion control: reaction of the controlled DOF
  int negative_eigenvalues = -1;
  bool stable = false;
  double min_eigenvalue = 0.0;
  std::optional<Mat6> stiffness;    // stiffness_node: node_stiffness->K when it is ok
  // stiffness_node: the loaded stiffness, compliance, rigid and free directions of the node
  // (solvers/condensed_stiffness.hpp, node_compliance).
  std::optional<CondensedStiffness> node_stiffness;
  NonlinearState state;
  std::vector<Vec12> end_forces;
  // frequency_modes > 0: the lowest natural frequencies about this state (Hz, ascending; negative
  // where omega^2 < 0: unstable), and why they are missing when the eigen-solver failed.
  Eigen::VectorXd frequencies;
  std::string frequencies_failure;
  // Where the path re-decided the redundant constraint rows at this state (PathSystem::reselect):
  // the rows dropped from here on, whose reactions are statically indeterminate (PathResult's
  // statically_indeterminate names those of the reference).
  std::optional<std::vector<std::string>> statically_indeterminate;
};

// Singularity: a singular pose of a closed loop (solvers/path/singularity.hpp).
enum class CriticalPointType { LimitPoint, Bifurcation, Singularity };
// "limit_point", "bifurcation" or "singularity" (the result file's contract).
const char* to_string(CriticalPointType t);

struct CriticalPoint {
  CriticalPointType type = CriticalPointType::Bifurcation;
  double load_factor = 0.0;
  int step = 0;                     // the step at whose end it was detected
  double control = 0.0;
  int negative_before = 0, negative_after = 0;
  double load_work = 0.0;           // |phi . p| / (|phi| |p|)
  double reaction = 0.0;            // imposed motion: the controlled DOF's reaction there
  Eigen::VectorXd mode;             // raw displacement (largest translation 1)
  bool branch_switched = false;
  // Singularity: the joints and nodes of the loop involved (model indices), what it is in words, and
  // whether the path went on through it (false: the path stopped there).
  std::vector<int> joints, nodes;
  std::string what;
  bool passed = false;
};

// Why the path stopped. The first four are a completed path (the target or a stop condition was
// reached); the others are an incomplete one.
enum class PathTermination {
  Succeeded,            // load or displacement control reached its target
  StopLoadFactor,       // "stop": {"load_factor"}
  StopBeyond,           // "stop": {"node", "dof", "beyond"}
  StopSteps,            // "stop": {"steps"}
  MaxSteps,             // max_steps converged steps without reaching the target or a stop
  NoConvergence,        // max_cuts step cuts (or the minimum step) without convergence
  NoForwardSolution,    // arc length: only solutions behind the start were found
  InitialStateFailed,   // the prescribed values could not be imposed at the start
  NoAutomaticStep,      // "arc_length": "auto" found no scale (a singular tangent at the start)
  Singularity,          // no step converged beyond a singular pose of a loop (the last critical point)
  RankChanged,          // a constraint row dropped as redundant departs from its target: the
                        // constraint rank grew away from the pose (singular for the loops) where
                        // the rows were chosen
};
bool is_completed(PathTermination t);

struct PathResult {
  std::vector<PathStep> steps;      // all converged steps; steps[0] is the initial state
  std::vector<CriticalPoint> critical_points;
  PathTermination termination = PathTermination::InitialStateFailed;
  bool completed = false;           // is_completed(termination)
  // What brief_report() quotes: the stop value or the load factor where it failed, a count (stop
  // steps, max_steps, cuts), a label (the stop's node and DOF) or the Newton solver's report.
  double termination_value = 0.0;
  int termination_count = 0;
  std::string termination_detail;
  int free_dofs = 0;
  // LU factorisations (numeric; symbolic analyses) of the path: the Newton iterations' and the
  // converged states' tangent systems (the predictor's, shared by the chord corrector).
  long factorizations = 0, symbolic_analyses = 0;
  // Steps (bisections and branch switches included) solved by the chord corrector, and those where
  // it gave up and full Newton solved the step.
  long chord_steps = 0, chord_fallbacks = 0;
  // Redundant constraint rows (over-constrained loops, supports on one rigid body), dropped from the
  // equations: their reactions are statically indeterminate (e.g. "joint 'jC' uz").
  std::vector<std::string> statically_indeterminate;
  // One line: why the path stopped (the result file's "termination").
  std::string brief_report() const;
  // Sets the termination and `completed`.
  void finish(PathTermination t, double value = 0.0, int count = 0, std::string detail = {});
};

}  // namespace beamfea
