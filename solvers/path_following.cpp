#include "solvers/path_following.hpp"

#include <Eigen/SVD>
#include <Eigen/SparseCholesky>
#include <Eigen/UmfPackSupport>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "solvers/buckling.hpp"
#include "solvers/eigen_lowest.hpp"
#include "solvers/sparse_factor.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

void PathOptions::validate(const Model& model) const {
  const int nn = static_cast<int>(model.nodes.size());
  if (control == PathControl::Displacement && (control_node < 0 || control_node >= nn || control_dof < 0 || control_dof > 5))
    throw Error("PathOptions: displacement control needs a node and a dof");
  if (increments < 1) throw Error("PathOptions: increments must be at least 1");
  if (!(arc_length > 0.0)) throw Error("PathOptions: arc_length must be positive");
  if (max_steps < 1) throw Error("PathOptions: max_steps must be at least 1");
  if (desired_iterations < 1) throw Error("PathOptions: desired_iterations must be at least 1");
  if (!(critical_tolerance > 0.0 && critical_tolerance < 1.0)) throw Error("PathOptions: critical_tolerance must be in (0, 1)");
  if (stop_beyond && (stop_node < 0 || stop_node >= nn)) throw Error("PathOptions: stop 'beyond' needs a node");
  for (int n : track)
    if (n < 0 || n >= nn) throw Error("PathOptions: tracked node out of range");
  newton.validate();
}

Model imperfect_model(const Model& model, int mode, double amplitude) {
  BucklingOptions bo;
  bo.modes = mode;
  const BucklingResult b = solve_buckling(model, bo);
  if (b.status != BucklingStatus::Ok || static_cast<int>(b.modes.size()) < mode)
    throw ModelError("", fmt::format("imperfection: buckling mode {} is not available ({})", mode, b.message));
  Model m = model;
  for (std::size_t n = 0; n < m.nodes.size(); ++n) m.nodes[n].x += amplitude * b.modes[mode - 1].segment<3>(6 * n);
  return m;
}

namespace {

struct ConstraintDef {
  int node = -1, comp = 0;
  double target = 0.0;
};

enum class StepKind { Load, Control, Arc };

// A factorisation whose symbolic analysis is kept while the sparsity pattern does not change.
template <class Solver>
class PatternFactor {
 public:
  // Returns false when the numeric factorisation fails.
  bool factorize(const SparseMatrix& A0) {
    A_ = A0;
    A_.makeCompressed();
    if (!pattern_.same_or_remember(A_)) solver_.analyzePattern(A_);
    solver_.factorize(A_);
    if (solver_.info() != Eigen::Success) {
      pattern_.forget();
      return false;
    }
    return true;
  }
  const Solver& solver() const { return solver_; }

 private:
  SparseMatrix A_;
  Solver solver_;
  PatternMemory pattern_;
};
using LdltFactor = PatternFactor<Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>>>;
using LuFactor = PatternFactor<Eigen::UmfPackLU<SparseMatrix>>;

// What one step solves for. Unknowns u = [Delta over free gens, mu over slave constraints, extra],
// extra = lambda (Control with loads, Arc) or the controlled DOF's reaction (Control without loads).
struct StepSpec {
  StepKind kind = StepKind::Load;
  double lambda = 0.0;        // Load: the load factor; otherwise the start value
  double control = 0.0;       // Control: the target of the controlled DOF
  double ds = 0.0;            // Arc
};

struct Converged {
  NonlinearState state;
  double lambda = 0.0;
  Eigen::VectorXd mu;         // slave constraint multipliers
  double extra_mu = 0.0;      // controlled DOF's reaction (imposed motion)
  long iterations = 0;
};

class Problem {
 public:
  Problem(const Model& model, const PathOptions& o) : ns(model), opt(o) {
    const DofMap& map = ns.reference_map();
    L = ns.length_scale();
    gen_to_free.assign(ns.size(), -1);
    for (int i = 0; i < ns.size(); ++i) {
      if (map.prescribed_index(ns.gens()[i].raw) >= 0) continue;
      gen_to_free[i] = static_cast<int>(free.size());
      free.push_back(i);
    }
    for (int p = 0; p < map.prescribed_size(); ++p) {
      const auto& pv = map.prescribed()[p];
      if (pv.dof.owner == DofRef::Owner::Node && map.is_slave(pv.dof.index))
        cons.push_back({pv.dof.index, pv.dof.comp, pv.value});
    }
    f_ext = external_force(model, map);
    has_loads = f_ext.cwiseAbs().maxCoeff() > 0.0;
    if (o.control == PathControl::Displacement) {
      const int raw = map.raw_node(o.control_node, o.control_dof);
      if (map.prescribed_index(raw) >= 0)
        throw ModelError(model.describe({DofRef::Owner::Node, o.control_node, o.control_dof}),
                         "is supported or prescribed: it cannot be the controlled DOF");
      ctrl = {o.control_node, o.control_dof, 0.0};
    }
    if (!has_loads && o.control != PathControl::Displacement)
      throw ModelError("", "path: the model has no loads; use displacement control to impose a motion");
    nf = static_cast<int>(free.size());
    nc = static_cast<int>(cons.size());
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
    // Forces below 1e-5 of the stiffest element's force for a displacement of L are round-off.
    F_ref = std::max(fmax, 1e-5 * kmax * L);
    if (!(F_ref > 0.0)) F_ref = 1.0;
  }

  int unknowns(const StepSpec& s) const { return nf + nc + (s.kind == StepKind::Load ? 0 : 1); }
  bool extra_is_lambda(const StepSpec& s) const { return s.kind == StepKind::Arc || (s.kind == StepKind::Control && has_loads); }
  double weight(int gen) const { return ns.is_rotation(gen) ? L * L : 1.0; }

  double cvalue(const NonlinearState& st, const ConstraintDef& c) const {
    if (c.comp < 3) return st.x[c.node][c.comp] - ns.model().nodes[c.node].x[c.comp];
    return log_so3(st.R[c.node])[c.comp - 3];
  }

  Eigen::VectorXd delta_gens(const Eigen::VectorXd& u) const {
    Eigen::VectorXd d = Eigen::VectorXd::Zero(ns.size());
    for (int k = 0; k < nf; ++k) d[free[k]] = u[k];
    return d;
  }

  // Unknowns at the start of a step.
  Eigen::VectorXd start_unknowns(const Converged& c, const StepSpec& s) const {
    Eigen::VectorXd u = Eigen::VectorXd::Zero(unknowns(s));
    u.segment(nf, nc) = c.mu;
    if (s.kind != StepKind::Load) u[nf + nc] = extra_is_lambda(s) ? c.lambda : c.extra_mu;
    return u;
  }

  struct Eval {
    NonlinearState st;
    double lambda;
    Eigen::VectorXd f_app;
  };
  Eval state_of(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u) const {
    Eval e;
    e.st = ns.retract(start.state, delta_gens(u));
    e.lambda = s.kind == StepKind::Load ? s.lambda : (extra_is_lambda(s) ? u[nf + nc] : 0.0);
    e.f_app = e.lambda * f_ext;
    const DofMap& map = ns.reference_map();
    for (int c = 0; c < nc; ++c) e.f_app[map.raw_node(cons[c].node, cons[c].comp)] += u[nf + c];
    if (s.kind == StepKind::Control && !has_loads) e.f_app[map.raw_node(ctrl.node, ctrl.comp)] += u[nf + nc];
    return e;
  }

  double arc_equation(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u, double lambda) const {
    double a = 0.0;
    for (int k = 0; k < nf; ++k) a += weight(free[k]) * u[k] * u[k];
    const double dl = lambda - start.lambda;
    return (a + psi2 * dl * dl - s.ds * s.ds) / (2.0 * s.ds);
  }

  void residual(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u, Eigen::VectorXd& F) const {
    const Eval e = state_of(start, s, u);
    const auto ev = ns.evaluate(e.st, e.f_app, false);
    F.resize(unknowns(s));
    for (int k = 0; k < nf; ++k) F[k] = ev.residual[free[k]];
    for (int c = 0; c < nc; ++c) F[nf + c] = cvalue(e.st, cons[c]) - cons[c].target;
    if (s.kind == StepKind::Control) F[nf + nc] = cvalue(e.st, ctrl) - s.control;
    if (s.kind == StepKind::Arc) F[nf + nc] = arc_equation(start, s, u, e.lambda);
  }

  // Sparse row of a constraint over free gens at a state (D applied when given).
  std::vector<std::pair<int, double>> crow(const NonlinearState& st, const std::vector<Twist>& tw, const ConstraintDef& c,
                                           const SparseMatrix* D) const {
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

  void jacobian(const Converged& start, const StepSpec& s, const Eigen::VectorXd& u, SparseMatrix& J) const {
    const Eval e = state_of(start, s, u);
    const auto ev = ns.evaluate(e.st, e.f_app, true);
    const Eigen::VectorXd dg = delta_gens(u);
    const SparseMatrix D = ns.retraction_jacobian(dg);
    const SparseMatrix KD = ev.tangent * D;
    const auto tw = ns.twists(e.st);
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(KD.nonZeros() + 16 * (nc + 1));
    for (int j = 0; j < KD.outerSize(); ++j) {
      if (gen_to_free[j] < 0) continue;
      for (SparseMatrix::InnerIterator it(KD, j); it; ++it)
        if (gen_to_free[it.row()] >= 0) t.emplace_back(gen_to_free[it.row()], gen_to_free[j], it.value());
    }
    for (int c = 0; c < nc; ++c) {
      for (const auto& [k, v] : crow(e.st, tw, cons[c], nullptr)) t.emplace_back(k, nf + c, -v);
      for (const auto& [k, v] : crow(e.st, tw, cons[c], &D)) t.emplace_back(nf + c, k, v);
    }
    const int x = nf + nc;
    if (s.kind != StepKind::Load) {
      if (extra_is_lambda(s)) {
        const Eigen::VectorXd p = ns.reduce(e.st, tw, f_ext);
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
    for (int k = 0; k < x; ++k) t.emplace_back(k, k, 0.0);
    J.resize(unknowns(s), unknowns(s));
    J.setFromTriplets(t.begin(), t.end());
  }

  Eigen::VectorXd fscale(const StepSpec& s) const {
    Eigen::VectorXd f(unknowns(s));
    for (int k = 0; k < nf; ++k) f[k] = 1.0 / (F_ref * (ns.is_rotation(free[k]) ? L : 1.0));
    for (int c = 0; c < nc; ++c) f[nf + c] = cons[c].comp < 3 ? 1.0 / L : 1.0;
    if (s.kind == StepKind::Control) f[nf + nc] = ctrl.comp < 3 ? 1.0 / L : 1.0;
    if (s.kind == StepKind::Arc) f[nf + nc] = 1.0 / s.ds;
    return f;
  }

  // Solves one step from `start` with initial guess u (predictor). Returns false on failure.
  bool solve(KinsolSolver& kin, const Converged& start, const StepSpec& s, Eigen::VectorXd u, Converged& out,
             std::string& report) const {
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
    if (sum.status != KinsolStatus::Converged) return false;
    const Eval e = state_of(start, s, u);
    out.state = e.st;
    out.lambda = e.lambda;
    out.mu = u.segment(nf, nc);
    out.extra_mu = (s.kind == StepKind::Control && !has_loads) ? u[nf + nc] : 0.0;
    out.iterations = sum.iterations;
    return true;
  }

  // Tangent direction at a converged state: [dDelta (nf), dmu (nc), dextra] per unit lambda (loads)
  // or per unit control (imposed motion). Empty when the tangent is singular.
  Eigen::VectorXd tangent(const Converged& c) const {
    StepSpec s;
    Eigen::VectorXd rhs;
    if (has_loads) {
      s.kind = StepKind::Load;
      s.lambda = c.lambda;
    } else {
      s.kind = StepKind::Control;
      s.control = cvalue(c.state, ctrl);
    }
    const Eigen::VectorXd u0 = start_unknowns(c, s);
    SparseMatrix J;
    jacobian(c, s, u0, J);
    rhs = Eigen::VectorXd::Zero(J.rows());
    if (has_loads) {
      const Eigen::VectorXd p = ns.reduce(c.state, ns.twists(c.state), f_ext);
      for (int k = 0; k < nf; ++k) rhs[k] = p[free[k]];
    } else {
      rhs[nf + nc] = 1.0;
    }
    if (!predictor_lu.factorize(J)) return {};
    Eigen::VectorXd t = predictor_lu.solver().solve(rhs);
    if (!t.allFinite()) return {};
    return t;
  }

  // Constraint rows (nc [+ control]) over the free gens at a state, dense.
  Eigen::MatrixXd constraint_matrix(const NonlinearState& st, bool with_control) const {
    const auto tw = ns.twists(st);
    const int m = nc + (with_control ? 1 : 0);
    Eigen::MatrixXd C = Eigen::MatrixXd::Zero(m, nf);
    for (int c = 0; c < m; ++c)
      for (const auto& [k, v] : crow(st, tw, c < nc ? cons[c] : ctrl, nullptr)) C(c, k) += v;
    return C;
  }

  // Null-space basis Z (nf x (nf - rank)) of C by Gauss-Jordan elimination with full pivoting.
  static SparseMatrix null_space(const Eigen::MatrixXd& C0, int n) {
    std::vector<Eigen::Triplet<double>> t;
    if (C0.rows() == 0) {
      SparseMatrix Z(n, n);
      Z.setIdentity();
      return Z;
    }
    Eigen::MatrixXd C = C0;
    std::vector<int> pivot_col;
    std::vector<char> is_pivot(n, 0);
    const double scale = C.cwiseAbs().maxCoeff();
    int r = 0;
    for (; r < C.rows(); ++r) {
      Eigen::Index pr, pc;
      const double best = C.bottomRows(C.rows() - r).cwiseAbs().maxCoeff(&pr, &pc);
      if (!(best > 1e-12 * scale)) break;
      pr += r;
      C.row(r).swap(C.row(pr));
      C.row(r) /= C(r, pc);
      for (Eigen::Index i = 0; i < C.rows(); ++i)
        if (i != r && C(i, pc) != 0.0) C.row(i) -= C(i, pc) * C.row(r);
      pivot_col.push_back(static_cast<int>(pc));
      is_pivot[pc] = 1;
    }
    int col = 0;
    for (int j = 0; j < n; ++j) {
      if (is_pivot[j]) continue;
      t.emplace_back(j, col, 1.0);
      for (int i = 0; i < r; ++i)
        if (C(i, j) != 0.0) t.emplace_back(pivot_col[i], col, -C(i, j));
      ++col;
    }
    SparseMatrix Z(n, col);
    Z.setFromTriplets(t.begin(), t.end());
    return Z;
  }

  struct Stab {
    StabilityInfo info;
    SparseMatrix Z;
    SparseMatrix K;        // Z^T K_ff Z (not symmetrised)
    Eigen::VectorXd p;     // Z^T p_free
  };

  Stab stability(const Converged& c, bool displacement_control, bool want_mode) const {
    Stab out;
    StepSpec s;
    s.kind = StepKind::Load;
    s.lambda = c.lambda;
    const Eval e = state_of(c, s, start_unknowns(c, s));
    Eigen::VectorXd f_app = e.f_app;
    if (ctrl.node >= 0 && !has_loads) f_app[ns.reference_map().raw_node(ctrl.node, ctrl.comp)] += c.extra_mu;
    const auto ev = ns.evaluate(c.state, f_app, true);
    std::vector<Eigen::Triplet<double>> t;
    for (int j = 0; j < ev.tangent.outerSize(); ++j) {
      if (gen_to_free[j] < 0) continue;
      for (SparseMatrix::InnerIterator it(ev.tangent, j); it; ++it)
        if (gen_to_free[it.row()] >= 0) t.emplace_back(gen_to_free[it.row()], gen_to_free[j], it.value());
    }
    SparseMatrix Kff(nf, nf);
    Kff.setFromTriplets(t.begin(), t.end());
    out.Z = null_space(constraint_matrix(c.state, displacement_control), nf);
    out.K = SparseMatrix(out.Z.transpose() * Kff * out.Z);
    const Eigen::VectorXd p = ns.reduce(c.state, ns.twists(c.state), f_ext);
    Eigen::VectorXd pf(nf);
    for (int k = 0; k < nf; ++k) pf[k] = p[free[k]];
    out.p = out.Z.transpose() * pf;
    SparseMatrix S = SparseMatrix(0.5 * (out.K + SparseMatrix(out.K.transpose())));
    const int n = static_cast<int>(S.rows());
    if (n == 0) return out;
    // Inertia by LDL^T (Sylvester): the number of negative pivots.
    if (inertia_ldlt.factorize(S)) {
      out.info.negative = static_cast<int>((inertia_ldlt.solver().vectorD().array() < 0.0).count());
    } else {
      out.info.negative = -1;
    }
    // Lowest eigenvalue of the Jacobi-scaled matrix.
    Eigen::VectorXd sc(n);
    for (int i = 0; i < n; ++i) {
      const double d = std::abs(S.coeff(i, i));
      sc[i] = d > 0.0 ? 1.0 / std::sqrt(d) : 1.0;
    }
    const SparseMatrix A = SparseMatrix(sc.asDiagonal() * S * sc.asDiagonal());
    double shift = -1e-6;  // just below a positive definite spectrum: fast shift-invert convergence
    if (out.info.negative != 0) {
      double g = 0.0;
      for (int j = 0; j < A.outerSize(); ++j) {
        double diag = 0.0, off = 0.0;
        for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
          if (it.row() == j) diag += it.value();
          else off += std::abs(it.value());
        }
        g = std::min(g, diag - off);
      }
      shift = g - 1e-6;
    }
    const int want = want_mode ? std::max(1, out.info.negative) + 1 : 1;
    try {
      const EigenPairs ep = lowest_eigenpairs(A, std::min(want, n), shift);
      if (ep.values.size() > 0) {
        out.info.min_eigenvalue = ep.values[0];
        if (want_mode) {
          Eigen::Index best = 0;
          ep.values.cwiseAbs().minCoeff(&best);
          out.info.mode = out.Z * Eigen::VectorXd(sc.cwiseProduct(ep.vectors.col(best)));
        }
      }
    } catch (const Error&) {
      out.info.min_eigenvalue = NAN;
    }
    return out;
  }

  // Loaded Cartesian stiffness of a node: condensation of the constrained tangent.
  std::optional<Mat6> node_stiffness(const Converged& c, const Stab& st, int node) const {
    const auto tw = ns.twists(c.state);
    const int n = static_cast<int>(st.K.rows());
    if (n == 0) return std::nullopt;
    std::vector<Eigen::Triplet<double>> t;
    for (int j = 0; j < st.K.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(st.K, j); it; ++it) t.emplace_back(static_cast<int>(it.row()), j, it.value());
    bool moves = false;
    for (int k = 0; k < 6; ++k) {
      Eigen::VectorXd r = Eigen::VectorXd::Zero(nf);
      for (const auto& [g, v] : ns.raw_row(c.state, tw, node, k))
        if (gen_to_free[g] >= 0) r[gen_to_free[g]] += v;
      const Eigen::VectorXd rz = st.Z.transpose() * r;
      if (rz.size() > 0 && rz.cwiseAbs().maxCoeff() > 0.0) moves = true;
      for (int i = 0; i < n; ++i)
        if (rz[i] != 0.0) {
          t.emplace_back(n + k, i, rz[i]);
          t.emplace_back(i, n + k, rz[i]);
        }
    }
    if (!moves) return std::nullopt;  // the node is held
    SparseMatrix A(n + 6, n + 6);
    A.setFromTriplets(t.begin(), t.end());
    Eigen::UmfPackLU<SparseMatrix> lu;
    lu.compute(A);
    if (lu.info() == Eigen::Success) {
      Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n + 6, 6);
      B.bottomRows(6).setIdentity();
      const Eigen::MatrixXd X = lu.solve(B);
      if (X.allFinite()) return Mat6(-X.bottomRows(6));
    }
    // Fewer than six independent motions reach the node (a chain with fewer joints): the
    // stiffness is the pseudo-inverse of the compliance T_n K^-1 T_n^T, of rank below six.
    Eigen::UmfPackLU<SparseMatrix> lk;
    lk.compute(st.K);
    if (lk.info() != Eigen::Success) return std::nullopt;
    Eigen::MatrixXd Tn(n, 6);
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < 6; ++k) Tn(j, k) = A.coeff(n + k, j);
    const Eigen::MatrixXd Y = lk.solve(Tn);
    if (!Y.allFinite()) return std::nullopt;
    const Mat6 C = Tn.transpose() * Y;
    Eigen::JacobiSVD<Mat6> svd(C, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const double smax = svd.singularValues()[0];
    Vec6 inv = Vec6::Zero();
    for (int k = 0; k < 6; ++k)
      if (svd.singularValues()[k] > 1e-10 * smax) inv[k] = 1.0 / svd.singularValues()[k];
    return Mat6(svd.matrixV() * inv.asDiagonal() * svd.matrixU().transpose());
  }

  NonlinearStructure ns;
  const PathOptions& opt;
  mutable LuFactor predictor_lu;      // tangent predictor: symbolic analysis kept along the path
  mutable LdltFactor inertia_ldlt;    // inertia count: symbolic analysis kept along the path
  double L = 1.0, F_ref = 1.0, psi2 = 0.0;
  std::vector<int> free, gen_to_free;
  std::vector<ConstraintDef> cons;
  ConstraintDef ctrl;
  Eigen::VectorXd f_ext;
  bool has_loads = false;
  int nf = 0, nc = 0;
};

}  // namespace

PathResult follow_path(const Model& original, const PathOptions& o) {
  o.validate(original);
  PathResult res;
  const Model model = o.imperfection_mode > 0 ? imperfect_model(original, o.imperfection_mode, o.imperfection_amplitude)
                                              : original;
  Problem P(model, o);
  res.free_dofs = P.nf;
  KinsolSolver kin(o.newton);
  auto say = [&](const std::string& s) {
    if (o.progress) o.progress(s);
  };
  const bool disp = o.control == PathControl::Displacement;

  // Start: the reference state with prescribed independent values imposed.
  Converged cur;
  cur.state = P.ns.reference_state();
  {
    const DofMap& map = P.ns.reference_map();
    bool nonzero = false;
    Eigen::VectorXd d = Eigen::VectorXd::Zero(P.ns.size());
    for (int i = 0; i < P.ns.size(); ++i) {
      const int p = map.prescribed_index(P.ns.gens()[i].raw);
      if (p >= 0 && map.prescribed()[p].value != 0.0) {
        d[i] = map.prescribed()[p].value;
        nonzero = true;
      }
    }
    cur.state = P.ns.retract(cur.state, d);
    cur.mu = Eigen::VectorXd::Zero(P.nc);
    for (const auto& c : P.cons) nonzero = nonzero || c.target != 0.0;
    if (nonzero) {
      StepSpec s;
      s.kind = StepKind::Load;
      std::string rep;
      Converged c0;
      if (!P.solve(kin, cur, s, P.start_unknowns(cur, s), c0, rep)) {
        res.termination = "the initial state with the prescribed values did not converge: " + rep;
        return res;
      }
      cur = c0;
    }
  }

  auto record = [&](const Converged& c, int step, double control, double ds, int& negative_out) {
    PathStep ps;
    ps.step = step;
    ps.load_factor = c.lambda;
    ps.control = control;
    ps.arc_length = ds;
    ps.iterations = c.iterations;
    ps.reaction = c.extra_mu;
    for (int n : o.track) {
      Vec6 d;
      d << c.state.x[n] - original.nodes[n].x, log_so3(c.state.R[n]);
      ps.track.push_back(d);
    }
    if (o.stability) {
      const auto st = P.stability(c, disp, false);
      ps.negative_eigenvalues = st.info.negative;
      ps.stable = st.info.negative == 0;
      ps.min_eigenvalue = st.info.min_eigenvalue;
      // The loaded stiffness of the node with the controlled DOF released (it is the probe).
      if (o.stiffness_node >= 0)
        ps.stiffness = P.node_stiffness(c, disp ? P.stability(c, false, false) : st, o.stiffness_node);
    }
    negative_out = ps.negative_eigenvalues;
    ps.state = c.state;
    ps.end_forces = P.ns.evaluate(c.state, Eigen::VectorXd::Zero(P.ns.reference_map().raw_size()), false).end_forces;
    res.steps.push_back(std::move(ps));
  };

  double path_s = 0.0;
  auto control_of = [&](const Converged& c) {
    switch (o.control) {
      case PathControl::LoadFactor: return c.lambda;
      case PathControl::Displacement: return P.cvalue(c.state, P.ctrl);
      case PathControl::ArcLength: return path_s;
    }
    return 0.0;
  };
  int neg = 0;
  record(cur, 0, control_of(cur), 0.0, neg);

  // Step size: load factor, control value or arc length.
  double h = 0.0;
  const double start_control = control_of(cur);
  if (o.control == PathControl::LoadFactor) h = (o.target - cur.lambda) / o.increments;
  if (disp) h = (o.target - start_control) / o.increments;
  if (o.control == PathControl::ArcLength) h = o.arc_length;
  const double h0 = std::abs(h);
  const double hmin = o.control == PathControl::ArcLength ? (o.min_arc_length > 0 ? o.min_arc_length : h0 * 1e-4) : h0 * 1e-4;
  const double hmax = o.control == PathControl::ArcLength ? (o.max_arc_length > 0 ? o.max_arc_length : h0 * 10) : h0 * 4;

  // Arc-length scaling psi^2 from the initial tangent.
  Eigen::VectorXd prev_dir;  // [Delta_f, dlambda] of the previous step
  if (o.control == PathControl::ArcLength) {
    const Eigen::VectorXd t = P.tangent(cur);
    double tw = 0.0;
    if (t.size())
      for (int k = 0; k < P.nf; ++k) tw += P.weight(P.free[k]) * t[k] * t[k];
    // A unit load-factor increment weighs like a displacement of one model length, or like the
    // initial tangent displacement where that is larger (stiff primary paths, e.g. a column).
    P.psi2 = std::max(tw, P.L * P.L);
  }

  // Builds the spec and predictor of a step of size hh from c (direction sign for arc length).
  auto make_step = [&](const Converged& c, double hh, StepSpec& s, Eigen::VectorXd& u, const Eigen::VectorXd* dir) {
    const Eigen::VectorXd t = P.tangent(c);
    if (o.control == PathControl::LoadFactor) {
      s.kind = StepKind::Load;
      s.lambda = c.lambda + hh;
      u = P.start_unknowns(c, s);
      if (t.size()) u.head(P.nf + P.nc) += hh * t.head(P.nf + P.nc);
      return;
    }
    if (disp) {
      s.kind = StepKind::Control;
      s.control = P.cvalue(c.state, P.ctrl) + hh;
      u = P.start_unknowns(c, s);
      if (!t.size()) return;
      if (P.has_loads) {
        // Change of the controlled DOF per unit load factor.
        const auto tw = P.ns.twists(c.state);
        double rate = 0.0;
        for (const auto& [k, v] : P.crow(c.state, tw, P.ctrl, nullptr)) rate += v * t[k];
        if (std::abs(rate) < 1e-300) return;
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
      double dot = 0.0;
      if (prev_dir.size())
        for (int k = 0; k <= P.nf; ++k) dot += (k < P.nf ? P.weight(P.free[k]) : P.psi2) * d[k] * prev_dir[k];
      if (dot < 0.0) d = -d;
    } else if (prev_dir.size()) {
      d = prev_dir;  // secant predictor where the tangent is singular
    } else {
      d = Eigen::VectorXd::Zero(P.nf + 1);
      d[P.nf] = 1.0;
    }
    double nrm = P.psi2 * d[P.nf] * d[P.nf];
    for (int k = 0; k < P.nf; ++k) nrm += P.weight(P.free[k]) * d[k] * d[k];
    const double a = hh / std::sqrt(std::max(nrm, 1e-300));
    u.head(P.nf) += a * d.head(P.nf);
    u[P.nf + P.nc] += a * d[P.nf];
    if (t.size() && !dir) u.segment(P.nf, P.nc) += a * d[P.nf] * t.segment(P.nf, P.nc);
  };

  auto direction_of = [&](const Converged& a, const Converged& b, const Eigen::VectorXd& u) {
    Eigen::VectorXd d(P.nf + 1);
    d.head(P.nf) = u.head(P.nf);
    d[P.nf] = b.lambda - a.lambda;
    return d;
  };

  int step = 0;
  // The stop conditions after a converged step; sets the termination.
  auto stopped = [&](const Converged& nx) {
    if (o.stop_load_factor) {
      const double v = *o.stop_load_factor;
      if ((v >= 0 && nx.lambda >= v) || (v < 0 && nx.lambda <= v)) {
        res.termination = fmt::format("stop: load factor {:.6g} reached", v);
        res.completed = true;
        return true;
      }
    }
    if (o.stop_beyond) {
      const double v = o.stop_dof < 3 ? nx.state.x[o.stop_node][o.stop_dof] - original.nodes[o.stop_node].x[o.stop_dof]
                                      : log_so3(nx.state.R[o.stop_node])[o.stop_dof - 3];
      const double b = *o.stop_beyond;
      if ((b >= 0 && v >= b) || (b < 0 && v <= b)) {
        res.termination = fmt::format("stop: node '{}' {} beyond {:.6g}", original.nodes[o.stop_node].id,
                                      kDofNames[o.stop_dof], b);
        res.completed = true;
        return true;
      }
    }
    if (o.stop_steps && step >= *o.stop_steps) {
      res.termination = fmt::format("stop: {} steps", *o.stop_steps);
      res.completed = true;
      return true;
    }
    return false;
  };

  bool switched = false;
  int cuts = 0;
  const double lf_tol = 1e-12 * std::max(1.0, std::abs(o.target));
  while (true) {
    if (step >= o.max_steps) {
      res.termination = fmt::format("max_steps ({}) reached", o.max_steps);
      res.completed = true;
      break;
    }
    if (o.control != PathControl::ArcLength) {
      const double remaining = o.target - control_of(cur);
      if (std::abs(remaining) <= lf_tol + 1e-12 * std::abs(h0)) {
        res.termination = "control target reached";
        res.completed = true;
        break;
      }
      if (std::abs(h) > std::abs(remaining) || (remaining * h < 0)) h = remaining;
    }
    StepSpec spec;
    Eigen::VectorXd u;
    make_step(cur, h, spec, u, nullptr);
    Converged next;
    std::string rep;
    if (!P.solve(kin, cur, spec, u, next, rep)) {
      ++cuts;
      h *= 0.5;
      say(fmt::format("step {}: no convergence ({}); cutting the step to {:.4g}", step + 1, rep, h));
      if (cuts > o.max_cuts || std::abs(h) < hmin) {
        res.termination = fmt::format("no convergence after {} step cuts at load factor {:.6g}: {}", cuts, cur.lambda, rep);
        break;
      }
      continue;
    }
    // The unknowns of the converged point, for the direction.
    Eigen::VectorXd du(P.nf);
    {
      // Recover Delta from the two states through the predictor's solution: re-solve is not needed,
      // the retraction increment is what KINSOL returned; approximate it by the difference of the
      // independent coordinates (translations exact, spins by the logarithm).
      const auto& gens = P.ns.gens();
      for (int k = 0; k < P.nf; ++k) {
        const auto& g = gens[P.free[k]];
        switch (g.kind) {
          case NonlinearStructure::GenKind::NodeTranslation:
            du[k] = next.state.x[g.owner][g.comp] - cur.state.x[g.owner][g.comp];
            break;
          case NonlinearStructure::GenKind::NodeSpin:
            du[k] = log_so3(next.state.R[g.owner] * cur.state.R[g.owner].transpose())[g.comp];
            break;
          case NonlinearStructure::GenKind::JointScalar:
            du[k] = next.state.q[g.owner][g.comp] - cur.state.q[g.owner][g.comp];
            break;
          case NonlinearStructure::GenKind::JointSpherical:
            du[k] = next.state.q[g.owner][g.comp] - cur.state.q[g.owner][g.comp];
            break;
        }
      }
    }
    const Eigen::VectorXd dir = direction_of(cur, next, du);
    if (o.control == PathControl::ArcLength && prev_dir.size()) {
      // The spherical constraint has a second root behind the start: a step that went back along
      // the path is rejected and cut.
      double dot = P.psi2 * dir[P.nf] * prev_dir[P.nf];
      for (int k = 0; k < P.nf; ++k) dot += P.weight(P.free[k]) * dir[k] * prev_dir[k];
      if (dot < 0.0) {
        ++cuts;
        h *= 0.5;
        say(fmt::format("step {}: the step went back along the path; cutting it to {:.4g}", step + 1, h));
        if (cuts > o.max_cuts || std::abs(h) < hmin) {
          res.termination = fmt::format("no forward solution after {} step cuts at load factor {:.6g}", cuts, cur.lambda);
          break;
        }
        continue;
      }
    }
    ++step;
    if (o.control == PathControl::ArcLength) path_s += std::abs(h);
    const int neg_before = neg;
    record(next, step, control_of(next), std::abs(h), neg);
    say(fmt::format("step {}: load factor {:.6g}, control {:.6g}, {} iterations, {} negative eigenvalues", step,
                    next.lambda, control_of(next), next.iterations, neg));

    // Critical point between cur and next.
    if (o.stability && o.locate_critical && neg >= 0 && neg_before >= 0 && neg != neg_before) {
      CriticalPoint cp;
      cp.step = step;
      cp.negative_before = neg_before;
      cp.negative_after = neg;
      double lo = 0.0, hi = 1.0;
      Converged c_lo = cur, c_hi = next;
      for (int it = 0; it < 40 && hi - lo > o.critical_tolerance; ++it) {
        const double mid = 0.5 * (lo + hi);
        StepSpec s2;
        Eigen::VectorXd u2;
        if (o.control == PathControl::ArcLength) {
          Eigen::VectorXd d2 = dir;
          make_step(cur, mid * std::abs(h), s2, u2, &d2);
        } else {
          make_step(cur, mid * h, s2, u2, nullptr);
        }
        Converged cm;
        std::string r2;
        if (!P.solve(kin, cur, s2, u2, cm, r2)) break;
        const auto st = P.stability(cm, disp, false);
        if (st.info.negative == neg_before) {
          lo = mid;
          c_lo = cm;
        } else {
          hi = mid;
          c_hi = cm;
        }
      }
      const auto st = P.stability(c_hi, disp, true);
      cp.load_factor = 0.5 * (c_lo.lambda + c_hi.lambda);
      cp.control = o.control == PathControl::ArcLength ? path_s - (1.0 - 0.5 * (lo + hi)) * std::abs(h)
                                                       : 0.5 * (control_of(c_lo) + control_of(c_hi));
      if (st.info.mode.size()) {
        const double pn = st.p.norm(), mn = st.Z.cols() ? (st.Z.transpose() * st.info.mode).norm() : 0.0;
        // Work of the mode on the load pattern, over the free coordinates.
        Eigen::VectorXd pf(P.nf);
        {
          const Eigen::VectorXd p = P.ns.reduce(c_hi.state, P.ns.twists(c_hi.state), P.f_ext);
          for (int k = 0; k < P.nf; ++k) pf[k] = p[P.free[k]];
        }
        (void)pn;
        (void)mn;
        const double w = std::abs(pf.dot(st.info.mode)) / std::max(1e-300, pf.norm() * st.info.mode.norm());
        cp.load_work = pf.norm() > 0.0 ? w : 0.0;
        // Mode over raw node DOFs.
        Eigen::VectorXd raw = Eigen::VectorXd::Zero(P.ns.reference_map().raw_size());
        const auto tw = P.ns.twists(c_hi.state);
        for (int n = 0; n < static_cast<int>(model.nodes.size()); ++n)
          for (int k = 0; k < 6; ++k)
            for (const auto& [g, v] : P.ns.raw_row(c_hi.state, tw, n, k))
              if (P.gen_to_free[g] >= 0) raw[6 * n + k] += v * st.info.mode[P.gen_to_free[g]];
        cp.mode = normalise_mode(model, raw);
      }
      const bool limit = P.has_loads && !disp && cp.load_work > 1e-3;
      cp.type = limit ? "limit_point" : "bifurcation";
      say(fmt::format("critical point ({}) at load factor {:.6g}, step {}", cp.type, cp.load_factor, step));

      if (!limit && o.branch_switch && !switched && o.control == PathControl::ArcLength && st.info.mode.size()) {
        // Inject the critical mode from the last stable state before the bifurcation.
        Eigen::VectorXd d(P.nf + 1);
        d.head(P.nf) = st.info.mode;
        d[P.nf] = 0.0;
        StepSpec s3;
        Eigen::VectorXd u3;
        Converged cb;
        std::string r3;
        bool ok = false;
        for (double f : {1.0, 0.5, 0.25, 0.125}) {
          make_step(c_lo, f * std::abs(h), s3, u3, &d);
          if ((ok = P.solve(kin, c_lo, s3, u3, cb, r3))) {
            h = h < 0 ? -f * std::abs(h) : f * std::abs(h);
            break;
          }
        }
        if (ok) {
          switched = true;
          cp.branch_switched = true;
          // Replace the primary-path step by the located point and the first secondary step.
          res.steps.pop_back();
          record(c_lo, step, path_s - std::abs(h) + lo * std::abs(h), lo * std::abs(h), neg);
          ++step;
          path_s = path_s - std::abs(h) + lo * std::abs(h) + std::abs(h);
          record(cb, step, path_s, std::abs(h), neg);
          Eigen::VectorXd du3 = u3;  // not used
          (void)du3;
          // Direction for the next predictor: from c_lo to cb.
          Eigen::VectorXd db(P.nf + 1);
          db.setZero();
          db.head(P.nf) = d.head(P.nf);
          db[P.nf] = cb.lambda - c_lo.lambda;
          prev_dir = db;
          cur = cb;
          res.critical_points.push_back(cp);
          say(fmt::format("branch switched onto the secondary path at load factor {:.6g}", cb.lambda));
          if (stopped(cb)) break;
          continue;
        }
        say("branch switching failed: " + r3);
      }
      res.critical_points.push_back(cp);
    }

    prev_dir = dir;
    cur = next;
    // Adapt the step.
    const double ratio = std::sqrt(static_cast<double>(o.desired_iterations) / std::max<long>(1, next.iterations));
    double hn = std::abs(h) * std::clamp(ratio, 0.5, 2.0);
    hn = std::clamp(hn, hmin, hmax);
    h = h < 0 ? -hn : hn;
    if (cuts > 0) cuts = 0;

    if (stopped(next)) break;
  }
  res.factorizations = kin.factorizations();
  res.symbolic_analyses = kin.symbolic_analyses();
  return res;
}

}  // namespace beamfea
