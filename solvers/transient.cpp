#include "solvers/transient.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "core/errors.hpp"
#include "solvers/dynamic_system.hpp"
#include "solvers/linear_solver.hpp"
#include "solvers/member_loading.hpp"

namespace beamfea {

namespace {

// duration / dt within this fraction of a step of an integer counts as that integer (rounding of
// the user's decimal values).
constexpr double kStepRounding = 1e-9;

struct IntegratorParameters {
  double am = 0.0, af = 0.0, gamma = 0.5, beta = 0.25;
};

IntegratorParameters parameters(const TransientOptions& o) {
  switch (o.method) {
    case Integrator::Newmark: return {0.0, 0.0, o.gamma, o.beta};
    case Integrator::Hht:  // Hilber, Hughes & Taylor 1977: af = -alpha
      return {0.0, -o.alpha, 0.5 * (1.0 - 2.0 * o.alpha), 0.25 * (1.0 - o.alpha) * (1.0 - o.alpha)};
    case Integrator::GeneralizedAlpha: {  // Chung & Hulbert 1993, eqs. 25, 17, 20
      const double r = o.rho_inf;
      const double am = (2.0 * r - 1.0) / (r + 1.0), af = r / (r + 1.0);
      return {am, af, 0.5 - am + af, 0.25 * (1.0 - am + af) * (1.0 - am + af)};
    }
  }
  return {};
}

// The tracked nodes' raw rows of T_f, 6 per node: raw u = O u_free.
Eigen::SparseMatrix<double, Eigen::RowMajor> tracked_rows(const DofMap& map, const std::vector<int>& nodes) {
  Eigen::SparseMatrix<double, Eigen::RowMajor> O(6 * static_cast<Eigen::Index>(nodes.size()), map.free_size());
  for (std::size_t t = 0; t < nodes.size(); ++t)
    for (int c = 0; c < 6; ++c) O.row(6 * static_cast<Eigen::Index>(t) + c) = map.T_free().row(map.raw_node(nodes[t], c));
  return O;
}

TransientResult transient_failed(TransientStatus s, std::string message) {
  TransientResult r;
  r.status = s;
  r.message = "transient: " + std::move(message);
  return r;
}

}  // namespace

double TimeFunction::operator()(double t) const {
  switch (kind) {
    case Kind::Step: return t >= 0.0 ? 1.0 : 0.0;
    case Kind::Ramp: return t <= 0.0 ? 0.0 : t >= duration ? 1.0 : t / duration;
    case Kind::Sine: return std::sin(2.0 * std::numbers::pi * frequency * t + phase_deg * std::numbers::pi / 180.0);
    case Kind::Table: {
      if (points.empty()) return 0.0;
      if (t <= points.front()[0]) return points.front()[1];
      if (t >= points.back()[0]) return points.back()[1];
      const auto it = std::upper_bound(points.begin(), points.end(), t, [](double x, const std::array<double, 2>& p) { return x < p[0]; });
      const auto& b = *it;
      const auto& a = *(it - 1);
      return a[1] + (b[1] - a[1]) * (t - a[0]) / (b[0] - a[0]);
    }
  }
  return 0.0;
}

const char* to_string(TimeFunction::Kind k) {
  switch (k) {
    case TimeFunction::Kind::Step: return "step";
    case TimeFunction::Kind::Ramp: return "ramp";
    case TimeFunction::Kind::Sine: return "sine";
    case TimeFunction::Kind::Table: return "table";
  }
  return "?";
}

const char* to_string(Integrator m) {
  switch (m) {
    case Integrator::Newmark: return "newmark";
    case Integrator::Hht: return "hht";
    case Integrator::GeneralizedAlpha: return "generalized_alpha";
  }
  return "?";
}

const char* to_string(TransientStatus s) {
  switch (s) {
    case TransientStatus::Succeeded: return "ok";
    case TransientStatus::NoMass: return "no mass";
    case TransientStatus::Singular: return "singular";
    case TransientStatus::Diverged: return "diverged";
  }
  return "?";
}

void TransientOptions::validate() const {
  if (!(dt > 0.0) || !std::isfinite(dt)) throw Error("TransientOptions: dt must be positive");
  if (!(duration > 0.0) || !std::isfinite(duration)) throw Error("TransientOptions: duration must be positive");
  if (!(gamma > 0.0 && beta > 0.0)) throw Error("TransientOptions: gamma and beta must be positive");
  if (!(alpha >= -1.0 / 3.0 && alpha <= 0.0)) throw Error("TransientOptions: HHT alpha must be in [-1/3, 0]");
  if (!(rho_inf >= 0.0 && rho_inf <= 1.0)) throw Error("TransientOptions: rho_inf must be in [0, 1]");
  if (output_every < 1) throw Error("TransientOptions: output_every must be at least 1");
  if (step_count() > kMaxTransientSteps) throw Error("TransientOptions: too many steps");
}

long long TransientOptions::step_count() const {
  const double n = duration / dt;
  if (!(n < 1e18)) return kMaxTransientSteps + 1;
  const double near = std::round(n);
  return std::max(1LL, static_cast<long long>(std::abs(n - near) <= kStepRounding * std::max(1.0, n) ? near : std::ceil(n)));
}

TransientResult solve_transient(const Model& model, const std::vector<TransientLoad>& loads, const TransientOptions& options,
                                const ShapeSink& shapes) {
  options.validate();
  const DofMap map(model);
  DynamicSystemOptions so;
  so.mass = options.mass;
  const DynamicSystem sys = dynamic_system(model, map, model.default_loads(), so);
  if (sys.status == DynamicSystemStatus::NoMass) return transient_failed(TransientStatus::NoMass, sys.message);
  if (sys.status != DynamicSystemStatus::Succeeded) return transient_failed(TransientStatus::Singular, sys.message);
  if (model.damping.kind == Damping::Kind::Modal)
    throw Error("transient: modal damping (a ratio per mode) is not a damping matrix; use Rayleigh damping");
  const SparseMatrix &K = sys.K, &M = sys.M, &C = sys.C;
  const bool damped = sys.has_damping_matrix;
  const Eigen::Index n = K.rows();

  // The load vectors over the free DOFs, and f(t).
  std::vector<Eigen::VectorXd> f_cases;
  for (const TransientLoad& l : loads) f_cases.push_back(map.reduce(external_force(model, map, *l.loads)));
  const auto force = [&](double t, Eigen::VectorXd& f) {
    f.setZero(n);
    for (std::size_t i = 0; i < loads.size(); ++i) f += loads[i].function(t) * f_cases[i];
  };

  TransientResult r;
  const IntegratorParameters p = parameters(options);
  r.am = p.am, r.af = p.af, r.gamma = p.gamma, r.beta = p.beta;
  const double dt = options.dt;
  Eigen::VectorXd d = Eigen::VectorXd::Zero(n), v = Eigen::VectorXd::Zero(n), a(n), f0, f1;
  force(0.0, f0);
  if (options.static_initial) {
    std::unique_ptr<LinearSolver> ks = make_linear_solver();
    if (ks->compute(K) != FactorStatus::Succeeded)
      return transient_failed(TransientStatus::Singular, "the static start needs a non-singular stiffness (the structure is a mechanism)");
    d = ks->solve(f0);
  }
  for (const auto& [dof, value] : options.initial_velocity) {
    const int q = map.free_index(map.raw_index(dof));
    if (q < 0) throw Error("transient: an initial velocity on " + model.describe(dof) + ", which is not a free DOF");
    v[q] = value;
  }

  // The effective matrix, factorised once.
  SparseMatrix S = (1.0 - p.am) * M + ((1.0 - p.af) * p.beta * dt * dt) * K;
  if (damped) S += ((1.0 - p.af) * p.gamma * dt) * C;
  std::unique_ptr<LinearSolver> solver = make_linear_solver();
  if (solver->compute(S) != FactorStatus::Succeeded)
    return transient_failed(TransientStatus::Singular, "the effective matrix (1 - am) M + (1 - af) gamma dt C + (1 - af) beta dt^2 K could not be factorised");

  // a_0 from M a_0 = f(0) - C v_0 - K d_0.
  Eigen::VectorXd rhs = f0 - K * d;
  if (damped) rhs -= C * v;
  {
    std::unique_ptr<LinearSolver> ms = make_linear_solver();
    if (ms->compute(M) == FactorStatus::Succeeded) {
      a = ms->solve(rhs);
    } else {
      a = solver->solve(rhs);
      r.warnings.push_back("transient: the mass matrix is singular (DOFs without mass); the start acceleration solves the effective matrix instead of M");
    }
  }

  const auto O = tracked_rows(map, options.track);
  const long long steps = options.step_count();
  const long long outputs = 1 + steps / options.output_every + ((steps % options.output_every) != 0 ? 1 : 0);
  r.times.reserve(static_cast<std::size_t>(outputs));
  r.displacement.resize(outputs, O.rows());
  r.velocity.resize(outputs, O.rows());
  r.acceleration.resize(outputs, O.rows());
  r.energy.resize(outputs, 4);
  double work = 0.5 * v.dot(M * v) + 0.5 * d.dot(K * d), dissipated = 0.0, work_max = std::abs(work);
  Eigen::Index row = 0;
  const auto record = [&](double t) {
    r.times.push_back(t);
    r.displacement.row(row) = (O * d).transpose();
    r.velocity.row(row) = (O * v).transpose();
    r.acceleration.row(row) = (O * a).transpose();
    const double kinetic = 0.5 * v.dot(M * v), strain = 0.5 * d.dot(K * d);
    r.energy.row(row) << kinetic, strain, dissipated, work;
    work_max = std::max({work_max, std::abs(work), kinetic + strain});
    r.max_energy_error = std::max(r.max_energy_error, std::abs(kinetic + strain + dissipated - work));
    if (shapes) shapes(t, map.T_free() * d);
    ++row;
  };
  record(0.0);

  Eigen::VectorXd d_pred(n), v_pred(n), d_new(n), v_new(n), f_mid(n);
  for (long long k = 1; k <= steps; ++k) {
    const double t = static_cast<double>(k) * dt;
    force(t, f1);
    d_pred = d + dt * v + (dt * dt * (0.5 - p.beta)) * a;
    v_pred = v + (dt * (1.0 - p.gamma)) * a;
    f_mid = (1.0 - p.af) * f1 + p.af * f0;
    rhs = f_mid - K * ((1.0 - p.af) * d_pred + p.af * d);
    if (p.am != 0.0) rhs -= p.am * (M * a);
    if (damped) rhs -= C * ((1.0 - p.af) * v_pred + p.af * v);
    solver->solve(rhs, a);
    d_new = d_pred + (p.beta * dt * dt) * a;
    v_new = v_pred + (p.gamma * dt) * a;
    const Eigen::VectorXd dd = d_new - d;
    work += 0.5 * dd.dot(f0 + f1);
    if (damped) dissipated += 0.5 * dd.dot(C * (v + v_new));
    d.swap(d_new);
    v.swap(v_new);
    f0.swap(f1);
    r.steps = k;
    if (!d.allFinite() || !v.allFinite()) {
      r.status = TransientStatus::Diverged;
      r.message = fmt::format("transient: the state became non-finite at step {} (t = {:.6g})", k, t);
      r.times.resize(static_cast<std::size_t>(row));
      for (Eigen::MatrixXd* m : {&r.displacement, &r.velocity, &r.acceleration, &r.energy}) m->conservativeResize(row, m->cols());
      return r;
    }
    if (k % options.output_every == 0 || k == steps) record(t);
  }
  if (work_max > 0.0) r.max_energy_error /= work_max;
  r.status = TransientStatus::Succeeded;
  r.message = fmt::format("transient: {}, {} free DOFs, {} steps of {:.6g}, {} outputs, energy balance to {:.3g}", to_string(options.method), n,
                          steps, dt, row, r.max_energy_error);
  return r;
}

}  // namespace beamfea
