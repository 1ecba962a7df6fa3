#include "solvers/path/predictor.hpp"

#include <algorithm>
#include <cmath>

namespace beamfea {

namespace {
// Below this |dU_c/dlambda| (or |d|_W^2) the tangent gives no usable predictor: the start values are
// the guess (denormal-safe guard against division by zero, not a tolerance on the physics).
constexpr double kTinyRate = 1e-300;
}  // namespace

double Predictor::arc_dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
  const int nf = eq_.nf;
  return eq_.weighted_dot(a, b) + eq_.psi2 * a[nf] * b[nf];
}

Eigen::VectorXd Predictor::direction(const Converged& a, const Converged& b) const {
  Eigen::VectorXd d(eq_.nf + 1);
  d.head(eq_.nf) = eq_.increment(a, b);
  d[eq_.nf] = b.lambda - a.lambda;
  return d;
}

void Predictor::make_step(const Converged& c, double hh, StepSpec& s, Eigen::VectorXd& u, const Eigen::VectorXd* dir) const {
  const PathEquilibrium& P = eq_;
  const Eigen::VectorXd t = P.tangent(c);
  if (control == PathControl::LoadFactor) {
    s.kind = StepKind::Load;
    s.lambda = c.lambda + hh;
    u = P.start_unknowns(c, s);
    if (t.size()) u.head(P.nf + P.nc) += hh * t.head(P.nf + P.nc);
    return;
  }
  if (control == PathControl::Displacement) {
    s.kind = StepKind::Control;
    s.control = P.control_value(c.state) + hh;
    u = P.start_unknowns(c, s);
    if (!t.size()) return;
    if (P.has_loads) {
      // Change of the controlled DOF per unit load factor.
      const auto tw = P.ns.twists(c.state);
      double rate = 0.0;
      for (const auto& [k, v] : P.crow(c.state, tw, P.ctrl, nullptr)) rate += v * t[k];
      if (std::abs(rate) < kTinyRate) return;
      const double dl = hh / rate;
      u.head(P.nf + P.nc) += dl * t.head(P.nf + P.nc);
      u[P.nf + P.nc] += dl;
    } else {
      u += hh * t;
    }
    return;
  }
  s.kind = StepKind::Arc;
  s.lambda = c.lambda;
  s.ds = hh;
  u = P.start_unknowns(c, s);
  Eigen::VectorXd d;  // [Delta_f, dlambda] direction
  if (dir) {
    d = *dir;
  } else if (t.size()) {
    d.resize(P.nf + 1);
    d.head(P.nf) = t.head(P.nf);
    d[P.nf] = 1.0;
    if (previous_direction.size() && arc_dot(d, previous_direction) < 0.0) d = -d;
  } else if (previous_direction.size()) {
    d = previous_direction;  // secant predictor where the tangent is singular
  } else {
    d = Eigen::VectorXd::Zero(P.nf + 1);
    d[P.nf] = 1.0;
  }
  const double a = hh / std::sqrt(std::max(arc_dot(d, d), kTinyRate));
  u.head(P.nf) += a * d.head(P.nf);
  u[P.nf + P.nc] += a * d[P.nf];
  if (t.size() && !dir) u.segment(P.nf, P.nc) += a * d[P.nf] * t.segment(P.nf, P.nc);
}

}  // namespace beamfea
