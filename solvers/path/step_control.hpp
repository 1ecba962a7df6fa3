#pragma once
// The step controls of a path: what a step prescribes (a load factor, a value of the controlled DOF
// or an arc length), its size, its cuts on failure and its adaptation to the Newton iteration count.
//
//   load factor    h = (target - lambda_0) / increments, bounded by h0 * kMaxIncrementGrowth;
//   displacement   h = (target - u_0) / increments, idem;
//   arc length     h = ds, within [min_arc_length, max_arc_length] (defaults relative to the first ds).
// After a converged step h <- h * clamp(sqrt(desired / iterations), 1/2, 2) (Crisfield 1991, vol. 1,
// eq. 9.40 with the exponent 1/2); after a failure h <- h / 2.
#include <cmath>

#include <Eigen/Core>

#include "solvers/path/equilibrium.hpp"
#include "solvers/path/path_types.hpp"

namespace beamfea {

// Default step bounds, relative to the first step h0.
inline constexpr double kDefaultMinStepRatio = 1e-4;   // hmin = h0 * 1e-4 (all controls)
inline constexpr double kDefaultMaxArcRatio = 10.0;    // arc length: hmax = 10 ds
inline constexpr double kMaxIncrementGrowth = 4.0;     // load/displacement: hmax = 4 h0
// Adaptation after a converged step: the factor sqrt(desired / iterations) is clamped to these.
inline constexpr double kMinStepGrowth = 0.5;
inline constexpr double kMaxStepGrowth = 2.0;
inline constexpr double kCutFactor = 0.5;              // a failed step is halved
// Arc length: a converged point farther than this fraction of the step from its predictor (in the
// arc-length metric) is rejected and the step cut: on a smooth path the corrector moves by
// O(ds^2 x curvature); a Newton iteration that jumped to another branch moves by the jump.
inline constexpr double kMaxCorrectorRatio = 0.5;
// The target of load/displacement control is reached within this fraction of max(1, |target|)
// (plus the same fraction of the first step).
inline constexpr double kTargetTolerance = 1e-12;

// The iteration count a converged step feeds to StepControl::adapt. A step full Newton solved (the
// chord corrector gave up, or is off): its Newton iterations, the chord's wasted ones not counted.
// A step the chord corrector solved (solvers/path/corrector.hpp): its chord iterations divided by
// kChordIterationsPerNewton, i.e. two chord iterations count as one Newton iteration. Measured:
// the steps full Newton solves in 2 iterations take 2-3 chord iterations on the frames of
// bench_path_step and up to 6 on Williams' toggle; with this count the path tests take the same
// steps as with full Newton (deep arch: limit point at step 63; Lee's frame: 15 and 30; Williams'
// toggle: 5 steps), where counting each chord iteration as one shrank the toggle's steps (8 steps).
// Since the count reaches desired_iterations (5) only at 10 chord iterations, beyond the chord's
// limit (kMaxChordIterations, 8), the steps grow under the chord until it gives up and full Newton's
// count takes over: the step sizes stay those of full Newton's regime.
inline constexpr double kChordIterationsPerNewton = 2.0;
double adapt_count(const Converged& c);

class StepControl {
 public:
  // ds0: the first arc length (the user's, or the automatic one of solvers/path/path_scales.hpp).
  StepControl(const PathOptions& o, const PathSystem& sys, const Converged& start, double ds0);

  // The path's control value at a state: lambda, the controlled DOF, or the path length so far.
  double value(const Converged& c) const;
  // Load/displacement control: true when the target is reached; otherwise the step is clipped so
  // as not to overshoot it. Arc length: always false.
  bool target_reached(const Converged& cur);
  // Halves the step; false when it falls below the minimum.
  bool cut();
  // A step of size h was accepted: the path length grows by |h|.
  void advance() { path_length_ += std::abs(h_); }
  // A branch switch replaced the last step: the path length at the first secondary state, and the
  // arc length ds of the step onto it (the next step's size, with the current direction's sign).
  void restart_at(double path_length, double ds) {
    path_length_ = path_length;
    h_ = h_ < 0 ? -ds : ds;
  }
  // Adapts h to the iteration count of the last converged step, within [hmin, hmax].
  void adapt(double iterations);

  // Displacement control through a snap-back of the controlled DOF (where it turns back, no step
  // toward the target converges): the steps go on under arc length (first step ds, bounds relative
  // to it) until the controlled DOF, having moved back, moves toward its target again; then
  // displacement control resumes with its last step. False when not under displacement control,
  // and when the controlled DOF turns back again without having passed its last turn by more than
  // the smallest step that failed there (a bound it cannot pass: the target is out of reach).
  bool fall_back_to_arc_length(const Converged& cur, double ds);
  // After an accepted step from prev to next: true when displacement control resumes.
  bool resume_displacement(const Converged& prev, const Converged& next);

  double last_turn() const { return turned_at_; }  // the controlled DOF's last turn back (NaN: none)
  PathControl mode() const { return mode_; }  // the control of the next step (o.control, or ArcLength in a fall-back)
  double h() const { return h_; }             // signed step (load factor, control value or arc length)
  double path_length() const { return path_length_; }  // arc length: sum of the accepted |h|

 private:
  PathControl mode_;
  double h_ = 0.0;
  double h0_ = 0.0, hmin_ = 0.0, hmax_ = 0.0;
  double path_length_ = 0.0;
  const PathOptions& o_;
  const PathSystem& sys_;
  // Fall-back state: the displacement step and bounds to restore, the direction of the target,
  // whether the controlled DOF has moved away from it yet.
  double h_disp_ = 0.0, hmin_disp_ = 0.0, hmax_disp_ = 0.0;
  double toward_ = 1.0;
  bool moved_back_ = false;
  // Where the controlled DOF last turned back, and the smallest step that failed beyond it.
  double turned_at_ = NAN, turn_step_ = 0.0;
};

}  // namespace beamfea
