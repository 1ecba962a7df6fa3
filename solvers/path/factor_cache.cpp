#include "solvers/path/factor_cache.hpp"

#include <algorithm>
#include <cmath>

namespace beamfea {

namespace {
// Exact equality of two converged states (the key of the evaluation kept by FactorCache).
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

const NonlinearStructure::Evaluation& FactorCache::evaluation_at(const PathSystem& sys, const Converged& c) {
  if (valid_ && same_state(key_, c)) return ev_;
  valid_ = has_tangent_ = false;
  const StepSpec s = sys.tangent_spec(c);
  ev_ = sys.evaluate(sys.state_of(c, s, sys.start_unknowns(c, s)), TangentWanted::Yes);
  key_ = c;
  valid_ = true;
  return ev_;
}

const Eigen::VectorXd& FactorCache::tangent(const PathSystem& sys, const Converged& c) {
  const NonlinearStructure::Evaluation& ev = evaluation_at(sys, c);
  if (has_tangent_) return t_;
  const StepSpec s = sys.tangent_spec(c);
  const Eigen::VectorXd u0 = sys.start_unknowns(c, s);
  J_ = sys.jacobian_from(c, s, u0, sys.state_of(c, s, u0), ev.tangent);
  const int nf = sys.nf(), nc = sys.nc();
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(J_.rows());
  if (sys.has_loads()) {
    rhs.head(nf) = sys.load_pattern(c.state);
  } else {
    rhs[nf + nc] = 1.0;
  }
  t_.resize(0);
  cholesky_ = false;
  // The symmetric tangent's LL^T where it applies (see the header), else the LU.
  if (nf > kSymmetricTangentMinDofs && nc == 0 && J_.rows() == nf) {
    J_.makeCompressed();
    if (symmetric_part(J_, llt_.matrix()) && llt_.factorize()) {
      t_ = llt_.solver().solve(rhs);
      cholesky_ = t_.allFinite();
      if (!cholesky_) t_.resize(0);
    }
  }
  if (!cholesky_ && lu_.factorize(J_)) {
    t_ = lu_.solver().solve(rhs);
    if (!t_.allFinite()) t_.resize(0);
  }
  has_tangent_ = true;
  return t_;
}

int FactorCache::factor_rows(const Converged& c) const {
  if (!valid_ || !has_tangent_ || !t_.size() || !same_state(key_, c)) return -1;
  return static_cast<int>(J_.rows());
}

Eigen::VectorXd FactorCache::solve(const Eigen::VectorXd& b) {
  if (cholesky_) return llt_.solver().solve(b);
  auto& lu = lu_.solver();
  const double irstep = lu.umfpackControl()(UMFPACK_IRSTEP);
  lu.umfpackControl()(UMFPACK_IRSTEP) = 0;
  Eigen::VectorXd x = lu.solve(b);
  lu.umfpackControl()(UMFPACK_IRSTEP) = irstep;
  return x;
}

double conjugate_slope(const PathSystem& sys, FactorCache& factors, const Converged& c) {
  const Eigen::VectorXd& t = factors.tangent(sys, c);
  if (!t.size()) return NAN;
  if (!sys.has_loads()) return t[sys.nf() + sys.nc()];
  double rate = 0.0;  // du_c / dlambda
  for (const auto& [k, v] : sys.control_row(c.state)) rate += v * t[k];
  return 1.0 / rate;  // +-inf where the controlled DOF does not move with the load (its snap-back)
}

}  // namespace beamfea
