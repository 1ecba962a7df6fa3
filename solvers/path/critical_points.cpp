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
  bool limit = P.has_loads && !with_control && c.point.load_work > kLimitLoadWork;
  if (parts.options.control == PathControl::ArcLength && P.has_loads) {
    // The turn of the load factor: the sign of dlambda along the path (the tangent [t; 1] oriented
    // by the step's direction) on both sides of the located point. It turns at a limit point and not
    // at a bifurcation, whatever the symmetry of the structure (the work of a mode on the load is
    // small at the limit point of an unsymmetric arch).
    const Eigen::VectorXd tb = P.tangent(c.before), ta = P.tangent(c.after);
    if (tb.size() && ta.size()) {
      Eigen::VectorXd db(P.nf + 1), da(P.nf + 1);
      db << tb.head(P.nf), 1.0;
      da << ta.head(P.nf), 1.0;
      limit = (parts.predictor.arc_dot(db, dir) > 0.0) != (parts.predictor.arc_dot(da, dir) > 0.0);
    }
  }
  c.point.type = limit ? CriticalPointType::LimitPoint : CriticalPointType::Bifurcation;
  return c;
}

LocatedCriticalPoint locate_extremum(const CriticalPointParts& parts, const Converged& cur, const Converged& next,
                                     double h, double slope_before,
                                     const std::function<double(const Converged&, double)>& control_at) {
  const PathEquilibrium& P = parts.eq;
  LocatedCriticalPoint c;
  c.before = cur;
  c.after = next;
  const bool positive_before = slope_before > 0.0;
  for (int it = 0; it < kMaxBisections && c.hi - c.lo > parts.options.critical_tolerance; ++it) {
    const double mid = 0.5 * (c.lo + c.hi);
    StepSpec s;
    Eigen::VectorXd u;
    parts.predictor.make_step(cur, mid * h, s, u);
    Converged cm;
    std::string report;
    if (!P.solve(parts.kin, cur, s, u, cm, report)) break;
    const double slope = P.conjugate_slope(cm);
    if (std::isnan(slope)) break;
    if ((slope > 0.0) == positive_before) {
      c.lo = mid;
      c.before = cm;
    } else {
      c.hi = mid;
      c.after = cm;
    }
  }
  c.point.type = CriticalPointType::LimitPoint;
  c.point.load_factor = 0.5 * (c.before.lambda + c.after.lambda);
  c.point.reaction = 0.5 * (c.before.extra_mu + c.after.extra_mu);
  c.point.control = 0.5 * (control_at(c.before, c.lo) + control_at(c.after, c.hi));
  // The structure with the controlled DOF released: its inertia changes at the extremum.
  if (parts.options.stability) {
    c.point.negative_before = parts.stability.analyse(c.before, false, false).info.negative;
    const StabilityAnalysis st = parts.stability.analyse(c.after, false, true);
    c.point.negative_after = st.info.negative;
    if (st.info.mode.size()) {
      c.mode = st.info.mode;
      const Eigen::VectorXd pf = P.has_loads ? P.load_pattern(c.after.state) : Eigen::VectorXd();
      if (pf.size() && pf.norm() > 0.0)
        c.point.load_work = std::abs(pf.dot(c.mode)) / std::max(1e-300, pf.norm() * c.mode.norm());
      c.point.mode = raw_mode(P, c.after.state, c.mode);
    }
  }
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
