#include "solvers/path/equilibrium.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "solvers/path/corrector.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

namespace {
// Forces below this fraction of the stiffest element's force for a displacement of L are round-off:
// the floor of the force scale of the convergence test on models loaded lightly or not at all.
constexpr double kRoundOffForceRatio = 1e-5;
}  // namespace

PathEquilibrium::PathEquilibrium(const Model& model, const PathOptions& o) : ns(model), chord(o.chord_corrector) {
  const DofMap& map = ns.reference_map();
  // Prescribed values that the constraints make inconsistent (a loop that cannot close, a rigid link
  // whose ends are prescribed apart): bad input naming the link, joint or DOF.
  if (auto conflict = map.check_consistency(map.prescribed_values()); !conflict.empty()) throw ModelError("supports and prescribed values", conflict);
  L = ns.length_scale();
  gen_to_free.assign(ns.size(), -1);
  for (int i = 0; i < ns.size(); ++i) {
    if (map.prescribed_index(ns.gens()[i].raw) >= 0) continue;
    gen_to_free[i] = static_cast<int>(free.size());
    free.push_back(i);
  }
  for (int p = 0; p < map.prescribed_size(); ++p) {
    const auto& pv = map.prescribed()[p];
    if (pv.dof.owner == DofRef::Owner::Node && map.is_slave(pv.dof.index)) cons.push_back({pv.dof.index, pv.dof.comp, pv.value});
  }
  select_independent_constraints();
  f_ext = external_force(model, map);
  has_loads = f_ext.size() > 0 && f_ext.cwiseAbs().maxCoeff() > 0.0;
  if (o.control == PathControl::Displacement) {
    const int raw = map.raw_node(o.control_node, o.control_dof);
    if (map.prescribed_index(raw) >= 0)
      throw ModelError(model.describe({DofRef::Owner::Node, o.control_node, o.control_dof}),
                       "is supported or prescribed: it cannot be the controlled DOF");
    ctrl = {o.control_node, o.control_dof, 0.0};
  }
  if (!has_loads && o.control != PathControl::Displacement)
    throw ModelError("loads", "path: the model has none; use displacement control to impose a motion");
  nf = static_cast<int>(free.size());
  nc = ncs + static_cast<int>(closure_rows.size());
  // Reference force for the convergence test.
  double fmax = 0.0;
  for (int n = 0; n < static_cast<int>(model.nodes.size()); ++n) {
    fmax = std::max(fmax, f_ext.segment<3>(6 * n).cwiseAbs().maxCoeff());
    fmax = std::max(fmax, f_ext.segment<3>(6 * n + 3).cwiseAbs().maxCoeff() / L);
  }
  for (int r = 6 * static_cast<int>(model.nodes.size()); r < map.raw_size(); ++r) fmax = std::max(fmax, std::abs(f_ext[r]));
  const NonlinearState s0 = ns.reference_state();
  const auto ev = ns.evaluate(s0, Eigen::VectorXd::Zero(map.raw_size()), true);
  double kmax = 0.0;
  for (int i = 0; i < ns.size(); ++i) {
    const double k = std::abs(ev.tangent.coeff(i, i)) / (ns.is_rotation(i) ? L * L : 1.0);
    kmax = std::max(kmax, k);
  }
  f_max = fmax;
  F_floor = kRoundOffForceRatio * kmax * L;
  set_load_scale(1.0);
}

void PathEquilibrium::set_load_scale(double lambda_ref) {
  F_ref = std::max(f_max * lambda_ref, F_floor);
  if (!(F_ref > 0.0)) F_ref = 1.0;
}

void PathEquilibrium::select_independent_constraints() {
  const NonlinearState s0 = ns.reference_state();
  const auto tw = ns.twists(s0);
  const int nfree = static_cast<int>(free.size());
  const int nl = ns.closure_rows();
  const int m = static_cast<int>(cons.size()) + nl;
  if (m == 0) return;
  // Rows and coordinates in lengths: rotation rows and rotation coordinates scaled by L.
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(m, nfree);
  for (std::size_t c = 0; c < cons.size(); ++c)
    for (const auto& [g, v] : ns.raw_row(s0, tw, cons[c].node, cons[c].comp))
      if (gen_to_free[g] >= 0) C(static_cast<Eigen::Index>(c), gen_to_free[g]) += v * (cons[c].comp < 3 ? 1.0 : L);
  const SparseMatrix Cl = ns.closure_jacobian(s0, tw);
  for (int j = 0; j < Cl.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(Cl, j); it; ++it)
      if (gen_to_free[j] >= 0) {
        const int r = static_cast<int>(it.row());
        C(static_cast<Eigen::Index>(cons.size()) + r, gen_to_free[j]) += it.value() * (r % 6 < 3 ? 1.0 : L);
      }
  for (int k = 0; k < nfree; ++k)
    if (ns.is_rotation(free[k])) C.col(k) /= L;
  const RowSelection sel = independent_rows(C);
  std::vector<ConstraintDef> kept;
  for (int i : sel.kept) {
    if (i < static_cast<int>(cons.size())) kept.push_back(cons[i]);
    else closure_rows.push_back(i - static_cast<int>(cons.size()));
  }
  for (int i : sel.redundant)
    redundant.push_back(i < static_cast<int>(cons.size())
                            ? ns.model().describe({DofRef::Owner::Node, cons[i].node, cons[i].comp})
                            : ns.describe_closure_row(i - static_cast<int>(cons.size())));
  cons = std::move(kept);
  ncs = static_cast<int>(cons.size());
}

Eigen::VectorXd PathEquilibrium::closure_multipliers(const Eigen::VectorXd& mu) const {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(ns.closure_rows());
  for (std::size_t i = 0; i < closure_rows.size(); ++i) out[closure_rows[i]] = mu[ncs + static_cast<Eigen::Index>(i)];
  return out;
}

double PathEquilibrium::weighted_dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
  double s = 0.0;
  for (int k = 0; k < nf; ++k) s += weight(free[k]) * a[k] * b[k];
  return s;
}

double PathEquilibrium::cvalue(const NonlinearState& st, const ConstraintDef& c) const {
  if (c.comp < 3) return st.x[c.node][c.comp] - ns.model().nodes[c.node].x[c.comp];
  return log_so3(st.R[c.node])[c.comp - 3];
}

Eigen::VectorXd PathEquilibrium::delta_gens(const Eigen::VectorXd& u) const {
  Eigen::VectorXd d = Eigen::VectorXd::Zero(ns.size());
  for (int k = 0; k < nf; ++k) d[free[k]] = u[k];
  return d;
}

Eigen::VectorXd PathEquilibrium::start_unknowns(const Converged& c, const StepSpec& s) const {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(unknowns(s));
  u.segment(nf, nc) = c.mu;
  if (s.kind != StepKind::Load) u[nf + nc] = extra_is_lambda(s) ? c.lambda : c.extra_mu;
  return u;
}

PathEquilibrium::Eval PathEquilibrium::state_of(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u) const {
  Eval e;
  e.st = ns.retract(start.state, delta_gens(u));
  e.lambda = s.kind == StepKind::Load ? s.lambda : (extra_is_lambda(s) ? u[nf + nc] : 0.0);
  e.f_app = e.lambda * f_ext;
  const DofMap& map = ns.reference_map();
  for (int c = 0; c < ncs; ++c) e.f_app[map.raw_node(cons[c].node, cons[c].comp)] += u[nf + c];
  e.mu_closure = closure_multipliers(u.segment(nf, nc));
  if (s.kind == StepKind::Control && !has_loads) e.f_app[map.raw_node(ctrl.node, ctrl.comp)] += u[nf + nc];
  return e;
}

void PathEquilibrium::residual(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u, Eigen::VectorXd& F) const {
  const Eval e = state_of(start, s, u);
  const auto ev = ns.evaluate(e.st, e.f_app, false, e.mu_closure, e.lambda);
  F.resize(unknowns(s));
  for (int k = 0; k < nf; ++k) F[k] = ev.residual[free[k]];
  for (int c = 0; c < ncs; ++c) F[nf + c] = cvalue(e.st, cons[c]) - cons[c].target;
  if (!closure_rows.empty()) {
    const Eigen::VectorXd cl = ns.closure_values(e.st);
    for (std::size_t i = 0; i < closure_rows.size(); ++i) F[nf + ncs + static_cast<int>(i)] = cl[closure_rows[i]];
  }
  if (s.kind == StepKind::Control) F[nf + nc] = cvalue(e.st, ctrl) - s.control;
  if (s.kind == StepKind::Arc) {
    const double dl = e.lambda - start.lambda;
    F[nf + nc] = (weighted_dot(u, u) + psi2 * dl * dl - s.ds * s.ds) / (2.0 * s.ds);
  }
}

std::vector<std::pair<int, double>> PathEquilibrium::crow(const NonlinearState& st, const std::vector<Twist>& tw,
                                                          const ConstraintDef& c, const SparseMatrix* D) const {
  std::vector<std::pair<int, double>> out;
  const auto row = ns.raw_row(st, tw, c.node, c.comp);
  if (!D) {
    for (const auto& [g, v] : row)
      if (gen_to_free[g] >= 0) out.emplace_back(gen_to_free[g], v);
    return out;
  }
  Eigen::VectorXd r = Eigen::VectorXd::Zero(ns.size());
  for (const auto& [g, v] : row) r[g] = v;
  const Eigen::VectorXd rd = SparseMatrix(D->transpose()) * r;
  for (int k = 0; k < nf; ++k)
    if (rd[free[k]] != 0.0) out.emplace_back(k, rd[free[k]]);
  return out;
}

void PathEquilibrium::jacobian(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u, SparseMatrix& J) const {
  const Eval e = state_of(start, s, u);
  const auto ev = ns.evaluate(e.st, e.f_app, true, e.mu_closure, e.lambda);
  jacobian_from(start, s, u, e, ev.tangent, J);
}

void PathEquilibrium::jacobian_from(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u, const Eval& e,
                                    const SparseMatrix& tangent, SparseMatrix& J) const {
  const Eigen::VectorXd dg = delta_gens(u);
  const SparseMatrix D = ns.retraction_jacobian(dg);
  // D = I at Delta = 0 (a converged state's own tangent): no product (a spherical joint's block
  // A^-1 I A is I only to round-off: multiplied as before).
  const bool at_start = dg.isZero(0.0) && std::none_of(ns.gens().begin(), ns.gens().end(), [](const auto& g) {
                          return g.kind == NonlinearStructure::GenKind::JointSpherical;
                        });
  SparseMatrix KDp;
  if (!at_start) KDp = tangent * D;
  const SparseMatrix& KD = at_start ? tangent : KDp;
  const auto tw = ns.twists(e.st);
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(KD.nonZeros() + 16 * (nc + 1));
  for (int j = 0; j < KD.outerSize(); ++j) {
    if (gen_to_free[j] < 0) continue;
    for (SparseMatrix::InnerIterator it(KD, j); it; ++it)
      if (gen_to_free[it.row()] >= 0) t.emplace_back(gen_to_free[it.row()], gen_to_free[j], it.value());
  }
  for (int c = 0; c < ncs; ++c) {
    for (const auto& [k, v] : crow(e.st, tw, cons[c], nullptr)) t.emplace_back(k, nf + c, -v);
    for (const auto& [k, v] : crow(e.st, tw, cons[c], &D)) t.emplace_back(nf + c, k, v);
  }
  if (!closure_rows.empty()) {
    // Columns: the force rows B (the residual gains B^T mu); rows: the exact gradient of c times D.
    const SparseRowMatrix B = ns.closure_force_rows(e.st, tw);
    const SparseRowMatrix CD = SparseRowMatrix(ns.closure_jacobian(e.st, tw) * D);
    for (std::size_t i = 0; i < closure_rows.size(); ++i) {
      const int r = closure_rows[i], x = nf + ncs + static_cast<int>(i);
      for (SparseRowMatrix::InnerIterator it(B, r); it; ++it)
        if (gen_to_free[it.col()] >= 0) t.emplace_back(gen_to_free[it.col()], x, it.value());
      for (SparseRowMatrix::InnerIterator it(CD, r); it; ++it)
        if (gen_to_free[it.col()] >= 0) t.emplace_back(x, gen_to_free[it.col()], it.value());
    }
  }
  const int x = nf + nc;
  if (s.kind != StepKind::Load) {
    if (extra_is_lambda(s)) {
      const Eigen::VectorXd p = ns.reduce(e.st, tw, load_at(e.st));
      for (int k = 0; k < nf; ++k)
        if (p[free[k]] != 0.0) t.emplace_back(k, x, -p[free[k]]);
    } else {
      for (const auto& [k, v] : crow(e.st, tw, ctrl, nullptr)) t.emplace_back(k, x, -v);
    }
    if (s.kind == StepKind::Control) {
      for (const auto& [k, v] : crow(e.st, tw, ctrl, &D)) t.emplace_back(x, k, v);
    } else {
      for (int k = 0; k < nf; ++k) t.emplace_back(x, k, weight(free[k]) * u[k] / s.ds);
      t.emplace_back(x, x, psi2 * (e.lambda - start.lambda) / s.ds);
    }
    t.emplace_back(x, x, 0.0);
  }
  // Explicit zeros on the diagonal keep the pattern (and UMFPACK's symbolic analysis) constant.
  for (int k = 0; k < x; ++k) t.emplace_back(k, k, 0.0);
  J.resize(unknowns(s), unknowns(s));
  J.setFromTriplets(t.begin(), t.end());
}

Eigen::VectorXd PathEquilibrium::fscale(const StepSpec& s) const {
  Eigen::VectorXd f(unknowns(s));
  for (int k = 0; k < nf; ++k) f[k] = 1.0 / (F_ref * (ns.is_rotation(free[k]) ? L : 1.0));
  for (int c = 0; c < ncs; ++c) f[nf + c] = cons[c].comp < 3 ? 1.0 / L : 1.0;
  for (std::size_t i = 0; i < closure_rows.size(); ++i) f[nf + ncs + static_cast<int>(i)] = closure_rows[i] % 6 < 3 ? 1.0 / L : 1.0;
  if (s.kind == StepKind::Control) f[nf + nc] = ctrl.comp < 3 ? 1.0 / L : 1.0;
  if (s.kind == StepKind::Arc) f[nf + nc] = 1.0 / s.ds;
  return f;
}

bool PathEquilibrium::solve(KinsolSolver& kin, const Converged& start, const StepSpec& s, Eigen::VectorXd u, Converged& out,
                            std::string& report) const {
  auto finish = [&](const Eigen::VectorXd& uu) {
    const Eval e = state_of(start, s, uu);
    out.state = e.st;
    out.lambda = e.lambda;
    out.mu = uu.segment(nf, nc);
    out.extra_mu = (s.kind == StepKind::Control && !has_loads) ? uu[nf + nc] : 0.0;
  };
  long chord_its = 0;
  if (chord && tangent_factor_rows(start) >= 0) {
    Eigen::VectorXd uc = u;
    const ChordOutcome co = chord_correct(*this, start, s, uc, kin.options().function_tolerance);
    chord_its = co.iterations;
    if (co.converged) {
      ++chord_steps_;
      finish(uc);
      out.iterations = 0;
      out.chord_iterations = chord_its;
      out.by_chord = true;
      report = fmt::format("chord: converged after {} iterations, |F| = {:.3e}", chord_its, co.residual_norm);
      return true;
    }
    ++chord_fallbacks_;
  }
  KinsolSummary sum;
  try {
    sum = kin.solve(
        u, fscale(s), [&](const Eigen::VectorXd& uu, Eigen::VectorXd& F) { residual(start, s, uu, F); },
        [&](const Eigen::VectorXd& uu, const Eigen::VectorXd&, SparseMatrix& J) { jacobian(start, s, uu, J); });
  } catch (const ModelError& e) {  // e.g. a co-rotated frame that cannot be defined: a failed step
    report = e.what();
    return false;
  }
  report = sum.report();
  if (sum.status != KinsolStatus::Succeeded) return false;
  finish(u);
  out.iterations = sum.iterations;
  out.chord_iterations = chord_its;
  out.by_chord = false;
  return true;
}

Eigen::VectorXd PathEquilibrium::load_at(const NonlinearState& st) const { return f_ext + ns.dead_load_change(st); }

Eigen::VectorXd PathEquilibrium::load_pattern(const NonlinearState& st) const {
  const Eigen::VectorXd p = ns.reduce(st, ns.twists(st), load_at(st));
  Eigen::VectorXd pf(nf);
  for (int k = 0; k < nf; ++k) pf[k] = p[free[k]];
  return pf;
}

StepSpec PathEquilibrium::tangent_spec(const Converged& c) const {
  StepSpec s;
  if (has_loads) {
    s.kind = StepKind::Load;
    s.lambda = c.lambda;
  } else {
    s.kind = StepKind::Control;
    s.control = cvalue(c.state, ctrl);
  }
  return s;
}

namespace {
// Exact equality of two converged states (the key of the evaluation kept by PathEquilibrium).
bool same_vector(const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return a.size() == b.size() && a == b; }
bool same_state(const Converged& a, const Converged& b) {
  if (a.lambda != b.lambda || a.extra_mu != b.extra_mu || !same_vector(a.mu, b.mu)) return false;
  const NonlinearState &x = a.state, &y = b.state;
  if (x.x.size() != y.x.size() || x.R.size() != y.R.size() || x.q.size() != y.q.size() || x.Q.size() != y.Q.size())
    return false;
  for (std::size_t i = 0; i < x.x.size(); ++i)
    if (x.x[i] != y.x[i] || x.R[i] != y.R[i]) return false;
  for (std::size_t i = 0; i < x.q.size(); ++i)
    if (!same_vector(x.q[i], y.q[i])) return false;
  for (std::size_t i = 0; i < x.Q.size(); ++i)
    if (x.Q[i] != y.Q[i]) return false;
  return true;
}
}  // namespace

const NonlinearStructure::Evaluation& PathEquilibrium::evaluation_at(const Converged& c) const {
  if (cache_.valid && same_state(cache_.key, c)) return cache_.ev;
  cache_.valid = cache_.has_tangent = false;
  const StepSpec s = tangent_spec(c);
  const Eval e = state_of(c, s, start_unknowns(c, s));
  cache_.ev = ns.evaluate(e.st, e.f_app, true, e.mu_closure, e.lambda);
  cache_.key = c;
  cache_.valid = true;
  return cache_.ev;
}

namespace {
// S = the lower triangle of sym(J) when J is symmetric to kSymmetricTangentSkew (and its pattern is);
// false otherwise (S not set).
bool symmetric_part(const SparseMatrix& J, SparseMatrix& S) {
  const SparseMatrix Jt = J.transpose();
  double big = 0.0, skew = 0.0;
  for (int j = 0; j < J.outerSize(); ++j) {
    SparseMatrix::InnerIterator a(J, j), b(Jt, j);
    // Same pattern both ways (an assembled tangent's is symmetric); otherwise not taken.
    for (; a && b; ++a, ++b) {
      if (a.row() != b.row()) return false;
      big = std::max(big, std::abs(a.value()));
      skew = std::max(skew, std::abs(a.value() - b.value()));
    }
    if (a || b) return false;
  }
  if (!(big > 0.0) || !(skew <= kSymmetricTangentSkew * big)) return false;
  S = SparseMatrix(0.5 * (J + Jt)).triangularView<Eigen::Lower>();
  return true;
}
}  // namespace

const Eigen::VectorXd& PathEquilibrium::tangent(const Converged& c) const {
  const NonlinearStructure::Evaluation& ev = evaluation_at(c);
  if (cache_.has_tangent) return cache_.t;
  const StepSpec s = tangent_spec(c);
  const Eigen::VectorXd u0 = start_unknowns(c, s);
  jacobian_from(c, s, u0, state_of(c, s, u0), ev.tangent, cache_.J);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(cache_.J.rows());
  if (has_loads) {
    rhs.head(nf) = load_pattern(c.state);
  } else {
    rhs[nf + nc] = 1.0;
  }
  cache_.t.resize(0);
  cache_.cholesky = false;
  // The symmetric tangent's LL^T where it applies (see tangent_is_cholesky), else the LU.
  if (nf > kSymmetricTangentMinDofs && nc == 0 && cache_.J.rows() == nf) {
    cache_.J.makeCompressed();
    if (symmetric_part(cache_.J, symmetric_llt_.matrix()) && symmetric_llt_.factorize()) {
      cache_.t = symmetric_llt_.solver().solve(rhs);
      cache_.cholesky = cache_.t.allFinite();
      if (!cache_.cholesky) cache_.t.resize(0);
    }
  }
  if (!cache_.cholesky && predictor_lu_.factorize(cache_.J)) {
    cache_.t = predictor_lu_.solver().solve(rhs);
    if (!cache_.t.allFinite()) cache_.t.resize(0);
  }
  cache_.has_tangent = true;
  return cache_.t;
}

int PathEquilibrium::tangent_factor_rows(const Converged& c) const {
  if (!cache_.valid || !cache_.has_tangent || !cache_.t.size() || !same_state(cache_.key, c)) return -1;
  return static_cast<int>(cache_.J.rows());
}

bool PathEquilibrium::tangent_is_cholesky(const Converged& c) const {
  return tangent_factor_rows(c) >= 0 && cache_.cholesky;
}

void PathEquilibrium::solve_with_symmetric_tangent(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  x = symmetric_llt_.solver().solve(b);
}

Eigen::VectorXd PathEquilibrium::solve_with_tangent_factor(const Eigen::VectorXd& b) const {
  if (cache_.cholesky) return symmetric_llt_.solver().solve(b);
  auto& lu = predictor_lu_.solver();
  const double irstep = lu.umfpackControl()(UMFPACK_IRSTEP);
  lu.umfpackControl()(UMFPACK_IRSTEP) = 0;
  Eigen::VectorXd x = lu.solve(b);
  lu.umfpackControl()(UMFPACK_IRSTEP) = irstep;
  return x;
}

double PathEquilibrium::conjugate_slope(const Converged& c) const {
  const Eigen::VectorXd& t = tangent(c);
  if (!t.size()) return NAN;
  if (!has_loads) return t[nf + nc];
  const auto tw = ns.twists(c.state);
  double rate = 0.0;  // du_c / dlambda
  for (const auto& [k, v] : crow(c.state, tw, ctrl, nullptr)) rate += v * t[k];
  return 1.0 / rate;  // +-inf where the controlled DOF does not move with the load (its snap-back)
}

Eigen::VectorXd PathEquilibrium::increment(const Converged& a, const Converged& b) const {
  Eigen::VectorXd du(nf);
  const auto& gens = ns.gens();
  for (int k = 0; k < nf; ++k) {
    const auto& g = gens[free[k]];
    switch (g.kind) {
      case NonlinearStructure::GenKind::NodeTranslation: du[k] = b.state.x[g.owner][g.comp] - a.state.x[g.owner][g.comp]; break;
      case NonlinearStructure::GenKind::NodeSpin:
        du[k] = log_so3(b.state.R[g.owner] * a.state.R[g.owner].transpose())[g.comp];
        break;
      case NonlinearStructure::GenKind::JointScalar:
      case NonlinearStructure::GenKind::JointSpherical: du[k] = b.state.q[g.owner][g.comp] - a.state.q[g.owner][g.comp]; break;
    }
  }
  return du;
}

Eigen::MatrixXd PathEquilibrium::constraint_matrix(const NonlinearState& st, bool with_control) const {
  const auto tw = ns.twists(st);
  const int m = nc + (with_control ? 1 : 0);
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(m, nf);
  for (int c = 0; c < ncs; ++c)
    for (const auto& [k, v] : crow(st, tw, cons[c], nullptr)) C(c, k) += v;
  if (with_control)
    for (const auto& [k, v] : crow(st, tw, ctrl, nullptr)) C(nc, k) += v;
  if (!closure_rows.empty()) {
    const SparseRowMatrix Cl = ns.closure_jacobian(st, tw);
    for (std::size_t i = 0; i < closure_rows.size(); ++i)
      for (SparseRowMatrix::InnerIterator it(Cl, closure_rows[i]); it; ++it)
        if (gen_to_free[it.col()] >= 0) C(ncs + static_cast<Eigen::Index>(i), gen_to_free[it.col()]) += it.value();
  }
  return C;
}

bool PathEquilibrium::initial_state(KinsolSolver& kin, Converged& out, std::string& report) const {
  Converged cur;
  const DofMap& map = ns.reference_map();
  bool nonzero = false;
  Eigen::VectorXd d = Eigen::VectorXd::Zero(ns.size());
  for (int i = 0; i < ns.size(); ++i) {
    const int p = map.prescribed_index(ns.gens()[i].raw);
    if (p >= 0 && map.prescribed()[p].value != 0.0) {
      d[i] = map.prescribed()[p].value;
      nonzero = true;
    }
  }
  cur.state = ns.retract(ns.reference_state(), d);
  cur.mu = Eigen::VectorXd::Zero(nc);
  for (const auto& c : cons) nonzero = nonzero || c.target != 0.0;
  if (!nonzero) {
    out = cur;
    return true;
  }
  StepSpec s;
  s.kind = StepKind::Load;
  return solve(kin, cur, s, start_unknowns(cur, s), out, report);
}

}  // namespace beamfea
