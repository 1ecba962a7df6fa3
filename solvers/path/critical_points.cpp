#include "solvers/path/critical_points.hpp"

#include <cmath>

#include "solvers/buckling.hpp"

namespace beamfea {

namespace {

// The critical mode over raw node DOFs (largest translation 1) at a state.
Eigen::VectorXd raw_mode(const PathSystem& sys, const NonlinearState& st, const Eigen::VectorXd& mode_free) {
  const NonlinearStructure& ns = sys.structure();
  const Model& model = ns.model();
  Eigen::VectorXd raw = Eigen::VectorXd::Zero(ns.reference_map().raw_size());
  const auto tw = ns.twists(st);
  for (int n = 0; n < static_cast<int>(model.nodes.size()); ++n)
    for (int k = 0; k < 6; ++k)
      for (const auto& [g, v] : ns.raw_row(st, tw, n, k))
        if (sys.free_index(g) >= 0) raw[6 * n + k] += v * mode_free[sys.free_index(g)];
  return normalise_mode(model, raw);
}

}  // namespace

StepPrediction trial_step(const CriticalPointParts& parts, const Converged& cur, double f, double h,
                          const Eigen::VectorXd& dir, PathControl mode) {
  if (mode == PathControl::ArcLength) return parts.predictor.predict_along(cur, f * std::abs(h), dir);
  return parts.predictor.predict(cur, mode, f * h);
}

LocatedCriticalPoint locate_critical_point(const CriticalPointParts& parts, const Converged& cur, const Converged& next,
                                           double h, const Eigen::VectorXd& dir, int neg_before, int neg_after,
                                           ControlDof control, PathControl mode,
                                           const std::function<double(const Converged&, double)>& control_at) {
  const PathSystem& P = parts.system;
  LocatedCriticalPoint c;
  c.point.negative_before = neg_before;
  c.point.negative_after = neg_after;
  c.before = cur;
  c.after = next;
  // Bisection on the fraction of the step: `before` keeps the start's count.
  for (int it = 0; it < kMaxBisections && c.hi - c.lo > parts.options.critical_tolerance; ++it) {
    const double mid = 0.5 * (c.lo + c.hi);
    const StepPrediction trial = trial_step(parts, cur, mid, h, dir, mode);
    const StepSolution sol = parts.corrector.solve(cur, trial.spec, trial.u);
    if (!sol.converged) break;
    const Converged& cm = sol.state;
    if (parts.stability.analyse(cm, {.control = control}).info.negative == neg_before) {
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
  const StabilityAnalysis st = parts.stability.analyse(c.after, {.control = control, .mode = CriticalMode::Wanted});
  if (st.info.mode.size()) {
    c.mode = st.info.mode;
    const Eigen::VectorXd pf = P.load_pattern(c.after.state);
    const double w = std::abs(pf.dot(c.mode)) / std::max(1e-300, pf.norm() * c.mode.norm());
    c.point.load_work = pf.norm() > 0.0 ? w : 0.0;
    c.point.mode = raw_mode(P, c.after.state, c.mode);
  }
  bool limit = P.has_loads() && control == ControlDof::Free && c.point.load_work > kLimitLoadWork;
  if (mode == PathControl::ArcLength && P.has_loads()) {
    // The turn of the load factor: the sign of dlambda along the path (the tangent [t; 1] oriented
    // by the step's direction) on both sides of the located point. It turns at a limit point and not
    // at a bifurcation, whatever the symmetry of the structure (the work of a mode on the load is
    // small at the limit point of an unsymmetric arch).
    const Eigen::VectorXd tb = parts.factors.tangent(P, c.before), ta = parts.factors.tangent(P, c.after);
    if (tb.size() && ta.size()) {
      const int nf = P.nf();
      Eigen::VectorXd db(nf + 1), da(nf + 1);
      db << tb.head(nf), 1.0;
      da << ta.head(nf), 1.0;
      limit = (P.arc_dot(db, dir) > 0.0) != (P.arc_dot(da, dir) > 0.0);
    }
  }
  c.point.type = limit ? CriticalPointType::LimitPoint : CriticalPointType::Bifurcation;
  return c;
}

LocatedCriticalPoint locate_extremum(const CriticalPointParts& parts, const Converged& cur, const Converged& next,
                                     double h, double slope_before, const Eigen::VectorXd& dir, PathControl mode,
                                     const std::function<double(const Converged&, double)>& control_at) {
  const PathSystem& P = parts.system;
  LocatedCriticalPoint c;
  c.before = cur;
  c.after = next;
  const bool positive_before = slope_before > 0.0;
  for (int it = 0; it < kMaxBisections && c.hi - c.lo > parts.options.critical_tolerance; ++it) {
    const double mid = 0.5 * (c.lo + c.hi);
    const StepPrediction trial = trial_step(parts, cur, mid, h, dir, mode);
    const StepSolution sol = parts.corrector.solve(cur, trial.spec, trial.u);
    if (!sol.converged) break;
    const Converged& cm = sol.state;
    const double slope = conjugate_slope(P, parts.factors, cm);
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
    c.point.negative_before = parts.stability.analyse(c.before).info.negative;
    const StabilityAnalysis st = parts.stability.analyse(c.after, {.mode = CriticalMode::Wanted});
    c.point.negative_after = st.info.negative;
    if (st.info.mode.size()) {
      c.mode = st.info.mode;
      const Eigen::VectorXd pf = P.has_loads() ? P.load_pattern(c.after.state) : Eigen::VectorXd();
      if (pf.size() && pf.norm() > 0.0)
        c.point.load_work = std::abs(pf.dot(c.mode)) / std::max(1e-300, pf.norm() * c.mode.norm());
      c.point.mode = raw_mode(P, c.after.state, c.mode);
    }
  }
  return c;
}

BranchSwitch switch_branch(const CriticalPointParts& parts, const Converged& from, const Eigen::VectorXd& mode,
                           double h) {
  // The critical mode, at constant load factor, as the direction of the first secondary step.
  const int nf = parts.system.nf();
  Eigen::VectorXd d(nf + 1);
  d.head(nf) = mode;
  d[nf] = 0.0;
  BranchSwitch out;
  for (double f : {1.0, 0.5, 0.25, 0.125}) {
    const StepPrediction trial = parts.predictor.predict_along(from, f * std::abs(h), d);
    StepSolution sol = parts.corrector.solve(from, trial.spec, trial.u);
    out.report = std::move(sol.report);
    if (sol.converged) {
      out.switched = true;
      out.state = std::move(sol.state);
      out.ds = f * std::abs(h);
      out.direction = d;
      out.direction[nf] = out.state.lambda - from.lambda;
      return out;
    }
  }
  return out;
}

}  // namespace beamfea
