#include "solvers/path/step_control.hpp"

#include <algorithm>
#include <cmath>

namespace beamfea {

StepControl::StepControl(const PathOptions& o, const PathEquilibrium& eq, const Converged& start, double ds0)
    : mode(o.control), o_(o), eq_(eq) {
  switch (o.control) {
    case PathControl::LoadFactor: h = (o.target - start.lambda) / o.increments; break;
    case PathControl::Displacement: h = (o.target - value(start)) / o.increments; break;
    case PathControl::ArcLength: h = ds0; break;
  }
  h0 = std::abs(h);
  if (o.control == PathControl::ArcLength) {
    hmin = o.min_arc_length > 0 ? o.min_arc_length : h0 * kDefaultMinStepRatio;
    hmax = o.max_arc_length > 0 ? o.max_arc_length : h0 * kDefaultMaxArcRatio;
  } else {
    hmin = h0 * kDefaultMinStepRatio;
    hmax = h0 * kMaxIncrementGrowth;
  }
}

double StepControl::value(const Converged& c) const {
  switch (o_.control) {
    case PathControl::LoadFactor: return c.lambda;
    case PathControl::Displacement: return eq_.control_value(c.state);
    case PathControl::ArcLength: return path_length;
  }
  return 0.0;
}

bool StepControl::target_reached(const Converged& cur) {
  if (mode == PathControl::ArcLength) return false;
  const double remaining = o_.target - value(cur);
  const double tol = kTargetTolerance * std::max(1.0, std::abs(o_.target)) + kTargetTolerance * h0;
  if (std::abs(remaining) <= tol) return true;
  if (std::abs(h) > std::abs(remaining) || remaining * h < 0) h = remaining;
  return false;
}

bool StepControl::cut() {
  h *= kCutFactor;
  return std::abs(h) >= hmin;
}

bool StepControl::fall_back_to_arc_length(const Converged& cur, double ds) {
  if (o_.control != PathControl::Displacement || mode != PathControl::Displacement || !(ds > 0.0)) return false;
  h_disp_ = h0;
  hmin_disp_ = hmin;
  hmax_disp_ = hmax;
  toward_ = o_.target >= value(cur) ? 1.0 : -1.0;
  moved_back_ = false;
  mode = PathControl::ArcLength;
  h = ds;
  hmin = ds * kDefaultMinStepRatio;
  hmax = ds * kDefaultMaxArcRatio;
  return true;
}

bool StepControl::resume_displacement(const Converged& prev, const Converged& next) {
  if (o_.control != PathControl::Displacement || mode != PathControl::ArcLength) return false;
  const double du = (value(next) - value(prev)) * toward_;
  if (du < 0.0) moved_back_ = true;
  if (!moved_back_ || du <= 0.0) return false;
  mode = PathControl::Displacement;
  h = toward_ * std::abs(h_disp_);
  hmin = hmin_disp_;
  hmax = hmax_disp_;
  return true;
}

double adapt_count(const Converged& c) {
  if (!c.by_chord) return static_cast<double>(c.iterations);
  return kChordIterationsPerNewton > 0.0 ? static_cast<double>(c.chord_iterations) / kChordIterationsPerNewton : 0.0;
}

void StepControl::adapt(double iterations) {
  const double ratio = std::sqrt(static_cast<double>(o_.desired_iterations) / std::max(1.0, iterations));
  const double hn = std::clamp(std::abs(h) * std::clamp(ratio, kMinStepGrowth, kMaxStepGrowth), hmin, hmax);
  h = h < 0 ? -hn : hn;
}

}  // namespace beamfea
