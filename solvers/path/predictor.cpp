#include "solvers/path/predictor.hpp"

#include <algorithm>
#include <cmath>

namespace beamfea {

namespace {
// Below this |dU_c/dlambda| (or |d|_W^2) the tangent gives no usable predictor: the start values are
// the guess (denormal-safe guard against division by zero, not a tolerance on the physics).
constexpr double kTinyPredictorRate = 1e-300;
}  // namespace

StepPrediction Predictor::predict(const Converged& c, PathControl control, double h) {
  const PathSystem& P = sys_;
  const Eigen::VectorXd t = factors_.tangent(P, c);
  const int nf = P.nf(), nc = P.nc();
  StepPrediction out;
  StepSpec& s = out.spec;
  Eigen::VectorXd& u = out.u;
  if (control == PathControl::LoadFactor) {
    s.kind = StepKind::Load;
    s.lambda = c.lambda + h;
    u = P.start_unknowns(c, s);
    if (t.size()) u.head(nf + nc) += h * t.head(nf + nc);
    return out;
  }
  if (control == PathControl::Displacement) {
    s.kind = StepKind::Control;
    s.control = P.control_value(c.state) + h;
    u = P.start_unknowns(c, s);
    if (!t.size()) return out;
    if (P.has_loads()) {
      // Change of the controlled DOF per unit load factor.
      double rate = 0.0;
      for (const auto& [k, v] : P.control_row(c.state)) rate += v * t[k];
      if (std::abs(rate) < kTinyPredictorRate) return out;
      const double dl = h / rate;
      u.head(nf + nc) += dl * t.head(nf + nc);
      u[nf + nc] += dl;
    } else {
      u += h * t;
    }
    return out;
  }
  return arc_step(c, h, t, nullptr);
}

StepPrediction Predictor::predict_along(const Converged& c, double h, const Eigen::VectorXd& direction) {
  return arc_step(c, h, factors_.tangent(sys_, c), &direction);
}

StepPrediction Predictor::arc_step(const Converged& c, double h, const Eigen::VectorXd& t,
                                   const Eigen::VectorXd* direction) const {
  const PathSystem& P = sys_;
  const int nf = P.nf(), nc = P.nc();
  StepPrediction out;
  StepSpec& s = out.spec;
  s.kind = StepKind::Arc;
  s.lambda = c.lambda;
  s.ds = h;
  Eigen::VectorXd& u = out.u;
  u = P.start_unknowns(c, s);
  Eigen::VectorXd d;  // [Delta_f, dlambda] direction
  // The tangent's rates are per unit load factor (loads), or per unit of the controlled DOF (an
  // imposed motion alone: the arc-length steps of its snap-back fall-back, where d's last entry is
  // the reaction's rate, outside the metric: psi is 0 without loads).
  double along = 1.0;  // the sign of d against the tangent
  if (direction) {
    d = *direction;
  } else if (t.size()) {
    d.resize(nf + 1);
    d.head(nf) = t.head(nf);
    d[nf] = P.has_loads() ? 1.0 : t[nf + nc];
    if (previous_.size() && P.arc_dot(d, previous_) < 0.0) {
      d = -d;
      along = -1.0;
    }
  } else if (previous_.size()) {
    d = previous_;  // secant predictor where the tangent is singular
  } else {
    d = Eigen::VectorXd::Zero(nf + 1);
    d[nf] = 1.0;
  }
  const double a = h / std::sqrt(std::max(P.arc_dot(d, d), kTinyPredictorRate));
  u.head(nf) += a * d.head(nf);
  u[nf + nc] += a * d[nf];
  if (t.size() && !direction) u.segment(nf, nc) += a * along * t.segment(nf, nc);
  return out;
}

}  // namespace beamfea
