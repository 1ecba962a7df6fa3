#include "solvers/path/step_control.hpp"

#include <algorithm>
#include <cmath>

namespace beamfea {

StepControl::StepControl(const PathOptions& o, const PathSystem& sys, const Converged& start, double ds0)
    : mode_(o.control), o_(o), sys_(sys) {
  switch (o.control) {
    case PathControl::LoadFactor: h_ = (o.target - start.lambda) / o.increments; break;
    case PathControl::Displacement: h_ = (o.target - value(start)) / o.increments; break;
    case PathControl::ArcLength: h_ = ds0; break;
  }
  h0_ = std::abs(h_);
  if (o.control == PathControl::ArcLength) {
    hmin_ = o.min_arc_length > 0 ? o.min_arc_length : h0_ * kDefaultMinStepRatio;
    hmax_ = o.max_arc_length > 0 ? o.max_arc_length : h0_ * kDefaultMaxArcRatio;
  } else {
    hmin_ = h0_ * kDefaultMinStepRatio;
    hmax_ = h0_ * kMaxIncrementGrowth;
  }
}

double StepControl::value(const Converged& c) const {
  switch (o_.control) {
    case PathControl::LoadFactor: return c.lambda;
    case PathControl::Displacement: return sys_.control_value(c.state);
    case PathControl::ArcLength: return path_length_;
  }
  return 0.0;
}

bool StepControl::target_reached(const Converged& cur) {
  if (mode_ == PathControl::ArcLength) return false;
  const double remaining = o_.target - value(cur);
  const double tol = kTargetTolerance * std::max(1.0, std::abs(o_.target)) + kTargetTolerance * h0_;
  if (std::abs(remaining) <= tol) return true;
  if (std::abs(h_) > std::abs(remaining) || remaining * h_ < 0) h_ = remaining;
  return false;
}

bool StepControl::cut() {
  h_ *= kCutFactor;
  return std::abs(h_) >= hmin_;
}

bool StepControl::fall_back_to_arc_length(const Converged& cur, double ds) {
  if (o_.control != PathControl::Displacement || mode_ != PathControl::Displacement || !(ds > 0.0)) return false;
  const double v = value(cur), toward = o_.target >= v ? 1.0 : -1.0;
  if (!std::isnan(turned_at_) && (v - turned_at_) * toward <= turn_step_) return false;
  turned_at_ = v;
  turn_step_ = std::abs(h_);
  h_disp_ = h0_;
  hmin_disp_ = hmin_;
  hmax_disp_ = hmax_;
  toward_ = toward;
  moved_back_ = false;
  mode_ = PathControl::ArcLength;
  h_ = ds;
  hmin_ = ds * kDefaultMinStepRatio;
  hmax_ = ds * kDefaultMaxArcRatio;
  return true;
}

bool StepControl::resume_displacement(const Converged& prev, const Converged& next) {
  if (o_.control != PathControl::Displacement || mode_ != PathControl::ArcLength) return false;
  const double du = (value(next) - value(prev)) * toward_;
  if (du < 0.0) moved_back_ = true;
  if (!moved_back_ || du <= 0.0) return false;
  mode_ = PathControl::Displacement;
  h_ = toward_ * std::abs(h_disp_);
  hmin_ = hmin_disp_;
  hmax_ = hmax_disp_;
  return true;
}

double adapt_count(const Converged& c) {
  if (!c.by_chord) return static_cast<double>(c.iterations);
  return kChordIterationsPerNewton > 0.0 ? static_cast<double>(c.chord_iterations) / kChordIterationsPerNewton : 0.0;
}

void StepControl::adapt(double iterations) {
  const double ratio = std::sqrt(static_cast<double>(o_.desired_iterations) / std::max(1.0, iterations));
  const double hn = std::clamp(std::abs(h_) * std::clamp(ratio, kMinStepGrowth, kMaxStepGrowth), hmin_, hmax_);
  h_ = h_ < 0 ? -hn : hn;
}

}  // namespace beamfea
