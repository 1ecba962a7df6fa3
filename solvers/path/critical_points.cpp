#include "solvers/path/critical_points.hpp"

#include <cmath>

#include "solvers/buckling.hpp"

namespace beamfea {

namespace {

// The critical mode over raw node DOFs (largest translation 1) at a state.
Eigen::VectorXd raw_mode(const PathEquilibrium& eq, const NonlinearState& st, const Eigen::VectorXd& mode_free) {
  const Model& model = eq.ns.model();
  Eigen::VectorXd raw = Eigen::VectorXd::Zero(eq.ns.reference_map().raw_size());
  const auto tw = eq.ns.twists(st);
  for (int n = 0; n < static_cast<int>(model.nodes.size()); ++n)
    for (int k = 0; k < 6; ++k)
      for (const auto& [g, v] : eq.ns.raw_row(st, tw, n, k))
        if (eq.gen_to_free[g] >= 0) raw[6 * n + k] += v * mode_free[eq.gen_to_free[g]];
  return normalise_mode(model, raw);
}

// The trial step at fraction f of the step from cur (along dir under arc length).
void trial_step(const CriticalPointParts& parts, const Converged& cur, double f, double h, const Eigen::VectorXd& dir,
                StepSpec& s, Eigen::VectorXd& u) {
  if (parts.options.control == PathControl::ArcLength) {
    parts.predictor.make_step(cur, f * std::abs(h), s, u, &dir);
  } else {
    parts.predictor.make_step(cur, f * h, s, u);
  }
}

}  // namespace

LocatedCriticalPoint locate_critical_point(const CriticalPointParts& parts, const Converged& cur, const Converged& next,
                                           double h, const Eigen::VectorXd& dir, int neg_before, int neg_after,
                                           bool with_control,
                                           const std::function<double(const Converged&, double)>& control_at) {
  const PathEquilibrium& P = parts.eq;
  LocatedCriticalPoint c;
  c.point.negative_before = neg_before;
  c.point.negative_after = neg_after;
  c.before = cur;
  c.after = next;
  // Bisection on the fraction of the step: `before` keeps the start's count.
  for (int it = 0; it < kMaxBisections && c.hi - c.lo > parts.options.critical_tolerance; ++it) {
    const double mid = 0.5 * (c.lo + c.hi);
    StepSpec s;
    Eigen::VectorXd u;
    trial_step(parts, cur, mid, h, dir, s, u);
    Converged cm;
    std::string report;
    if (!P.solve(parts.kin, cur, s, u, cm, report)) break;
    if (parts.stability.analyse(cm, with_control, false).info.negative == neg_before) {
      c.lo = mid;
      c.before = cm;
    } else {
      c.hi = mid;
      c.after = cm;
    }
  }
  c.point.load_factor = 0.5 * (c.before.lambda + c.after.lambda);
  c.point.control = 0.5 * (control_at(c.before, c.lo) + control_at(c.after, c.hi));

  // Classification by the work of the critical mode on the load pattern.
  const StabilityAnalysis st = parts.stability.analyse(c.after, with_control, true);
  if (st.info.mode.size()) {
    c.mode = st.info.mode;
    const Eigen::VectorXd pf = P.load_pattern(c.after.state);
    const double w = std::abs(pf.dot(c.mode)) / std::max(1e-300, pf.norm() * c.mode.norm());
    c.point.load_work = pf.norm() > 0.0 ? w : 0.0;
    c.point.mode = raw_mode(P, c.after.state, c.mode);
  }
  const bool limit = P.has_loads && !with_control && c.point.load_work > kLimitLoadWork;
  c.point.type = limit ? CriticalPointType::LimitPoint : CriticalPointType::Bifurcation;
  return c;
}

bool switch_branch(const CriticalPointParts& parts, const Converged& from, const Eigen::VectorXd& mode, double h,
                   Converged& out, double& ds, Eigen::VectorXd& dir, std::string& report) {
  // The critical mode, at constant load factor, as the direction of the first secondary step.
  Eigen::VectorXd d(parts.eq.nf + 1);
  d.head(parts.eq.nf) = mode;
  d[parts.eq.nf] = 0.0;
  for (double f : {1.0, 0.5, 0.25, 0.125}) {
    StepSpec s;
    Eigen::VectorXd u;
    parts.predictor.make_step(from, f * std::abs(h), s, u, &d);
    if (parts.eq.solve(parts.kin, from, s, u, out, report)) {
      ds = f * std::abs(h);
      dir = d;
      dir[parts.eq.nf] = out.lambda - from.lambda;
      return true;
    }
  }
  return false;
}

}  // namespace beamfea
