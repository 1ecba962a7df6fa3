#include "solvers/path/step_control.hpp"

#include <algorithm>
#include <cmath>

namespace beamfea {

double arc_length_scaling(const PathEquilibrium& eq, const Converged& start) {
  const Eigen::VectorXd t = eq.tangent(start);
  const double tw = t.size() ? eq.weighted_dot(t, t) : 0.0;
  return std::max(tw, eq.L * eq.L);
}

StepControl::StepControl(const PathOptions& o, const PathEquilibrium& eq, const Converged& start) : o_(o), eq_(eq) {
  switch (o.control) {
    case PathControl::LoadFactor: h = (o.target - start.lambda) / o.increments; break;
    case PathControl::Displacement: h = (o.target - value(start)) / o.increments; break;
    case PathControl::ArcLength: h = o.arc_length; break;
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
  if (o_.control == PathControl::ArcLength) return false;
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

void StepControl::adapt(long iterations) {
  const double ratio = std::sqrt(static_cast<double>(o_.desired_iterations) / std::max<long>(1, iterations));
  const double hn = std::clamp(std::abs(h) * std::clamp(ratio, kMinStepGrowth, kMaxStepGrowth), hmin, hmax);
  h = h < 0 ? -hn : hn;
}

}  // namespace beamfea
