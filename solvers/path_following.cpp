// The path-following loop: composes the parts of solvers/path/ (see solvers/path_following.hpp).
#include "solvers/path_following.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/errors.hpp"
#include "solvers/blas_threads.hpp"
#include "solvers/buckling.hpp"
#include "solvers/member_loading.hpp"
#include "solvers/path/critical_points.hpp"
#include "solvers/path/equilibrium.hpp"
#include "solvers/path/path_scales.hpp"
#include "solvers/path/predictor.hpp"
#include "solvers/path/stability.hpp"
#include "solvers/path/step_control.hpp"
#include "solvers/path/vibration.hpp"

namespace beamfea {

Model imperfect_model(const Model& model, int mode, double amplitude) {
  BucklingOptions bo;
  bo.modes = mode;
  const BucklingResult b = solve_buckling(model, bo);
  if (b.status != BucklingStatus::Succeeded || static_cast<int>(b.modes.size()) < mode)
    throw ModelError(fmt::format("imperfection mode {}", mode),
                     fmt::format("buckling mode {} is not available ({})", mode, b.message));
  Model m = model;
  for (std::size_t n = 0; n < m.nodes.size(); ++n) m.nodes[n].x += amplitude * b.modes[mode - 1].segment<3>(6 * n);
  return m;
}

namespace {

// The record of a converged state; returns its negative-eigenvalue count (-1 without stability).
int record(PathResult& res, const PathOptions& o, const Model& original, const PathEquilibrium& P,
           StabilityAnalyzer& stab, const Converged& c, int step, double control, double ds, PathControl kind) {
  PathStep ps;
  ps.step = step;
  ps.step_control = kind;
  ps.load_factor = c.lambda;
  ps.control = control;
  ps.arc_length = ds;
  ps.iterations = c.iterations;
  ps.chord_iterations = c.chord_iterations;
  ps.reaction = c.extra_mu;
  for (int n : o.track) {
    Vec6 d;
    d << c.state.x[n] - original.nodes[n].x, log_so3(c.state.R[n]);
    ps.track.push_back(d);
  }
  if (o.stability) {
    const bool disp = o.control == PathControl::Displacement;
    const auto st = stab.analyse(c, disp, false);
    ps.negative_eigenvalues = st.info.negative;
    ps.stable = st.info.negative == 0;
    ps.min_eigenvalue = st.info.min_eigenvalue;
    // The loaded stiffness of the node with the controlled DOF released (it is the probe).
    if (o.stiffness_node >= 0) {
      ps.node_stiffness = stab.node_stiffness(c, disp ? stab.analyse(c, false, false) : st, o.stiffness_node);
      if (ps.node_stiffness->ok) ps.stiffness = ps.node_stiffness->K;
    }
  }
  if (o.frequency_modes > 0) {
    // Vibrations about the state: the controlled DOF is held only by an imposed motion (no loads).
    const bool hold = o.control == PathControl::Displacement && !P.has_loads;
    const PathFrequencies f =
        path_frequencies(P, c, constrained_tangent(P, c, hold), {o.frequency_modes, o.frequency_mass});
    if (f.ok) ps.frequencies = f.frequencies;
    else ps.frequencies_failure = f.message;
  }
  ps.state = c.state;
  // The evaluation at the state, shared with the stability analysis and the next predictor.
  ps.end_forces = P.evaluation_at(c).end_forces;
  // Plus the member loads' fixed-end forces in the co-rotated frames (dead loads), as linear_static.
  const auto fe = corotated_fixed_end_forces(original, original.default_loads(), c.state.x, c.state.R, c.lambda);
  for (std::size_t e = 0; e < fe.size(); ++e) ps.end_forces[e] += fe[e];
  res.steps.push_back(std::move(ps));
  return res.steps.back().negative_eigenvalues;
}

// The stop conditions after a converged step; sets the termination.
bool stopped(PathResult& res, const PathOptions& o, const Model& original, const Converged& nx, int step) {
  if (o.stop_load_factor) {
    const double v = *o.stop_load_factor;
    if ((v >= 0 && nx.lambda >= v) || (v < 0 && nx.lambda <= v)) {
      res.finish(PathTermination::StopLoadFactor, v);
      return true;
    }
  }
  if (o.stop_beyond) {
    const double v = o.stop_dof < 3 ? nx.state.x[o.stop_node][o.stop_dof] - original.nodes[o.stop_node].x[o.stop_dof]
                                    : log_so3(nx.state.R[o.stop_node])[o.stop_dof - 3];
    const double b = *o.stop_beyond;
    if ((b >= 0 && v >= b) || (b < 0 && v <= b)) {
      res.finish(PathTermination::StopBeyond, b, 0, fmt::format("node '{}' {}", original.nodes[o.stop_node].id, kDofNames[o.stop_dof]));
      return true;
    }
  }
  if (o.stop_steps && step >= *o.stop_steps) {
    res.finish(PathTermination::StopSteps, 0.0, *o.stop_steps);
    return true;
  }
  return false;
}

}  // namespace

PathResult follow_path(const Model& original, const PathOptions& o) {
  o.validate(original);
  // Small factorisations every few milliseconds: one BLAS thread (solvers/blas_threads.hpp).
  const SingleBlasThread one_blas_thread;
  PathResult res;
  const Model model = o.imperfection_mode > 0 ? imperfect_model(original, o.imperfection_mode, o.imperfection_amplitude)
                                              : original;
  PathEquilibrium P(model, o);
  res.free_dofs = P.nf;
  res.statically_indeterminate = P.redundant;
  if (P.nf == 0) {  // every DOF held: no path to follow (and KINSOL cannot take an empty system)
    res.finish(PathTermination::InitialStateFailed, 0.0, 0,
               "no free DOF (every DOF is supported, prescribed or held): there is no path to follow");
    return res;
  }
  KinsolSolver kin(o.newton);
  StabilityAnalyzer stab(P);
  Predictor predictor(o.control, P);
  const CriticalPointParts parts{o, P, kin, stab, predictor};
  auto say = [&](const std::string& s) {
    if (o.progress) o.progress(s);
  };
  const bool disp = o.control == PathControl::Displacement;

  Converged cur;
  std::string rep;
  if (!P.initial_state(kin, cur, rep)) {
    res.finish(PathTermination::InitialStateFailed, 0.0, 0, rep);
    return res;
  }
  // The structure's own scales: the arc-length weight of the load factor, the automatic first
  // step and the force scale of the convergence test (solvers/path/path_scales.hpp).
  const PathScales scales = path_scales(model, P, cur, P.has_loads);
  if (scales.lambda_ref > 0.0) P.set_load_scale(scales.lambda_ref);
  P.psi2 = scales.psi * scales.psi;
  double ds0 = o.arc_length;
  if (o.control == PathControl::ArcLength && o.arc_length_auto) {
    if (!(scales.ds_auto > 0.0)) {
      res.finish(PathTermination::NoAutomaticStep);
      return res;
    }
    ds0 = scales.ds_auto;
    say(fmt::format("arc_length auto: first step {:.6g} (load factor scale {:.6g}, psi {:.6g})", ds0, scales.lambda_ref,
                    scales.psi));
  }
  StepControl control(o, P, cur, ds0);
  int neg = record(res, o, original, P, stab, cur, 0, control.value(cur), 0.0, o.control);

  int step = 0, cuts = 0;
  bool switched = false;
  auto fail = [&](PathTermination why, const std::string& what) {  // a failed step: cut or give up
    ++cuts;
    const bool ok = control.cut() && cuts <= o.max_cuts;
    say(fmt::format("step {}: {}; cutting the step to {:.4g}", step + 1, what, control.h));
    if (ok) return true;
    // Displacement control at a snap-back of the controlled DOF: on under arc length, with the
    // arc length of the last accepted step.
    const Eigen::VectorXd& d = predictor.previous_direction;
    if (P.has_loads && d.size() && control.fall_back_to_arc_length(cur, std::sqrt(predictor.arc_dot(d, d)))) {
      cuts = 0;
      say(fmt::format("step {}: the controlled DOF turns back: arc length from here (ds {:.4g})", step + 1, control.h));
      return true;
    }
    res.finish(why, cur.lambda, cuts, rep);
    return false;
  };
  // Displacement control: the slope of the load factor (or reaction) against the controlled DOF,
  // whose change of sign is a limit point.
  double slope = disp && o.locate_critical ? P.conjugate_slope(cur) : NAN;
  while (true) {
    if (control.target_reached(cur)) {
      res.finish(PathTermination::Succeeded);
      break;
    }
    if (step >= o.max_steps) {  // an incomplete path
      res.finish(PathTermination::MaxSteps, 0.0, o.max_steps);
      break;
    }
    StepSpec spec;
    Eigen::VectorXd u;
    predictor.control = control.mode;
    predictor.make_step(cur, control.h, spec, u);
    Converged next;
    if (!P.solve(kin, cur, spec, u, next, rep)) {
      if (!fail(PathTermination::NoConvergence, "no convergence (" + rep + ")")) break;
      continue;
    }
    const Eigen::VectorXd dir = predictor.direction(cur, next);
    if (control.mode == PathControl::ArcLength) {
      // The corrector went far from the predictor: Newton may have jumped to another branch (over
      // a limit point, with the same inertia at both ends). Cut the step.
      Eigen::VectorXd moved = dir;
      moved.head(P.nf) -= u.head(P.nf);
      moved[P.nf] -= u[P.nf + P.nc] - cur.lambda;
      if (predictor.arc_dot(moved, moved) > kMaxCorrectorRatio * kMaxCorrectorRatio * control.h * control.h) {
        if (!fail(PathTermination::NoConvergence, "the corrector went far from the predictor (a jump?)")) break;
        continue;
      }
    }
    // The spherical constraint has a second root behind the start: a step that went back along the
    // path is rejected and cut.
    if (control.mode == PathControl::ArcLength && predictor.previous_direction.size()) {
      const Eigen::VectorXd& d = predictor.previous_direction;
      if (predictor.arc_dot(dir, d) < 0.0) {
        if (!fail(PathTermination::NoForwardSolution, "the step went back along the path")) break;
        continue;
      }
    }
    ++step;
    control.advance();
    const int neg_before = neg;
    neg = record(res, o, original, P, stab, next, step, control.value(next), std::abs(control.h), control.mode);
    say(fmt::format("step {}: load factor {:.6g}, control {:.6g}, {} iterations{}, {} negative eigenvalues", step,
                    next.lambda, control.value(next), next.iterations,
                    next.chord_iterations ? fmt::format(" ({} chord)", next.chord_iterations) : std::string(), neg));

    const bool fall_back = control.mode != o.control;  // no critical points in a snap-back fall-back
    bool control_turns = false;  // the step straddles a turn of the controlled DOF (not of the load)
    if (disp && o.locate_critical) {
      const double slope_next = P.conjugate_slope(next);
      if (!fall_back && slope * slope_next < 0.0) {
        const double h = control.h;
        LocatedCriticalPoint lc = locate_extremum(parts, cur, next, h, slope,
                                                  [&](const Converged& c, double) { return control.value(c); });
        // The slope changes sign through zero at an extremum of the load factor (or reaction), and
        // through infinity where the controlled DOF turns back: only the first is a limit point.
        const auto conj = [&](const Converged& c) { return P.has_loads ? c.lambda : c.extra_mu; };
        const double mid = 0.5 * (conj(lc.before) + conj(lc.after));
        control_turns = (mid - conj(cur)) * (mid - conj(next)) <= 0.0;
        if (!control_turns) {
          lc.point.step = step;
          say(fmt::format("critical point (limit_point) at load factor {:.6g}, step {}", lc.point.load_factor, step));
          res.critical_points.push_back(lc.point);
        }
      }
      slope = slope_next;
    }
    if (!fall_back && !control_turns && o.stability && o.locate_critical && neg >= 0 && neg_before >= 0 &&
        neg != neg_before) {
      const double h = control.h, s_end = control.path_length;
      const auto control_at = [&](const Converged& c, double f) {
        return o.control == PathControl::ArcLength ? s_end - (1.0 - f) * std::abs(h) : control.value(c);
      };
      LocatedCriticalPoint lc = locate_critical_point(parts, cur, next, h, dir, neg_before, neg, disp, control_at);
      CriticalPoint& cp = lc.point;
      cp.step = step;
      say(fmt::format("critical point ({}) at load factor {:.6g}, step {}", to_string(cp.type), cp.load_factor, step));
      if (cp.type == CriticalPointType::Bifurcation && o.branch_switch && !switched &&
          o.control == PathControl::ArcLength && lc.mode.size()) {
        Converged cb;
        double ds = 0.0;
        Eigen::VectorXd db;
        if (switch_branch(parts, lc.before, lc.mode, h, cb, ds, db, rep)) {
          switched = true;
          cp.branch_switched = true;
          // Replace the primary-path step by the located point and the first secondary step.
          res.steps.pop_back();
          const double s_lo = s_end - std::abs(h) + lc.lo * std::abs(h);
          record(res, o, original, P, stab, lc.before, step, s_lo, lc.lo * std::abs(h), o.control);
          ++step;
          control.path_length = s_lo + ds;
          control.h = h < 0 ? -ds : ds;
          neg = record(res, o, original, P, stab, cb, step, control.path_length, ds, o.control);
          predictor.previous_direction = db;
          cur = cb;
          res.critical_points.push_back(cp);
          say(fmt::format("branch switched onto the secondary path at load factor {:.6g}", cb.lambda));
          if (stopped(res, o, original, cb, step)) break;
          continue;
        }
        say("branch switching failed: " + rep);
      }
      res.critical_points.push_back(cp);
    }

    predictor.previous_direction = dir;
    if (fall_back && control.resume_displacement(cur, next))
      say(fmt::format("step {}: the controlled DOF moves toward its target again: displacement control", step));
    else
      control.adapt(adapt_count(next));
    cur = next;
    cuts = 0;
    if (stopped(res, o, original, next, step)) break;
  }
  res.factorizations = kin.factorizations() + P.tangent_factorizations();
  res.symbolic_analyses = kin.symbolic_analyses() + P.tangent_symbolic_analyses();
  res.chord_steps = P.chord_steps();
  res.chord_fallbacks = P.chord_fallbacks();
  return res;
}

}  // namespace beamfea
