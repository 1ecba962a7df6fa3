#pragma once
// Critical points of a path: detection, location, classification and branch switching.
//
// Detection: a change of the negative-eigenvalue count of the constrained tangent between two
// converged steps (solvers/path/stability.hpp). Location: bisection of the step (arc length, load
// factor or control value) to `critical_tolerance` of the step, each trial state solved from the
// step's start along the step's direction. Classification under arc length: a limit point when the
// load factor turns (dlambda along the path changes sign across the located point), a bifurcation
// otherwise; under load control (where no tangent orientation is known), a limit point when the
// critical mode phi does work on the load pattern (|phi . p| > kLimitLoadWork |phi| |p|). Under
// displacement control, the inertia with the controlled DOF held changes at bifurcations; the
// extrema of the load factor (or of the reaction, imposed motion) are the limit points, found by
// the sign of the conjugate slope (locate_extremum).
// Branch switching (arc-length control): from the last stable state before a bifurcation, the next
// predictor is the critical mode scaled to the arc length (tried at 1, 1/2, 1/4, 1/8 of the step).
#include <Eigen/Core>
#include <functional>
#include <string>

#include "solvers/path/corrector.hpp"
#include "solvers/path/equilibrium.hpp"
#include "solvers/path/factor_cache.hpp"
#include "solvers/path/path_types.hpp"
#include "solvers/path/predictor.hpp"
#include "solvers/path/stability.hpp"

namespace beamfea {

// The mode's normalised work on the load pattern above which a critical point is a limit point.
inline constexpr double kLimitLoadWork = 1e-3;
// At most this many bisections (the tolerance usually stops them first: 2^-10 < 1e-3).
inline constexpr int kMaxBisections = 40;

// The parts a critical-point search works with: the options and the system (read), the factor cache
// (tangents of the bracketing states), the corrector (trial states), the stability analysis and the
// predictor (trial steps).
struct CriticalPointParts {
  const PathOptions& options;
  const PathSystem& system;
  FactorCache& factors;
  Corrector& corrector;
  StabilityAnalyzer& stability;
  Predictor& predictor;
};

// The trial step at fraction f of the step of signed size h from cur, under the step's control `mode`
// (along dir under arc length).
StepPrediction trial_step(const CriticalPointParts& parts, const Converged& cur, double f, double h,
                          const Eigen::VectorXd& dir, PathControl mode);

// A critical point between two converged states, located and classified.
struct LocatedCriticalPoint {
  CriticalPoint point;
  Converged before, after;    // the bracket at the end of the bisection (same count as the start / end)
  double lo = 0.0, hi = 1.0;  // the bracket as fractions of the step
  Eigen::VectorXd mode;       // the critical mode over the free coordinates (empty when not found)
};

// cur -> next: the step of signed size h (direction dir under arc length); neg_before/after the
// negative-eigenvalue counts at cur and next; control: whether the controlled DOF is held
// (displacement control); mode: the step's control (arc length in a snap-back fall-back of displacement
// control). control_at(c, fraction): the path's control value of a state at that fraction of the step.
LocatedCriticalPoint locate_critical_point(const CriticalPointParts& parts, const Converged& cur, const Converged& next,
                                           double h, const Eigen::VectorXd& dir, int neg_before, int neg_after,
                                           ControlDof control, PathControl mode,
                                           const std::function<double(const Converged&, double)>& control_at);

// Displacement control: an extremum of the load factor (or, for imposed motion, of the controlled
// DOF's reaction) between cur and next, where conjugate_slope (solvers/path/factor_cache.hpp) changes sign
// (slope_before its value at cur; the step of signed size h under the step's control `mode`, along dir
// under arc length). Located by bisection on the sign of the slope; a limit point; the
// counts and the mode are those of the structure with the controlled DOF released (the structure
// under its load, whose inertia changes there).
LocatedCriticalPoint locate_extremum(const CriticalPointParts& parts, const Converged& cur, const Converged& next,
                                     double h, double slope_before, const Eigen::VectorXd& dir, PathControl mode,
                                     const std::function<double(const Converged&, double)>& control_at);

// The outcome of a branch switch: the first state on the secondary branch, the arc length of that
// step and its direction [Delta_f, dlambda]; or the last solver report when no fraction converged.
struct BranchSwitch {
  bool switched = false;
  Converged state;
  double ds = 0.0;
  Eigen::VectorXd direction;
  std::string report;
};

// Branch switching from the last stable state `from` along `mode` (free coordinates) with the arc
// length |h| (or a fraction of it).
BranchSwitch switch_branch(const CriticalPointParts& parts, const Converged& from, const Eigen::VectorXd& mode,
                           double h);

}  // namespace beamfea
