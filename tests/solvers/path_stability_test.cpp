// The stability analysis of large models against the dense one of small models. Above its dense
// limit (kStabilityDenseLimit free DOFs) StabilityAnalyzer proves positive definiteness by CHOLMOD's
// LL^T, takes the lowest eigenvalue from that factor (Lanczos on the inverse, warm-started from the
// last state's eigenvector) and counts negative pivots by LDL^T only past a critical point. Lowering
// the limit to 0 runs that path on the deep arch (237 free DOFs), whose dense analysis is the
// reference: the same inertia at every state, the same lowest eigenvalue.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "path_models.hpp"
#include "solvers/path/equilibrium.hpp"
#include "solvers/path/factor_cache.hpp"
#include "solvers/path/stability.hpp"
#include "solvers/path_following.hpp"

namespace path_stability_test {

using namespace beamfea;
using namespace beamfea::test;

namespace {
// Lanczos stops at a relative residual of 1e-10 on the eigenvalues of the inverse (Spectra's
// tolerance in solvers/eigen_lowest.cpp); the dense solver is exact to round-off of the
// Jacobi-scaled matrix (entries of order 1).
constexpr double kRelative = 1e-8;
constexpr double kAbsolute = 1e-12;
constexpr double kBackward = 1e-13;
}  // namespace

TEST(PathStability, LargeModelAnalysisAgreesWithDenseThroughALimitPoint) {
  const Model m = read_model(deep_arch(80, 1.0));
  PathOptions o;
  o.control = PathControl::ArcLength;
  o.arc_length_auto = true;
  o.stop_steps = 66;  // three steps past the limit point (found at step 63, path_benchmarks_test)
  const PathResult r = follow_path(m, o);
  ASSERT_TRUE(r.completed) << r.brief_report();
  ASSERT_GT(r.free_dofs, 200);

  const PathSystem P(m, o);
  ASSERT_EQ(P.nc(), 0);  // supports on master nodes only: a state is its positions and load factor
  FactorCache factors;
  StabilityAnalyzer dense(P, factors), large(P, factors, 0);
  int stable = 0, unstable = 0;
  for (const PathStep& s : r.steps) {
    Converged c;
    c.state = s.state;
    c.lambda = s.load_factor;
    c.mu = Eigen::VectorXd::Zero(P.nc());
    const StabilityInfo a = dense.analyse(c).info;
    const StabilityInfo b = large.analyse(c).info;
    EXPECT_EQ(a.negative, s.negative_eigenvalues) << "step " << s.step;
    EXPECT_EQ(b.negative, a.negative) << "step " << s.step;
    EXPECT_NEAR(a.min_eigenvalue, s.min_eigenvalue, kAbsolute) << "step " << s.step;
    EXPECT_NEAR(b.min_eigenvalue, a.min_eigenvalue, kRelative * std::abs(a.min_eigenvalue) + kAbsolute)
        << "step " << s.step;
    (a.negative == 0 ? stable : unstable) += 1;
  }
  // Both branches of the large-model analysis ran: LL^T with Lanczos, and LDL^T past the limit.
  EXPECT_GT(stable, 50);
  EXPECT_GE(unstable, 2);
}

// Above kSymmetricTangentMinDofs free coordinates a symmetric tangent is factorised once per state by
// LL^T (FactorCache::is_cholesky), and that factor serves the tangent direction, the
// chord iterations and the stability analysis. The deep arch of 140 elements (417 free DOFs), through
// its first limit point: at every recorded state the inertia and the lowest eigenvalue equal the
// dense analysis' (no shared factor: the dense limit above the size), the tangent direction and a
// solve with the factor equal a sparse LU's of the unsymmetrised tangent, and past the limit point the
// LL^T fails and the LU takes over.
TEST(PathStability, TheTangentsLLtServesTheStepsAndTheStabilityOfALargeSymmetricModel) {
  const Model m = read_model(deep_arch(140, 1.0));
  PathOptions o;
  o.control = PathControl::ArcLength;
  o.arc_length_auto = true;
  o.stop_steps = 67;  // a few steps past the first limit point (step 63)
  const PathResult r = follow_path(m, o);
  ASSERT_GT(r.free_dofs, kSymmetricTangentMinDofs);
  ASSERT_GE(r.steps.size(), 10u) << r.brief_report();

  const PathSystem P(m, o);
  ASSERT_EQ(P.nc(), 0);
  FactorCache factors;
  StabilityAnalyzer reference(P, factors, 1 << 30);  // dense, its own matrices
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  int first_unstable = r.steps.back().step;
  for (const PathStep& s : r.steps)
    if (s.negative_eigenvalues > 0) first_unstable = std::min(first_unstable, s.step);
  int shared = 0, unstable = 0, compared = 0;
  double worst = 0.0;
  for (const PathStep& s : r.steps) {
    // Every sixth state, and those from two steps before the limit point on (the dense reference
    // costs a 417 x 417 eigen-solve).
    if (s.step % 6 != 0 && s.step + 2 < first_unstable) continue;
    Converged c;
    c.state = s.state;
    c.lambda = s.load_factor;
    c.mu = Eigen::VectorXd::Zero(P.nc());
    const StabilityInfo a = reference.analyse(c).info;
    EXPECT_EQ(s.negative_eigenvalues, a.negative) << "step " << s.step;
    EXPECT_NEAR(s.min_eigenvalue, a.min_eigenvalue, kRelative * std::abs(a.min_eigenvalue) + kAbsolute) << "step " << s.step;
    // The tangent direction and a solve balance the tangent as assembled (unsymmetrised) to
    // rounding: their normwise backward error, |K x - b| / (|K| |x| + |b|) in the max norm, within
    // kBackward (a few hundred times eps: a skew part dropped by the symmetrisation would show far
    // above it). This arch's slender members make K ill-conditioned, about 1e12: a forward
    // comparison with another solver would measure that, not the factor.
    const Eigen::VectorXd& t = factors.tangent(P, c);
    ASSERT_EQ(t.size(), P.nf()) << "step " << s.step;
    const StabilityAnalysis k = constrained_tangent(P, factors, c, ControlDof::Free);
    const double norm_K = (SparseMatrix(k.K.cwiseAbs()) * Eigen::VectorXd::Ones(P.nf())).maxCoeff();
    const auto backward = [&](const Eigen::VectorXd& x, const Eigen::VectorXd& rhs) {
      return (k.K * x - rhs).cwiseAbs().maxCoeff() / (norm_K * x.cwiseAbs().maxCoeff() + rhs.cwiseAbs().maxCoeff());
    };
    EXPECT_LE(backward(t, k.p), kBackward) << "step " << s.step;
    Eigen::VectorXd b(P.nf());
    for (int i = 0; i < P.nf(); ++i) b[i] = normal(rng);
    EXPECT_LE(backward(factors.solve(b), b), kBackward) << "step " << s.step;
    worst = std::max({worst, backward(t, k.p), backward(factors.solve(b), b)});
    // LL^T exactly where the state is stable (positive definite), the LU past the critical point.
    EXPECT_EQ(factors.is_cholesky(c), a.negative == 0) << "step " << s.step;
    shared += factors.is_cholesky(c);
    ++compared;
    unstable += a.negative > 0;
  }
  EXPECT_GE(shared, 10);
  EXPECT_GE(unstable, 1);
  std::printf("states compared %d, by LL^T %d; worst backward error %.3e\n", compared, shared, worst);
}

// A tangent that is not symmetric at the state (an applied moment's skew part, -[M]x/2 on the loaded
// node's rotations: elements/corotational_beam.hpp) keeps the LU: a cantilever of 80 elements (480
// free DOFs) bent by an end moment, at its states along the path.
TEST(PathStability, AnAppliedMomentsSkewTangentKeepsTheLu) {
  json d = straight_member(10.0, 80, 1.0, 1.0, 1e4, 1.0, 1.0, 1.0);
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  d["loads"].push_back(load("B", 0, 0, 0, 0, 0, 0.2));
  const Model m = read_model(d);
  PathOptions o;
  o.control = PathControl::LoadFactor;
  o.increments = 3;
  const PathResult r = follow_path(m, o);
  ASSERT_TRUE(r.completed) << r.brief_report();
  ASSERT_GT(r.free_dofs, kSymmetricTangentMinDofs);
  const PathSystem P(m, o);
  FactorCache factors;
  const PathStep& s = r.steps.back();
  ASSERT_GT(s.load_factor, 0.0);
  Converged c;
  c.state = s.state;
  c.lambda = s.load_factor;
  c.mu = Eigen::VectorXd::Zero(P.nc());
  ASSERT_EQ(factors.tangent(P, c).size(), P.nf());
  EXPECT_FALSE(factors.is_cholesky(c));
  EXPECT_EQ(s.negative_eigenvalues, 0);
}

}  // namespace path_stability_test
