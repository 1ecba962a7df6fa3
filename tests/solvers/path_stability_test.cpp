// The stability analysis of large models against the dense one of small models. Above its dense
// limit (kStabilityDenseLimit free DOFs) StabilityAnalyzer proves positive definiteness by CHOLMOD's
// LL^T, takes the lowest eigenvalue from that factor (Lanczos on the inverse, warm-started from the
// last state's eigenvector) and counts negative pivots by LDL^T only past a critical point. Lowering
// the limit to 0 runs that path on the deep arch (237 free DOFs), whose dense analysis is the
// reference: the same inertia at every state, the same lowest eigenvalue.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "path_models.hpp"
#include "solvers/path/equilibrium.hpp"
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

  const PathEquilibrium P(m, o);
  ASSERT_EQ(P.nc, 0);  // supports on master nodes only: a state is its positions and load factor
  StabilityAnalyzer dense(P), large(P, 0);
  int stable = 0, unstable = 0;
  for (const PathStep& s : r.steps) {
    Converged c;
    c.state = s.state;
    c.lambda = s.load_factor;
    c.mu = Eigen::VectorXd::Zero(P.nc);
    const StabilityInfo a = dense.analyse(c, false, false).info;
    const StabilityInfo b = large.analyse(c, false, false).info;
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

}  // namespace path_stability_test
