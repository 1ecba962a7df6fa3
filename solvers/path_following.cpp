// The path-following loop: composes the parts of solvers/path/ (see solvers/path_following.hpp).
#include "solvers/path_following.hpp"

#include <fmt/format.h>

#include <cmath>
#include <optional>

#include "core/errors.hpp"
#include "solvers/blas_threads.hpp"
#include "solvers/buckling.hpp"
#include "solvers/member_loading.hpp"
#include "solvers/path/corrector.hpp"
#include "solvers/path/critical_points.hpp"
#include "solvers/path/equilibrium.hpp"
#include "solvers/path/factor_cache.hpp"
#include "solvers/path/path_scales.hpp"
#include "solvers/path/predictor.hpp"
#include "solvers/path/singularity.hpp"
#include "solvers/path/stability.hpp"
#include "solvers/path/step_control.hpp"
#include "solvers/path/vibration.hpp"

namespace beamfea {

Model imperfect_model(const Model& model, int mode, double amplitude) {
  return imperfect_model(model, model.default_loads(), mode, amplitude);
}

Model imperfect_model(const Model& model, const LoadSet& loads, int mode, double amplitude) {
  BucklingOptions bo;
  bo.modes = mode;
  const BucklingResult b = solve_buckling(model, loads, bo);
  if (b.status != BucklingStatus::Succeeded || static_cast<int>(b.modes.size()) < mode)
    throw ModelError(fmt::format("imperfection mode {}", mode),
                     fmt::format("buckling mode {} is not available ({})", mode, b.message));
  Model m = model;
  for (std::size_t n = 0; n < m.nodes.size(); ++n) m.nodes[n].x += amplitude * b.modes[mode - 1].segment<3>(6 * n);
  return m;
}

namespace {

// The departure (over the model length, or in radians) of a row dropped as redundant at the
// reference beyond which the rows kept there no longer hold the loops closed. Where the rank stays
// the reference's, a dropped row follows the kept ones, which Newton satisfies to its function
// tolerance (1e-9 of the model length): 1e6 times less than this. Where it grows, the dropped row
// departs at second order in the step (a flat four-bar's coupler shortens by L (1 - cos theta)),
// 1e-3 of the model length after a first step of 0.05 L.
constexpr double kDroppedRowDeparture = 1e-6;

// The rows kept as independent are chosen afresh at a converged state (PathSystem::reselect) when
// their smallest singular value has fallen below this fraction of a fresh selection's there: they
// are losing rank where the constraints are not (the pose would look singular, and Newton on them
// fail). The margin keeps a choice as good as the fresh one (the rank-revealing QR's pick is not
// the best of all) from being changed back and forth.
constexpr double kReselectRatio = 0.5;

// A state whose dropped rows depart by d has grown rank where its rows have more singular values
// above this many times d than rows are kept. A loop opened by d (Newton on rows that lost rank
// within the step found a solution off the constraints) gains singular values of the order of d;
// one leaving a singular reference pose gains one of the order of the step, while its dropped row
// departs at second order (a flat change-point four-bar: 0.02 against 2.3e-5 of the model length).
constexpr double kRankMargin = 10.0;

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

// Why a converged step is not taken (arc length): the termination should the cuts run out, and the
// words of the progress report.
struct StepRejection {
  PathTermination why;
  const char* what;
};

// What the rows dropped as redundant say of a converged step (PathRun::check_dropped_rows).
enum class DroppedRows {
  Held,        // they stay at their targets: the step stands
  Reselected,  // they depart, the rows were chosen afresh at the step's start: solve the step again
  Departed,    // they depart and no better choice exists at the start: cut the step
  Stop         // the constraint rank grew: the path stopped (termination set)
};

// One path: the parts of solvers/path/ and the loop's state (the current state, the step count,
// the cuts of the step, the last inertia and slope), composed by run().
class PathRun {
 public:
  PathRun(const Model& original, const PathOptions& o, PathSystem& sys, FactorCache& factors,
          KinsolSolver& kin, const Converged& start, double ds0, PathResult& res)
      : o_(o), original_(original), sys_(sys), factors_(factors),
        corrector_(sys, factors, kin, o.chord_corrector ? ChordIterations::On : ChordIterations::Off),
        stability_(sys, factors), predictor_(sys, factors), control_(o, sys, start, ds0),
        parts_{o, sys, factors, corrector_, stability_, predictor_}, monitor_(sys, start.state), res_(res), cur_(start) {}
  // Follows the path to its termination (set in the result).
  void run();
  const Corrector& corrector() const { return corrector_; }

 private:
  bool displacement() const { return o_.control == PathControl::Displacement; }
  ControlDof held_control() const { return displacement() ? ControlDof::Held : ControlDof::Free; }
  // "load factor 1.2", or under an imposed motion (no loads) "control 0.3": where a state is.
  std::string where(const Converged& c) const {
    return sys_.has_loads() ? fmt::format("load factor {:.6g}", c.lambda) : fmt::format("control {:.6g}", control_.value(c));
  }
  void say(const std::string& s) const {
    if (o_.progress) o_.progress(s);
  }
  // Records a converged state; returns its negative-eigenvalue count (-1 without stability).
  int record(const Converged& c, int step, double control, double ds, PathControl kind);
  void record_stability(PathStep& ps, const Converged& c);
  // A failed step: cut it (or fall back to arc length); false when the path stops here.
  bool cut(PathTermination why, const std::string& what);
  // A converged step from its prediction that is not taken, or none.
  std::optional<StepRejection> rejected(const StepPrediction& pred, const Eigen::VectorXd& dir) const;
  // Displacement control (and its arc-length fall-back): a limit point located between cur_ and next
  // (the step's direction dir) by the slope of the load factor (or reaction); true when the step
  // straddles a turn of the controlled DOF instead.
  bool locate_limit_point(const Converged& next, const Eigen::VectorXd& dir);
  // A change of inertia between cur_ and next: the critical point located, classified and recorded;
  // true when the path switched branch onto the secondary path there (cur_ is then its first state).
  bool locate_inertia_change(const Converged& next, const Eigen::VectorXd& dir, int neg_before);
  bool switch_onto_branch(const LocatedCriticalPoint& lc, CriticalPoint& cp);
  // The control value of a state at fraction f of the step just taken (under the step's control).
  double control_at(const Converged& c, double f) const;
  // The singular poses of the loops crossed between cur_ and next (measures m_next there), located
  // and recorded.
  void locate_singularities(const Converged& next, const Eigen::VectorXd& m_next, const Eigen::VectorXd& dir);
  // The path ends: true (and the termination set) when it ends at a singular pose of a loop.
  bool ends_at_singularity();
  // Whether a row dropped as redundant departs from its target at `next`
  // (PathSystem::dropped_row_departure), and what follows. Where the constraint rank at `next` is
  // higher than the rows kept, the pose where they were chosen is singular for the loops (a model
  // built at a change point) and the rows kept there do not hold them closed beyond it: the path
  // stops. Where it is the same, the kept rows stopped spanning the constraints within the step:
  // they are chosen afresh at cur_ and the step solved again, or, were they the best there already,
  // the step is cut.
  DroppedRows check_dropped_rows(const Converged& next);
  // Chooses the rows afresh at cur_ (the last converged state) when the rows kept lose rank there
  // while the constraints do not (kReselectRatio), or would a step ahead (their measure extrapolated
  // from the last two states); true when it changed them.
  bool refresh_rows();
  // Whether the fresh choice in `rows` (of the kept rows' rank) beats the kept rows, whose measure
  // is `kept`, by the factor 1 / ratio.
  bool fresh_rows_better(const PathSystem::RowsAt& rows, double kept, double ratio) const {
    return rows.rank == sys_.nc() && !rows.same_as_kept && kept < ratio * rows.best;
  }
  // Keeps the fresh selection `rows` (taken at cur_) from here on: cur_'s multipliers carried over,
  // the factor and the singularity measures dropped, the change recorded in cur_'s step.
  void reselect(const PathSystem::RowsAt& rows, const std::string& why);
  // The measures of the singular poses at cur_ (and the state before it) after cur_ changed.
  void track_singularities(const Eigen::VectorXd& m_next, const Converged& before);
  // The loops' bases carried to the converged state `to` (SingularityMonitor::transport), its
  // measures taken afresh where a basis was.
  void carry_singularity_bases(const Converged& to);

  const PathOptions& o_;
  const Model& original_;
  PathSystem& sys_;
  FactorCache& factors_;
  Corrector corrector_;
  StabilityAnalyzer stability_;
  Predictor predictor_;
  StepControl control_;
  const CriticalPointParts parts_;
  SingularityMonitor monitor_;
  // The singularity measures at the start, at cur_ and at the state before it (its load factor and
  // control value); the size of the step that failed first from cur_.
  Eigen::VectorXd m_start_, m_cur_, m_prev_;
  double lambda_prev_ = 0.0, c_prev_ = 0.0, h_failed_ = 0.0;
  PathResult& res_;
  Converged cur_;
  std::string report_;   // the last solver report (the reason given when the path stops)
  std::string rows_chosen_ = "at the reference pose";  // where the rows kept were chosen
  bool rows_rechosen_ = false;                         // elsewhere than at the reference
  double kept_before_ = NAN;  // the kept rows' measure at the last converged state (refresh_rows)
  int step_ = 0, cuts_ = 0, neg_ = -1;
  double slope_ = NAN;
  bool switched_ = false;
};

int PathRun::record(const Converged& c, int step, double control, double ds, PathControl kind) {
  PathStep ps;
  ps.step = step;
  ps.step_control = kind;
  ps.load_factor = c.lambda;
  ps.control = control;
  ps.arc_length = ds;
  ps.iterations = c.iterations;
  ps.chord_iterations = c.chord_iterations;
  ps.reaction = c.extra_mu;
  for (int n : o_.track) {
    Vec6 d;
    d << c.state.x[n] - original_.nodes[n].x, log_so3(c.state.R[n]);
    ps.track.push_back(d);
  }
  if (o_.stability) record_stability(ps, c);
  if (o_.frequency_modes > 0) {
    // Vibrations about the state: the controlled DOF is held only by an imposed motion (no loads).
    const ControlDof hold = displacement() && !sys_.has_loads() ? ControlDof::Held : ControlDof::Free;
    const PathFrequencies f = path_frequencies(sys_, c, constrained_tangent(sys_, factors_, c, hold),
                                               {o_.frequency_modes, o_.frequency_mass});
    if (f.ok) ps.frequencies = f.frequencies;
    else ps.frequencies_failure = f.message;
  }
  ps.state = c.state;
  // The evaluation at the state, shared with the stability analysis and the next predictor.
  ps.end_forces = factors_.evaluation_at(sys_, c).end_forces;
  // Plus the member loads' fixed-end forces in the co-rotated frames (dead loads), as linear_static.
  const auto fe = corotated_fixed_end_forces(original_, sys_.loads(), c.state.x, c.state.R, c.lambda);
  for (std::size_t e = 0; e < fe.size(); ++e) ps.end_forces[e] += fe[e];
  res_.steps.push_back(std::move(ps));
  return res_.steps.back().negative_eigenvalues;
}

void PathRun::record_stability(PathStep& ps, const Converged& c) {
  const auto st = stability_.analyse(c, {.control = held_control()});
  ps.negative_eigenvalues = st.info.negative;
  ps.stable = st.info.negative == 0;
  ps.min_eigenvalue = st.info.min_eigenvalue;
  // The loaded stiffness of the node with the controlled DOF released (it is the probe).
  if (o_.stiffness_node >= 0) {
    ps.node_stiffness = stability_.node_stiffness(c, displacement() ? stability_.analyse(c) : st, o_.stiffness_node);
    if (ps.node_stiffness->ok) ps.stiffness = ps.node_stiffness->K;
  }
}

bool PathRun::cut(PathTermination why, const std::string& what) {
  // Rows chosen afresh at cur_, where better ones exist there, before the step is cut: the rows kept
  // may be what failed it.
  if (sys_.has_dropped_rows()) {
    const PathSystem::RowsAt rows = sys_.rows_at(cur_.state);
    if (fresh_rows_better(rows, rows.kept, 1.0)) {
      reselect(rows, fmt::format("step {} failed: {}", step_ + 1, what));
      return true;
    }
  }
  if (cuts_ == 0) h_failed_ = std::abs(control_.h());
  ++cuts_;
  const bool ok = control_.cut() && cuts_ <= o_.max_cuts;
  say(fmt::format("step {}: {}; cutting the step to {:.4g}", step_ + 1, what, control_.h()));
  if (ok) return true;
  // Displacement control at a snap-back of the controlled DOF: on under arc length, with the
  // arc length of the last accepted step.
  const Eigen::VectorXd& d = predictor_.previous_direction();
  if (d.size() && control_.fall_back_to_arc_length(cur_, std::sqrt(sys_.arc_dot(d, d)))) {
    cuts_ = 0;
    say(fmt::format("step {}: the controlled DOF turns back: arc length from here (ds {:.4g})", step_ + 1,
                    control_.h()));
    return true;
  }
  if (displacement() && !std::isnan(control_.last_turn()))
    report_ = fmt::format("the controlled DOF turns back at {:.6g} again, not past its earlier turn at {:.6g}: "
                          "the target {:.6g} is out of its reach", control_.value(cur_), control_.last_turn(), o_.target);
  if (!ends_at_singularity()) res_.finish(why, cur_.lambda, cuts_, report_);
  return false;
}

double PathRun::control_at(const Converged& c, double f) const {
  if (control_.mode() == PathControl::ArcLength && o_.control == PathControl::ArcLength)
    return control_.path_length() - (1.0 - f) * std::abs(control_.h());
  return control_.value(c);
}

void PathRun::locate_singularities(const Converged& next, const Eigen::VectorXd& m_next, const Eigen::VectorXd& dir) {
  if (!o_.locate_critical) return;
  const auto at = [&](const Converged& c, double f) { return control_at(c, f); };
  for (int i = 0; i < m_next.size(); ++i) {
    if (!monitor_.candidates()[i].square || !(m_cur_[i] * m_next[i] < 0.0)) continue;
    bool confirmed = false;
    CriticalPoint cp = locate_singularity(parts_, monitor_, i, cur_, next, m_cur_[i], m_next[i], control_.h(), dir,
                                          control_.mode(), at, &confirmed);
    if (!confirmed) continue;  // the sign changed without the passive Jacobian losing rank
    cp.step = step_;
    say(fmt::format("critical point (singularity) at load factor {:.6g}, step {}: {}", cp.load_factor, step_, cp.what));
    res_.critical_points.push_back(std::move(cp));
  }
}

DroppedRows PathRun::check_dropped_rows(const Converged& next) {
  const PathSystem::Departure d = sys_.dropped_row_departure(next.state);
  if (!(d.value > kDroppedRowDeparture)) return DroppedRows::Held;
  const std::string departs = fmt::format("{}, dropped as redundant {}, departs from its target by {:.3g} of the model "
                                          "length at {}",
                                          d.row, rows_chosen_, d.value, where(next));
  // The rank grew where the rows gained a singular value well above the departure, which an open
  // loop has only to the order of its opening.
  if (sys_.rank_above(next.state, kRankMargin * d.value) > sys_.nc()) {
    const bool reference = !rows_rechosen_;
    res_.finish(PathTermination::RankChanged, cur_.lambda, 0,
                fmt::format("{}: the {} is singular for the loops (their rows lose rank there){}", departs,
                            reference ? "reference pose" : "pose where the rows were chosen",
                            reference ? "; build the model at a pose off it" : ""));
    say(res_.brief_report());
    return DroppedRows::Stop;
  }
  const PathSystem::RowsAt at_cur = sys_.rows_at(cur_.state);
  if (fresh_rows_better(at_cur, at_cur.kept, 1.0)) {
    reselect(at_cur, departs);
    return DroppedRows::Reselected;
  }
  report_ = departs;
  return DroppedRows::Departed;
}

bool PathRun::refresh_rows() {
  if (!sys_.has_dropped_rows()) return false;
  const PathSystem::RowsAt rows = sys_.rows_at(cur_.state);
  // The kept rows' measure one more step of the same size ahead, extrapolated from the last two
  // states: rows that would lose rank within the next step are changed before it.
  const double ahead = std::isnan(kept_before_) ? rows.kept : 2.0 * rows.kept - kept_before_;
  kept_before_ = rows.kept;
  if (!fresh_rows_better(rows, std::min(rows.kept, ahead), kReselectRatio)) return false;
  reselect(rows, fmt::format("the rows kept lose rank (smallest singular value {:.3g}, {:.3g} a step ahead, {:.3g} for "
                             "a fresh choice)",
                             rows.kept, ahead, rows.best));
  return true;
}

void PathRun::reselect(const PathSystem::RowsAt& rows, const std::string& why) {
  cur_.mu = sys_.reselect(cur_.state, cur_.mu, rows.fresh);
  factors_.forget();
  monitor_.refresh(cur_.state);
  if (!monitor_.empty()) {
    m_start_ = m_cur_ = monitor_.measures(cur_.state);
    m_prev_.resize(0);
  }
  rows_chosen_ = fmt::format("at {} (step {})", where(cur_), step_);
  kept_before_ = NAN;
  rows_rechosen_ = true;
  res_.steps.back().statically_indeterminate = sys_.redundant();
  std::string dropped;
  for (const auto& r : sys_.redundant()) dropped += (dropped.empty() ? "" : ", ") + r;
  say(fmt::format("step {}: redundant constraint rows chosen afresh at {} ({}): now {}", step_, where(cur_), why,
                  dropped));
}

bool PathRun::ends_at_singularity() {
  if (!o_.locate_critical || monitor_.empty() || !m_prev_.size()) return false;
  const double c_cur = control_.value(cur_);
  const double reach = kSingularReach * std::max(h_failed_, std::abs(c_cur - c_prev_));
  std::optional<CriticalPoint> cp =
      singular_end(monitor_, m_start_, m_prev_, m_cur_, lambda_prev_, cur_.lambda, c_prev_, c_cur, reach);
  if (!cp) return false;
  cp->step = step_;
  say(fmt::format("critical point (singularity) at load factor {:.6g}, step {}: {}; no step converges beyond it",
                  cp->load_factor, step_, cp->what));
  res_.finish(PathTermination::Singularity, cp->load_factor, cuts_, cp->what);
  res_.critical_points.push_back(std::move(*cp));
  return true;
}

void PathRun::carry_singularity_bases(const Converged& to) {
  if (monitor_.transport(to.state)) return;
  m_cur_ = monitor_.measures(to.state);
  m_prev_.resize(0);
}

void PathRun::track_singularities(const Eigen::VectorXd& m_next, const Converged& before) {
  m_prev_ = m_cur_;
  m_cur_ = m_next;
  lambda_prev_ = before.lambda;
  c_prev_ = control_.value(before);
}

std::optional<StepRejection> PathRun::rejected(const StepPrediction& pred, const Eigen::VectorXd& dir) const {
  if (control_.mode() != PathControl::ArcLength) return std::nullopt;
  // The corrector went far from the predictor: Newton may have jumped to another branch (over a
  // limit point, with the same inertia at both ends). Cut the step.
  const int nf = sys_.nf();
  Eigen::VectorXd moved = dir;
  moved.head(nf) -= pred.u.head(nf);
  moved[nf] -= pred.u[nf + sys_.nc()] - cur_.lambda;
  const double h = control_.h();
  if (sys_.arc_dot(moved, moved) > kMaxCorrectorRatio * kMaxCorrectorRatio * h * h)
    return StepRejection{PathTermination::NoConvergence, "the corrector went far from the predictor (a jump?)"};
  // The spherical constraint has a second root behind the start: a step that went back along the
  // path is rejected and cut.
  const Eigen::VectorXd& d = predictor_.previous_direction();
  if (d.size() && sys_.arc_dot(dir, d) < 0.0)
    return StepRejection{PathTermination::NoForwardSolution, "the step went back along the path"};
  return std::nullopt;
}

bool PathRun::locate_limit_point(const Converged& next, const Eigen::VectorXd& dir) {
  bool control_turns = false;
  const double slope_next = conjugate_slope(sys_, factors_, next);
  if (slope_ * slope_next < 0.0) {
    LocatedCriticalPoint lc =
        locate_extremum(parts_, cur_, next, control_.h(), slope_, dir, control_.mode(),
                        [&](const Converged& c, double) { return control_.value(c); });
    // The slope changes sign through zero at an extremum of the load factor (or reaction), and
    // through infinity where the controlled DOF turns back: only the first is a limit point.
    const auto conj = [&](const Converged& c) { return sys_.has_loads() ? c.lambda : c.extra_mu; };
    const double mid = 0.5 * (conj(lc.before) + conj(lc.after));
    control_turns = (mid - conj(cur_)) * (mid - conj(next)) <= 0.0;
    if (!control_turns) {
      lc.point.step = step_;
      say(fmt::format("critical point (limit_point) at load factor {:.6g}, step {}", lc.point.load_factor, step_));
      res_.critical_points.push_back(lc.point);
    }
  }
  slope_ = slope_next;
  return control_turns;
}

bool PathRun::locate_inertia_change(const Converged& next, const Eigen::VectorXd& dir, int neg_before) {
  const auto at = [&](const Converged& c, double f) { return control_at(c, f); };
  const LocatedCriticalPoint lc = locate_critical_point(parts_, cur_, next, control_.h(), dir, neg_before, neg_,
                                                        held_control(), control_.mode(), at);
  CriticalPoint cp = lc.point;
  cp.step = step_;
  say(fmt::format("critical point ({}) at load factor {:.6g}, step {}", to_string(cp.type), cp.load_factor, step_));
  if (cp.type == CriticalPointType::Bifurcation && o_.branch_switch && !switched_ &&
      o_.control == PathControl::ArcLength && lc.mode.size()) {
    if (switch_onto_branch(lc, cp)) return true;
    say("branch switching failed: " + report_);
  }
  res_.critical_points.push_back(cp);
  return false;
}

bool PathRun::switch_onto_branch(const LocatedCriticalPoint& lc, CriticalPoint& cp) {
  const double h = control_.h(), s_end = control_.path_length();
  BranchSwitch bs = switch_branch(parts_, lc.before, lc.mode, h);
  report_ = bs.report;
  if (!bs.switched) return false;
  switched_ = true;
  cp.branch_switched = true;
  // Replace the primary-path step by the located point and the first secondary step.
  res_.steps.pop_back();
  const double s_lo = s_end - std::abs(h) + lc.lo * std::abs(h);
  record(lc.before, step_, s_lo, lc.lo * std::abs(h), o_.control);
  ++step_;
  control_.restart_at(s_lo + bs.ds, bs.ds);
  neg_ = record(bs.state, step_, control_.path_length(), bs.ds, o_.control);
  predictor_.accept(bs.direction);
  if (!monitor_.empty()) {
    track_singularities(monitor_.measures(bs.state.state), lc.before);
    carry_singularity_bases(bs.state);
  }
  cur_ = std::move(bs.state);
  res_.critical_points.push_back(cp);
  say(fmt::format("branch switched onto the secondary path at load factor {:.6g}", cur_.lambda));
  return true;
}

void PathRun::run() {
  neg_ = record(cur_, 0, control_.value(cur_), 0.0, o_.control);
  if (!monitor_.empty()) m_start_ = m_cur_ = monitor_.measures(cur_.state);
  // Displacement control: the slope of the load factor (or reaction) against the controlled DOF,
  // whose change of sign is a limit point.
  if (displacement() && o_.locate_critical) slope_ = conjugate_slope(sys_, factors_, cur_);
  while (true) {
    if (control_.target_reached(cur_)) {
      res_.finish(PathTermination::Succeeded);
      return;
    }
    if (step_ >= o_.max_steps) {  // an incomplete path
      res_.finish(PathTermination::MaxSteps, 0.0, o_.max_steps);
      return;
    }
    const StepPrediction pred = predictor_.predict(cur_, control_.mode(), control_.h());
    StepSolution sol = corrector_.solve(cur_, pred.spec, pred.u);
    report_ = sol.report;
    if (!sol.converged) {
      if (!cut(PathTermination::NoConvergence, "no convergence (" + report_ + ")")) return;
      continue;
    }
    const Converged next = std::move(sol.state);
    const DroppedRows dropped = check_dropped_rows(next);
    if (dropped == DroppedRows::Stop) return;
    if (dropped == DroppedRows::Reselected) continue;
    if (dropped == DroppedRows::Departed) {
      if (!cut(PathTermination::NoConvergence, report_)) return;
      continue;
    }
    const Eigen::VectorXd dir = sys_.direction(cur_, next);
    if (const auto r = rejected(pred, dir)) {
      if (!cut(r->why, r->what)) return;
      continue;
    }
    // The singularity measures at next, and whether their signs compare with cur_'s (the loops'
    // row spaces turned less than 60 degrees over the step).
    const Eigen::VectorXd m_next = monitor_.empty() ? Eigen::VectorXd() : monitor_.measures(next.state);
    const bool signs_compare = m_next.size() && monitor_.transportable(next.state);
    ++step_;
    control_.advance();
    const int neg_before = neg_;
    neg_ = record(next, step_, control_.value(next), std::abs(control_.h()), control_.mode());
    say(fmt::format("step {}: load factor {:.6g}, control {:.6g}, {} iterations{}, {} negative eigenvalues", step_,
                    next.lambda, control_.value(next), next.iterations,
                    next.chord_iterations ? fmt::format(" ({} chord)", next.chord_iterations) : std::string(), neg_));
    const bool fall_back = control_.mode() != o_.control;  // a snap-back fall-back's arc-length step
    if (signs_compare) locate_singularities(next, m_next, dir);
    const bool control_turns = displacement() && o_.locate_critical && locate_limit_point(next, dir);
    if (!control_turns && o_.stability && o_.locate_critical && neg_ >= 0 && neg_before >= 0 &&
        neg_ != neg_before && locate_inertia_change(next, dir, neg_before)) {
      refresh_rows();
      if (stopped(res_, o_, original_, cur_, step_)) return;
      continue;
    }
    predictor_.accept(dir);
    if (m_next.size()) {
      track_singularities(m_next, cur_);
      carry_singularity_bases(next);
    }
    if (fall_back && control_.resume_displacement(cur_, next))
      say(fmt::format("step {}: the controlled DOF moves toward its target again: displacement control", step_));
    else
      control_.adapt(adapt_count(next));
    cur_ = next;
    cuts_ = 0;
    refresh_rows();
    if (stopped(res_, o_, original_, next, step_)) return;
  }
}

// The first step of the path: the user's arc length, or the automatic one (0: none available).
double first_step(const PathOptions& o, const PathScales& scales) {
  if (o.control != PathControl::ArcLength || !o.arc_length_auto) return o.arc_length;
  if (!(scales.ds_auto > 0.0)) return 0.0;
  if (o.progress)
    o.progress(fmt::format("arc_length auto: first step {:.6g} (load factor scale {:.6g}, psi {:.6g})", scales.ds_auto,
                           scales.lambda_ref, scales.psi));
  return scales.ds_auto;
}

}  // namespace

PathResult follow_path(const Model& original, const PathOptions& o) {
  return follow_path(original, original.default_loads(), o);
}

PathResult follow_path(const Model& original, const LoadSet& loads, const PathOptions& o) {
  o.validate(original);
  // Small factorisations every few milliseconds: one BLAS thread (solvers/blas_threads.hpp).
  const SingleBlasThread one_blas_thread;
  PathResult res;
  // An imperfect geometry is a copy with its nodes moved; otherwise the path runs on the model itself.
  std::optional<Model> imperfect;
  if (o.imperfection_mode > 0) imperfect.emplace(imperfect_model(original, loads, o.imperfection_mode, o.imperfection_amplitude));
  const Model& model = imperfect ? *imperfect : original;
  PathSystem unscaled(model, loads, o);
  res.free_dofs = unscaled.nf();
  res.statically_indeterminate = unscaled.redundant();
  if (unscaled.nf() == 0) {  // every DOF held: no path to follow (and KINSOL cannot take an empty system)
    res.finish(PathTermination::InitialStateFailed, 0.0, 0,
               "no free DOF (every DOF is supported, prescribed or held): there is no path to follow");
    return res;
  }
  KinsolSolver kin(o.newton);
  FactorCache factors;
  const StepSolution start = initial_state(unscaled, factors, kin);
  if (!start.converged) {
    res.finish(PathTermination::InitialStateFailed, 0.0, 0, start.report);
    return res;
  }
  // The structure's own scales: the arc-length weight of the load factor, the automatic first
  // step and the force scale of the convergence test (solvers/path/path_scales.hpp).
  const PathScales scales = path_scales(model, unscaled, factors, start.state);
  PathSystem sys = std::move(unscaled).with_scales(scales.lambda_ref, scales.psi);
  const double ds0 = first_step(o, scales);
  if (o.control == PathControl::ArcLength && o.arc_length_auto && !(ds0 > 0.0)) {
    res.finish(PathTermination::NoAutomaticStep);
    return res;
  }
  PathRun path(original, o, sys, factors, kin, start.state, ds0, res);
  path.run();
  res.factorizations = kin.factorizations() + factors.factorizations();
  res.symbolic_analyses = kin.symbolic_analyses() + factors.symbolic_analyses();
  res.chord_steps = path.corrector().chord_steps();
  res.chord_fallbacks = path.corrector().chord_fallbacks();
  return res;
}

}  // namespace beamfea
