#include "solvers/path/corrector.hpp"

#include <cmath>

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

ChordOutcome chord_correct(const PathEquilibrium& P, const Converged& start, const StepSpec& s, Eigen::VectorXd& u,
                           double tolerance) {
  ChordOutcome out;
  const int m = P.tangent_factor_rows(start);
  if (m < 0) {
    out.why = "no factor of the start state's tangent";
    return out;
  }
  const int n = P.unknowns(s);
  // The factor is of the step's own system (load control; imposed motion, whose tangent system holds
  // the controlled DOF), or of its leading block (the extra unknown is the load factor): bordered.
  const bool bordered = m == n - 1 && P.extra_is_lambda(s);
  if (m != n && !bordered) {
    out.why = "the start factor does not fit the step";
    return out;
  }
  const Eigen::VectorXd& t = P.tangent(start);  // J0^-1 q0 (kept: no new factorisation)
  if (bordered && t.size() != m) {
    out.why = "no tangent at the start state";
    return out;
  }
  const int nf = P.nf, x = n - 1;
  // Displacement control with loads: the controlled DOF's row over the free coordinates at the start.
  Eigen::VectorXd a;
  if (bordered && s.kind == StepKind::Control) {
    a = Eigen::VectorXd::Zero(nf);
    for (const auto& [k, v] : P.crow(start.state, P.ns.twists(start.state), P.ctrl, nullptr)) a[k] += v;
  }
  const Eigen::VectorXd fs = P.fscale(s);
  Eigen::VectorXd F(n), du(n);
  auto evaluate = [&]() {
    try {
      P.residual(start, s, u, F);
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
      du = -P.solve_with_tangent_factor(F);
    } else {
      // Block elimination (Crisfield 1991, vol. 1, eq. 9.12): du = dū + dlambda du_t.
      const Eigen::VectorXd dbar = -P.solve_with_tangent_factor(F.head(m));
      double a_dbar = 0.0, a_t = 0.0, b = 0.0;
      if (s.kind == StepKind::Arc) {
        a_dbar = P.weighted_dot(u, dbar) / s.ds;
        a_t = P.weighted_dot(u, t) / s.ds;
        b = P.psi2 * (u[x] - start.lambda) / s.ds;
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

}  // namespace beamfea
