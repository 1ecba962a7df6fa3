#include "solvers/path/corrector.hpp"

#include <fmt/format.h>

#include <cmath>
#include <utility>

#include "core/errors.hpp"

namespace beamfea {

namespace {
// Below this |a^T du_t + b| the bordered system is singular for the chord (denormal-safe guard
// against division by zero, not a tolerance on the physics): full Newton decides.
constexpr double kTinyPivot = 1e-300;

double scaled_norm(const Eigen::VectorXd& F, const Eigen::VectorXd& fscale) {
  return F.size() ? F.cwiseProduct(fscale).cwiseAbs().maxCoeff() : 0.0;
}
}  // namespace

ChordOutcome chord_correct(const PathSystem& sys, FactorCache& factors, const Converged& start, const StepSpec& s,
                           Eigen::VectorXd u0, double tolerance) {
  ChordOutcome out;
  Eigen::VectorXd& u = out.u;  // the iterate
  u = std::move(u0);
  const int m = factors.factor_rows(start);
  if (m < 0) {
    out.why = "no factor of the start state's tangent";
    return out;
  }
  const int n = sys.unknowns(s);
  if (s.kind == StepKind::Arc && !sys.has_loads()) {
    // The start factor is of the imposed motion's system (its last row holds the controlled DOF),
    // not of the arc-length step that frees it: no chord.
    out.why = "an imposed motion's arc-length step";
    return out;
  }
  // The factor is of the step's own system (load control; imposed motion, whose tangent system holds
  // the controlled DOF), or of its leading block (the extra unknown is the load factor): bordered.
  const bool bordered = m == n - 1 && sys.extra_is_lambda(s);
  if (m != n && !bordered) {
    out.why = "the start factor does not fit the step";
    return out;
  }
  const Eigen::VectorXd& t = factors.tangent(sys, start);  // J0^-1 q0 (kept: no new factorisation)
  if (bordered && t.size() != m) {
    out.why = "no tangent at the start state";
    return out;
  }
  const int nf = sys.nf(), x = n - 1;
  // Displacement control with loads: the controlled DOF's row over the free coordinates at the start.
  Eigen::VectorXd a;
  if (bordered && s.kind == StepKind::Control) {
    a = Eigen::VectorXd::Zero(nf);
    for (const auto& [k, v] : sys.control_row(start.state)) a[k] += v;
  }
  const Eigen::VectorXd fs = sys.fscale(s);
  Eigen::VectorXd F(n), du(n);
  auto evaluate = [&]() {
    try {
      F = sys.residual(start, s, u);
    } catch (const ModelError& e) {  // e.g. a co-rotated frame that cannot be defined
      out.why = e.what();
      return false;
    }
    if (!F.allFinite()) {
      out.why = "non-finite residual";
      return false;
    }
    out.residual_norm = scaled_norm(F, fs);
    return true;
  };
  if (!evaluate()) return out;
  if (out.residual_norm <= kInitialGuessFraction * tolerance) {
    out.converged = true;
    return out;
  }
  for (int k = 1; k <= kMaxChordIterations; ++k) {
    const double before = out.residual_norm;
    if (!bordered) {
      du = -factors.solve(F);
    } else {
      // Block elimination (Crisfield 1991, vol. 1, eq. 9.12): du = dū + dlambda du_t.
      const Eigen::VectorXd dbar = -factors.solve(F.head(m));
      double a_dbar = 0.0, a_t = 0.0, b = 0.0;
      if (s.kind == StepKind::Arc) {
        a_dbar = sys.weighted_dot(u, dbar) / s.ds;
        a_t = sys.weighted_dot(u, t) / s.ds;
        b = sys.psi2() * (u[x] - start.lambda) / s.ds;
      } else {
        a_dbar = a.dot(dbar.head(nf));
        a_t = a.dot(t.head(nf));
      }
      const double pivot = a_t + b;
      if (!(std::abs(pivot) > kTinyPivot)) {
        out.why = "singular border";
        return out;
      }
      const double dl = -(F[x] + a_dbar) / pivot;
      du.head(m) = dbar + dl * t;
      du[x] = dl;
    }
    if (!du.allFinite()) {
      out.why = "non-finite chord increment";
      return out;
    }
    u += du;
    out.iterations = k;
    if (!evaluate()) return out;
    if (out.residual_norm <= tolerance) {
      out.converged = true;
      return out;
    }
    // Linear convergence at the observed rate: give up when it cannot reach the tolerance within the
    // iterations left (or the residual grew).
    const double rate = out.residual_norm / before;
    if (!(rate < 1.0) || out.residual_norm * std::pow(rate, kMaxChordIterations - k) > tolerance) {
      out.why = "slow chord convergence";
      return out;
    }
  }
  out.why = "too many chord iterations";
  return out;
}

StepSolution Corrector::solve(const Converged& start, const StepSpec& s, Eigen::VectorXd u) {
  StepSolution out;
  // The converged state of the unknowns uu (its iteration counts set by the caller).
  const auto finish = [&](const Eigen::VectorXd& uu) -> Converged& {
    const PathSystem::Eval e = sys_.state_of(start, s, uu);
    Converged& c = out.state;
    c.state = e.st;
    c.lambda = e.lambda;
    c.mu = uu.segment(sys_.nf(), sys_.nc());
    c.extra_mu = (s.kind != StepKind::Load && !sys_.has_loads()) ? uu[sys_.nf() + sys_.nc()] : 0.0;
    out.converged = true;
    return c;
  };
  long chord_its = 0;
  if (chord_ == ChordIterations::On && factors_.factor_rows(start) >= 0) {
    const ChordOutcome co = chord_correct(sys_, factors_, start, s, u, kin_.options().function_tolerance);
    chord_its = co.iterations;
    if (co.converged) {
      ++chord_steps_;
      out.report = fmt::format("chord: converged after {} iterations, |F| = {:.3e}", chord_its, co.residual_norm);
      Converged& c = finish(co.u);
      c.iterations = 0;
      c.chord_iterations = chord_its;
      c.by_chord = true;
      return out;
    }
    ++chord_fallbacks_;
  }
  KinsolSummary sum;
  try {
    sum = kin_.solve(
        u, sys_.fscale(s), [&](const Eigen::VectorXd& uu, Eigen::VectorXd& F) { F = sys_.residual(start, s, uu); },
        [&](const Eigen::VectorXd& uu, const Eigen::VectorXd&, SparseMatrix& J) { J = sys_.jacobian(start, s, uu); });
  } catch (const ModelError& e) {  // e.g. a co-rotated frame that cannot be defined: a failed step
    out.report = e.what();
    return out;
  }
  out.report = sum.report();
  if (sum.status != KinsolStatus::Succeeded) return out;
  Converged& c = finish(u);
  c.iterations = sum.iterations;
  c.chord_iterations = chord_its;
  c.by_chord = false;
  return out;
}

StepSolution initial_state(const PathSystem& sys, FactorCache& factors, KinsolSolver& kin) {
  const PathSystem::Start start = sys.reference_start();
  if (start.settled) return {true, start.state, ""};
  // No factor of the reference state is kept yet: the chord iterations would not start.
  Corrector corrector(sys, factors, kin, ChordIterations::Off);
  StepSpec s;
  s.kind = StepKind::Load;
  return corrector.solve(start.state, s, sys.start_unknowns(start.state, s));
}

}  // namespace beamfea
