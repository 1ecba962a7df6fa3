#include "solvers/path/equilibrium.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "solvers/member_loading.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

namespace {
// Forces below this fraction of the stiffest element's force for a displacement of L are round-off:
// the floor of the force scale of the convergence test on models loaded lightly or not at all.
constexpr double kRoundOffForceRatio = 1e-5;

// f(node, comp, coefficient) for each term of a constraint (a single DOF: coefficient 1).
template <class F>
void for_each_term(const ConstraintDef& c, F&& f) {
  if (c.terms.empty()) {
    f(c.node, c.comp, 1.0);
    return;
  }
  for (const auto& t : c.terms) f(t.node, t.comp, t.coefficient);
}

// A general row from its terms (node, comp and coefficient each), held at `target`.
ConstraintDef general_row(std::vector<ConstraintDef::Term> terms, double target) {
  ConstraintDef c;
  c.node = terms.front().node;
  c.comp = terms.front().comp;
  c.target = target;
  c.terms = std::move(terms);
  return c;
}

// The user rows of core/dof_map.hpp (skewed supports, ties, linear constraints) as constraints of
// the path: exact on translations (linear in x - X); on rotations the same linear row on the
// rotation vectors log(R) of the nodes, as a support on a slave node holds its rotation.
void add_user_rows(const Model& m, std::vector<ConstraintDef>& cons) {
  for (const auto& s : m.supports) {
    if (!s.skewed) continue;
    for (int k = 0; k < 6; ++k) {
      if (!s.fixed[k]) continue;
      const int offset = k < 3 ? 0 : 3;
      std::vector<ConstraintDef::Term> terms;
      for (int i = 0; i < 3; ++i)
        if (s.axes(k - offset, i) != 0.0) terms.push_back({s.node, offset + i, s.axes(k - offset, i)});
      cons.push_back(general_row(std::move(terms), 0.0));
    }
  }
  for (const auto& t : m.ties)
    for (int k = 0; k < 6; ++k)
      if (t.dofs[k]) cons.push_back(general_row({{t.nodes[1], k, 1.0}, {t.nodes[0], k, -1.0}}, 0.0));
  for (const auto& lc : m.constraints) {
    std::vector<ConstraintDef::Term> terms;
    for (const auto& t : lc.terms) terms.push_back({t.dof.index, t.dof.comp, t.coefficient});
    cons.push_back(general_row(std::move(terms), lc.value));
  }
}
}  // namespace

PathSystem::PathSystem(const Model& model, const LoadSet& loads, const PathOptions& o) : ns_(model, loads), loads_(&loads) {
  const DofMap& map = ns_.reference_map();
  // Prescribed values that the constraints make inconsistent (a loop that cannot close, a rigid link
  // whose ends are prescribed apart): bad input naming the link, joint or DOF.
  if (auto conflict = map.check_consistency(map.prescribed_values()); !conflict.empty()) throw ModelError("supports and prescribed values", conflict);
  L_ = ns_.length_scale();
  gen_to_free_.assign(ns_.size(), -1);
  for (int i = 0; i < ns_.size(); ++i) {
    if (map.prescribed_index(ns_.gens()[i].raw) >= 0) continue;
    gen_to_free_[i] = static_cast<int>(free_.size());
    free_.push_back(i);
  }
  for (int p = 0; p < map.prescribed_size(); ++p) {
    const auto& pv = map.prescribed()[p];
    if (pv.constraint < 0 && pv.dof.owner == DofRef::Owner::Node && map.is_slave(pv.dof.index))
      all_cons_.push_back({pv.dof.index, pv.dof.comp, pv.value, {}});
  }
  add_user_rows(model, all_cons_);
  nf_ = static_cast<int>(free_.size());
  if (!all_cons_.empty() || ns_.closure_rows() > 0) keep_rows(independent_rows(scaled_rows(ns_.reference_state())));
  f_ext_ = external_force(model, map, loads);
  has_loads_ = f_ext_.size() > 0 && f_ext_.cwiseAbs().maxCoeff() > 0.0;
  if (o.control == PathControl::Displacement) {
    const int raw = map.raw_node(o.control_node, o.control_dof);
    if (map.prescribed_index(raw) >= 0)
      throw ModelError(model.describe({DofRef::Owner::Node, o.control_node, o.control_dof}),
                       "is supported or prescribed: it cannot be the controlled DOF");
    ctrl_ = {o.control_node, o.control_dof, 0.0, {}};
  }
  if (!has_loads_ && o.control != PathControl::Displacement)
    throw ModelError("loads", "path: the model has none; use displacement control to impose a motion");
  // Reference force for the convergence test.
  double fmax = 0.0;
  for (int n = 0; n < static_cast<int>(model.nodes.size()); ++n) {
    fmax = std::max(fmax, f_ext_.segment<3>(6 * n).cwiseAbs().maxCoeff());
    fmax = std::max(fmax, f_ext_.segment<3>(6 * n + 3).cwiseAbs().maxCoeff() / L_);
  }
  for (int r = 6 * static_cast<int>(model.nodes.size()); r < map.raw_size(); ++r) fmax = std::max(fmax, std::abs(f_ext_[r]));
  const NonlinearState s0 = ns_.reference_state();
  const auto ev = ns_.evaluate(s0, Eigen::VectorXd::Zero(map.raw_size()), /*with_tangent=*/true);
  double kmax = 0.0;
  for (int i = 0; i < ns_.size(); ++i) {
    const double k = std::abs(ev.tangent.coeff(i, i)) / (ns_.is_rotation(i) ? L_ * L_ : 1.0);
    kmax = std::max(kmax, k);
  }
  f_max_ = fmax;
  F_floor_ = kRoundOffForceRatio * kmax * L_;
  set_load_scale(1.0);
}

PathSystem PathSystem::with_scales(double lambda_ref, double psi) && {
  if (lambda_ref > 0.0) set_load_scale(lambda_ref);
  psi2_ = psi * psi;
  return std::move(*this);
}

void PathSystem::set_load_scale(double lambda_ref) {
  F_ref_ = std::max(f_max_ * lambda_ref, F_floor_);
  if (!(F_ref_ > 0.0)) F_ref_ = 1.0;
}

Eigen::MatrixXd PathSystem::scaled_rows(const NonlinearState& st) const {
  const auto tw = ns_.twists(st);
  const int nfree = static_cast<int>(free_.size());
  const int ncons = static_cast<int>(all_cons_.size());
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(ncons + ns_.closure_rows(), nfree);
  for (int c = 0; c < ncons; ++c)
    for_each_term(all_cons_[c], [&](int node, int comp, double coefficient) {
      for (const auto& [g, v] : ns_.raw_row(st, tw, node, comp))
        if (gen_to_free_[g] >= 0) C(c, gen_to_free_[g]) += coefficient * v * (comp < 3 ? 1.0 : L_);
    });
  if (ns_.closure_rows() > 0) {
    const SparseMatrix Cl = ns_.closure_jacobian(st, tw);
    for (int j = 0; j < Cl.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(Cl, j); it; ++it)
        if (gen_to_free_[j] >= 0) {
          const int r = static_cast<int>(it.row());
          C(ncons + r, gen_to_free_[j]) += it.value() * (r % 6 < 3 ? 1.0 : L_);
        }
  }
  for (int k = 0; k < nfree; ++k)
    if (ns_.is_rotation(free_[k])) C.col(k) /= L_;
  return C;
}

void PathSystem::keep_rows(const RowSelection& sel) {
  const int ncons = static_cast<int>(all_cons_.size());
  kept_ = sel.kept;
  cons_.clear();
  closure_rows_.clear();
  redundant_.clear();
  dropped_.clear();
  for (int i : sel.kept) {
    if (i < ncons) cons_.push_back(all_cons_[i]);
    else closure_rows_.push_back(i - ncons);
  }
  for (int i : sel.redundant) {
    const bool closure = i >= ncons;
    redundant_.push_back(!closure ? ns_.model().describe({DofRef::Owner::Node, all_cons_[i].node, all_cons_[i].comp})
                                  : ns_.describe_closure_row(i - ncons));
    dropped_.push_back(closure ? Dropped{{}, i - ncons} : Dropped{all_cons_[i], -1});
  }
  ncs_ = static_cast<int>(cons_.size());
  nc_ = ncs_ + static_cast<int>(closure_rows_.size());
}

namespace {
// The smallest singular value of the rows `rows` of C (0 for none): sigma_min^2, the lowest
// eigenvalue of A A^T (rows x rows).
double smallest_singular_value(const Eigen::MatrixXd& C, const std::vector<int>& rows) {
  if (rows.empty()) return 0.0;
  Eigen::MatrixXd A(static_cast<Eigen::Index>(rows.size()), C.cols());
  for (std::size_t r = 0; r < rows.size(); ++r) A.row(static_cast<Eigen::Index>(r)) = C.row(rows[r]);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(A * A.transpose(), Eigen::EigenvaluesOnly);
  return std::sqrt(std::max(0.0, es.eigenvalues()[0]));
}

// The `count` rows of C that a QR of C^T with column pivoting takes first (as independent_rows, without
// its tolerance), ascending, and the others.
RowSelection leading_rows(const Eigen::MatrixXd& C, int count) {
  RowSelection out;
  const int m = static_cast<int>(C.rows());
  std::vector<char> lead(m, 0);
  const double scale = C.cwiseAbs().maxCoeff();
  if (scale > 0.0 && count > 0) {
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(C.transpose() / scale);
    for (int k = 0; k < std::min(count, m); ++k) lead[qr.colsPermutation().indices()[k]] = 1;
  }
  for (int i = 0; i < m; ++i) (lead[i] ? out.kept : out.redundant).push_back(i);
  return out;
}
}  // namespace

PathSystem::RowsAt PathSystem::rows_at(const NonlinearState& st) const {
  RowsAt out;
  Eigen::MatrixXd C = scaled_rows(st);
  // Only the coordinates the rows reach (a loop's joints and links among a frame's many DOFs).
  std::vector<Eigen::Index> reached;
  for (Eigen::Index k = 0; k < C.cols(); ++k)
    if (C.col(k).cwiseAbs().maxCoeff() > 0.0) reached.push_back(k);
  if (static_cast<Eigen::Index>(reached.size()) < C.cols()) C = Eigen::MatrixXd(C(Eigen::all, reached));
  out.rank = static_cast<int>(independent_rows(C).kept.size());
  out.fresh = leading_rows(C, nc_);
  out.kept = smallest_singular_value(C, kept_);
  out.best = smallest_singular_value(C, out.fresh.kept);
  out.same_as_kept = out.fresh.kept == kept_;
  return out;
}

int PathSystem::rank_above(const NonlinearState& st, double sigma) const {
  const Eigen::MatrixXd C = scaled_rows(st);
  if (C.size() == 0) return 0;
  const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(C).singularValues();
  return static_cast<int>((s.array() > sigma).count());
}

double PathSystem::rank_measure(const NonlinearState& st) const {
  if (nc_ == 0) return 0.0;
  const Eigen::MatrixXd C = scaled_rows(st);
  // Eigenvalues of C C^T (rows x rows), ascending: the nc-th largest is the nc-th singular value squared.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(C * C.transpose(), Eigen::EigenvaluesOnly);
  return std::sqrt(std::max(0.0, es.eigenvalues()[C.rows() - nc_]));
}

Eigen::MatrixXd PathSystem::multiplier_forces(const NonlinearState& st) const {
  const auto tw = ns_.twists(st);
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(nf_, nc_);
  for (int c = 0; c < ncs_; ++c)
    for (const auto& [k, v] : constraint_row(st, tw, cons_[c], nullptr)) G(k, c) -= v;
  if (!closure_rows_.empty()) {
    const SparseRowMatrix B = ns_.closure_force_rows(st, tw);
    for (std::size_t i = 0; i < closure_rows_.size(); ++i)
      for (SparseRowMatrix::InnerIterator it(B, closure_rows_[i]); it; ++it)
        if (gen_to_free_[it.col()] >= 0) G(gen_to_free_[it.col()], ncs_ + static_cast<Eigen::Index>(i)) += it.value();
  }
  return G;
}

Eigen::VectorXd PathSystem::reselect(const NonlinearState& st, const Eigen::VectorXd& mu, const RowSelection& fresh) {
  const Eigen::VectorXd g = multiplier_forces(st) * mu;
  keep_rows(fresh);
  const Eigen::MatrixXd G = multiplier_forces(st);
  if (G.cols() == 0) return Eigen::VectorXd();
  return G.colPivHouseholderQr().solve(g);
}

PathSystem::Departure PathSystem::dropped_row_departure(const NonlinearState& st) const {
  Departure worst;
  Eigen::VectorXd closure;
  for (std::size_t k = 0; k < dropped_.size(); ++k) {
    const Dropped& d = dropped_[k];
    double v = 0.0;
    if (d.closure_row >= 0) {
      if (closure.size() == 0) closure = ns_.closure_values(st);
      v = closure[d.closure_row] / (d.closure_row % 6 < 3 ? L_ : 1.0);
    } else {
      v = (constraint_value(st, d.constraint) - d.constraint.target) / (d.constraint.comp < 3 ? L_ : 1.0);
    }
    if (std::abs(v) > worst.value) worst = {std::abs(v), redundant_[k]};
  }
  return worst;
}

Eigen::VectorXd PathSystem::closure_multipliers(const Eigen::VectorXd& mu) const {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(ns_.closure_rows());
  for (std::size_t i = 0; i < closure_rows_.size(); ++i) out[closure_rows_[i]] = mu[ncs_ + static_cast<Eigen::Index>(i)];
  return out;
}

double PathSystem::weighted_dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
  double s = 0.0;
  for (int k = 0; k < nf_; ++k) s += weight(free_[k]) * a[k] * b[k];
  return s;
}

double PathSystem::constraint_value(const NonlinearState& st, const ConstraintDef& c) const {
  double value = 0.0;
  for_each_term(c, [&](int node, int comp, double coefficient) {
    value += coefficient * (comp < 3 ? st.x[node][comp] - ns_.model().nodes[node].x[comp] : log_so3(st.R[node])[comp - 3]);
  });
  return value;
}

Eigen::VectorXd PathSystem::delta_gens(const Eigen::VectorXd& u) const {
  Eigen::VectorXd d = Eigen::VectorXd::Zero(ns_.size());
  for (int k = 0; k < nf_; ++k) d[free_[k]] = u[k];
  return d;
}

Eigen::VectorXd PathSystem::start_unknowns(const Converged& c, const StepSpec& s) const {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(unknowns(s));
  u.segment(nf_, nc_) = c.mu;
  if (s.kind != StepKind::Load) u[nf_ + nc_] = extra_is_lambda(s) ? c.lambda : c.extra_mu;
  return u;
}

PathSystem::Eval PathSystem::state_of(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u) const {
  Eval e;
  e.st = ns_.retract(start.state, delta_gens(u));
  e.lambda = s.kind == StepKind::Load ? s.lambda : (extra_is_lambda(s) ? u[nf_ + nc_] : 0.0);
  e.f_app = e.lambda * f_ext_;
  const DofMap& map = ns_.reference_map();
  for (int c = 0; c < ncs_; ++c)
    for_each_term(cons_[c], [&](int node, int comp, double coefficient) { e.f_app[map.raw_node(node, comp)] += coefficient * u[nf_ + c]; });
  e.mu_closure = closure_multipliers(u.segment(nf_, nc_));
  // Imposed motion (no loads): the extra unknown is the force at the controlled DOF, its reaction,
  // also on the arc-length steps of a snap-back fall-back (which free the controlled DOF).
  if (s.kind != StepKind::Load && !has_loads_) e.f_app[map.raw_node(ctrl_.node, ctrl_.comp)] += u[nf_ + nc_];
  return e;
}

NonlinearStructure::Evaluation PathSystem::evaluate(const Eval& e, TangentWanted tangent) const {
  return ns_.evaluate(e.st, e.f_app, tangent == TangentWanted::Yes, e.mu_closure, e.lambda);
}

Eigen::VectorXd PathSystem::residual(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u) const {
  const Eval e = state_of(start, s, u);
  const auto ev = evaluate(e, TangentWanted::No);
  Eigen::VectorXd F(unknowns(s));
  for (int k = 0; k < nf_; ++k) F[k] = ev.residual[free_[k]];
  for (int c = 0; c < ncs_; ++c) F[nf_ + c] = constraint_value(e.st, cons_[c]) - cons_[c].target;
  if (!closure_rows_.empty()) {
    const Eigen::VectorXd cl = ns_.closure_values(e.st);
    for (std::size_t i = 0; i < closure_rows_.size(); ++i) F[nf_ + ncs_ + static_cast<int>(i)] = cl[closure_rows_[i]];
  }
  if (s.kind == StepKind::Control) F[nf_ + nc_] = constraint_value(e.st, ctrl_) - s.control;
  if (s.kind == StepKind::Arc) {
    const double dl = e.lambda - start.lambda;
    F[nf_ + nc_] = (weighted_dot(u, u) + psi2_ * dl * dl - s.ds * s.ds) / (2.0 * s.ds);
  }
  return F;
}

std::vector<std::pair<int, double>> PathSystem::constraint_row(const NonlinearState& st, const std::vector<Twist>& tw,
                                                               const ConstraintDef& c, const SparseMatrix* D) const {
  std::vector<std::pair<int, double>> out;
  std::vector<std::pair<int, double>> row;
  for_each_term(c, [&](int node, int comp, double coefficient) {
    for (const auto& [g, v] : ns_.raw_row(st, tw, node, comp)) row.emplace_back(g, coefficient * v);
  });
  if (!D) {
    for (const auto& [g, v] : row)
      if (gen_to_free_[g] >= 0) out.emplace_back(gen_to_free_[g], v);
    return out;
  }
  Eigen::VectorXd r = Eigen::VectorXd::Zero(ns_.size());
  for (const auto& [g, v] : row) r[g] += v;
  const Eigen::VectorXd rd = SparseMatrix(D->transpose()) * r;
  for (int k = 0; k < nf_; ++k)
    if (rd[free_[k]] != 0.0) out.emplace_back(k, rd[free_[k]]);
  return out;
}

SparseMatrix PathSystem::jacobian(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u) const {
  const Eval e = state_of(start, s, u);
  return jacobian_from(start, s, u, e, evaluate(e, TangentWanted::Yes).tangent);
}

SparseMatrix PathSystem::jacobian_from(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u, const Eval& e,
                                       const SparseMatrix& tangent) const {
  const Eigen::VectorXd dg = delta_gens(u);
  const SparseMatrix D = ns_.retraction_jacobian(dg);
  // D = I at Delta = 0 (a converged state's own tangent): no product (a spherical joint's block
  // A^-1 I A is I only to round-off: it is multiplied out).
  const bool at_start = dg.isZero(0.0) && std::none_of(ns_.gens().begin(), ns_.gens().end(), [](const auto& g) {
                          return g.kind == NonlinearStructure::GenKind::JointSpherical;
                        });
  SparseMatrix KDp;
  if (!at_start) KDp = tangent * D;
  const SparseMatrix& KD = at_start ? tangent : KDp;
  const auto tw = ns_.twists(e.st);
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(KD.nonZeros() + 16 * (nc_ + 1));
  for (int j = 0; j < KD.outerSize(); ++j) {
    if (gen_to_free_[j] < 0) continue;
    for (SparseMatrix::InnerIterator it(KD, j); it; ++it)
      if (gen_to_free_[it.row()] >= 0) t.emplace_back(gen_to_free_[it.row()], gen_to_free_[j], it.value());
  }
  for (int c = 0; c < ncs_; ++c) {
    for (const auto& [k, v] : constraint_row(e.st, tw, cons_[c], nullptr)) t.emplace_back(k, nf_ + c, -v);
    for (const auto& [k, v] : constraint_row(e.st, tw, cons_[c], &D)) t.emplace_back(nf_ + c, k, v);
  }
  if (!closure_rows_.empty()) {
    // Columns: the force rows B (the residual gains B^T mu); rows: the exact gradient of c times D.
    const SparseRowMatrix B = ns_.closure_force_rows(e.st, tw);
    const SparseRowMatrix CD = SparseRowMatrix(ns_.closure_jacobian(e.st, tw) * D);
    for (std::size_t i = 0; i < closure_rows_.size(); ++i) {
      const int r = closure_rows_[i], x = nf_ + ncs_ + static_cast<int>(i);
      for (SparseRowMatrix::InnerIterator it(B, r); it; ++it)
        if (gen_to_free_[it.col()] >= 0) t.emplace_back(gen_to_free_[it.col()], x, it.value());
      for (SparseRowMatrix::InnerIterator it(CD, r); it; ++it)
        if (gen_to_free_[it.col()] >= 0) t.emplace_back(x, gen_to_free_[it.col()], it.value());
    }
  }
  const int x = nf_ + nc_;
  if (s.kind != StepKind::Load) {
    if (extra_is_lambda(s)) {
      const Eigen::VectorXd p = ns_.reduce(e.st, tw, load_at(e.st));
      for (int k = 0; k < nf_; ++k)
        if (p[free_[k]] != 0.0) t.emplace_back(k, x, -p[free_[k]]);
    } else {
      for (const auto& [k, v] : constraint_row(e.st, tw, ctrl_, nullptr)) t.emplace_back(k, x, -v);
    }
    if (s.kind == StepKind::Control) {
      for (const auto& [k, v] : constraint_row(e.st, tw, ctrl_, &D)) t.emplace_back(x, k, v);
    } else {
      for (int k = 0; k < nf_; ++k) t.emplace_back(x, k, weight(free_[k]) * u[k] / s.ds);
      t.emplace_back(x, x, psi2_ * (e.lambda - start.lambda) / s.ds);
    }
    t.emplace_back(x, x, 0.0);
  }
  // Explicit zeros on the diagonal keep the pattern (and UMFPACK's symbolic analysis) constant.
  for (int k = 0; k < x; ++k) t.emplace_back(k, k, 0.0);
  SparseMatrix J(unknowns(s), unknowns(s));
  J.setFromTriplets(t.begin(), t.end());
  return J;
}

Eigen::VectorXd PathSystem::fscale(const StepSpec& s) const {
  Eigen::VectorXd f(unknowns(s));
  for (int k = 0; k < nf_; ++k) f[k] = 1.0 / (F_ref_ * (ns_.is_rotation(free_[k]) ? L_ : 1.0));
  for (int c = 0; c < ncs_; ++c) f[nf_ + c] = cons_[c].comp < 3 ? 1.0 / L_ : 1.0;
  for (std::size_t i = 0; i < closure_rows_.size(); ++i) f[nf_ + ncs_ + static_cast<int>(i)] = closure_rows_[i] % 6 < 3 ? 1.0 / L_ : 1.0;
  if (s.kind == StepKind::Control) f[nf_ + nc_] = ctrl_.comp < 3 ? 1.0 / L_ : 1.0;
  if (s.kind == StepKind::Arc) f[nf_ + nc_] = 1.0 / s.ds;
  return f;
}

Eigen::VectorXd PathSystem::load_at(const NonlinearState& st) const { return f_ext_ + ns_.dead_load_change(st); }

Eigen::VectorXd PathSystem::load_pattern(const NonlinearState& st) const {
  const Eigen::VectorXd p = ns_.reduce(st, ns_.twists(st), load_at(st));
  Eigen::VectorXd pf(nf_);
  for (int k = 0; k < nf_; ++k) pf[k] = p[free_[k]];
  return pf;
}

StepSpec PathSystem::tangent_spec(const Converged& c) const {
  StepSpec s;
  if (has_loads_) {
    s.kind = StepKind::Load;
    s.lambda = c.lambda;
  } else {
    s.kind = StepKind::Control;
    s.control = constraint_value(c.state, ctrl_);
  }
  return s;
}

Eigen::VectorXd PathSystem::direction(const Converged& a, const Converged& b) const {
  Eigen::VectorXd d(nf_ + 1);
  d.head(nf_) = increment(a, b);
  d[nf_] = b.lambda - a.lambda;
  return d;
}

Eigen::VectorXd PathSystem::increment(const Converged& a, const Converged& b) const { return increment(a.state, b.state); }

NonlinearState PathSystem::between(const NonlinearState& a, const NonlinearState& b, double f) const {
  return ns_.retract(a, delta_gens(f * increment(a, b)));
}

Eigen::VectorXd PathSystem::increment(const NonlinearState& a, const NonlinearState& b) const {
  Eigen::VectorXd du(nf_);
  const auto& gens = ns_.gens();
  for (int k = 0; k < nf_; ++k) {
    const auto& g = gens[free_[k]];
    switch (g.kind) {
      case NonlinearStructure::GenKind::NodeTranslation: du[k] = b.x[g.owner][g.comp] - a.x[g.owner][g.comp]; break;
      case NonlinearStructure::GenKind::NodeSpin:
        du[k] = log_so3(b.R[g.owner] * a.R[g.owner].transpose())[g.comp];
        break;
      case NonlinearStructure::GenKind::JointScalar:
      case NonlinearStructure::GenKind::JointSpherical: du[k] = b.q[g.owner][g.comp] - a.q[g.owner][g.comp]; break;
    }
  }
  return du;
}

Eigen::MatrixXd PathSystem::constraint_matrix(const NonlinearState& st, ControlDof control) const {
  const bool with_control = control == ControlDof::Held;
  const auto tw = ns_.twists(st);
  const int m = nc_ + (with_control ? 1 : 0);
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(m, nf_);
  for (int c = 0; c < ncs_; ++c)
    for (const auto& [k, v] : constraint_row(st, tw, cons_[c], nullptr)) C(c, k) += v;
  if (with_control)
    for (const auto& [k, v] : constraint_row(st, tw, ctrl_, nullptr)) C(nc_, k) += v;
  if (!closure_rows_.empty()) {
    const SparseRowMatrix Cl = ns_.closure_jacobian(st, tw);
    for (std::size_t i = 0; i < closure_rows_.size(); ++i)
      for (SparseRowMatrix::InnerIterator it(Cl, closure_rows_[i]); it; ++it)
        if (gen_to_free_[it.col()] >= 0) C(ncs_ + static_cast<Eigen::Index>(i), gen_to_free_[it.col()]) += it.value();
  }
  return C;
}

PathSystem::Start PathSystem::reference_start() const {
  Start out;
  const DofMap& map = ns_.reference_map();
  bool nonzero = false;
  Eigen::VectorXd d = Eigen::VectorXd::Zero(ns_.size());
  for (int i = 0; i < ns_.size(); ++i) {
    const int p = map.prescribed_index(ns_.gens()[i].raw);
    if (p >= 0 && map.prescribed()[p].value != 0.0) {
      d[i] = map.prescribed()[p].value;
      nonzero = true;
    }
  }
  out.state.state = ns_.retract(ns_.reference_state(), d);
  out.state.mu = Eigen::VectorXd::Zero(nc_);
  for (const auto& c : cons_) nonzero = nonzero || c.target != 0.0;
  out.settled = !nonzero;
  return out;
}

}  // namespace beamfea
