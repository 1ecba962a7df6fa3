// A cantilever under a large uniform dead load (fixed direction, per unit length) against the
// elastica, solved here as a boundary-value problem by shooting with RK4.
//
// Elastica (inextensible, Euler-Bernoulli; e.g. Frisch-Fay, Flexible Bars, 1962, ch. 3): with
// theta(s) the slope, s in [0, 1] the arc length over L and alpha = q L^3 / EI,
//   theta'' = alpha (1 - s) cos(theta),   theta(0) = 0,   theta'(1) = 0,
//   x' = cos(theta),  z' = sin(theta);
// for small alpha the tip deflection is alpha/8 (q L^4 / 8 EI).
#include <gtest/gtest.h>

#include <array>
#include <algorithm>
#include <cmath>

#include "solvers/linear_static.hpp"
#include "solvers/path_following.hpp"
#include "support/models.hpp"

namespace dead_load_path_test {

using namespace beamfea;
using nlohmann::json;

namespace {

struct Tip {
  double x, z, theta_end_slope;
};

// Integrates from s = 0 with theta'(0) = p; returns x(1), z(1), theta'(1).
Tip shoot(double alpha, double p, int steps) {
  using S = std::array<double, 4>;  // theta, theta', x, z
  auto rhs = [&](double s, const S& y) { return S{y[1], alpha * (1 - s) * std::cos(y[0]), std::cos(y[0]), std::sin(y[0])}; };
  S y{0.0, p, 0.0, 0.0};
  const double h = 1.0 / steps;
  for (int k = 0; k < steps; ++k) {
    const double s = k * h;
    auto add = [](const S& a, const S& b, double f) { return S{a[0] + f * b[0], a[1] + f * b[1], a[2] + f * b[2], a[3] + f * b[3]}; };
    const S k1 = rhs(s, y), k2 = rhs(s + h / 2, add(y, k1, h / 2)), k3 = rhs(s + h / 2, add(y, k2, h / 2)),
            k4 = rhs(s + h, add(y, k3, h));
    for (int i = 0; i < 4; ++i) y[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  }
  return {y[2], y[3], y[1]};
}

// theta'(0) such that theta'(1) = 0 (bisection: theta'(1) grows with p).
Tip elastica(double alpha) {
  double lo = -alpha, hi = 0.0;
  for (int k = 0; k < 100; ++k) {
    const double mid = 0.5 * (lo + hi);
    (shoot(alpha, mid, 4000).theta_end_slope < 0.0 ? lo : hi) = mid;
  }
  return shoot(alpha, 0.5 * (lo + hi), 4000);
}

}  // namespace

TEST(DeadLoadPath, CantileverUnderLargeUniformDeadLoadFollowsTheElastica) {
  const double L = 1.0, E = 1e7, I = 1e-6, A = 1e-1;  // EA / (q L) ~ 1e5: inextensible
  const double alpha = 3.0, q = alpha * E * I / (L * L * L);
  const Tip want = elastica(alpha);
  // Small-load check of the shooting itself: alpha/8.
  EXPECT_NEAR(elastica(1e-4).z, -1e-4 / 8, 1e-9);
  double prev = 1.0;
  for (int n : {4, 8, 16}) {
    json doc = test::cantilever(L, E, E / 2.6, A, I, I, 2 * I, n);
    doc["loads"].push_back({{"element", "e"}, {"distributed", {0, 0, -q}}});
    const Model m = test::model_from(doc);
    PathOptions o;
    o.target = 1.0;
    o.increments = 10;
    o.stability = false;
    o.track = {m.find_node("B")};
    const PathResult r = follow_path(m, o);
    ASSERT_TRUE(r.completed) << r.brief_report();
    const Vec6 d = r.steps.back().track[0];
    const double ex = std::abs(L + d[0] - want.x), ez = std::abs(d[2] - want.z);
    const double err = std::max(ex, ez) / L;
    std::printf("elastica alpha = %.1f, %2d elements: tip (%.6f, %.6f) vs (%.6f, %.6f), error %.2e\n", alpha, n, L + d[0],
                d[2], want.x, want.z, err);
    EXPECT_LT(err, prev);
    prev = err;
  }
  EXPECT_LT(prev, 1e-4);  // O(h^2): 7.4e-4, 2.0e-4, 5.3e-5 with 4, 8, 16 elements
}

// A path step's element end forces are the co-rotated nodal forces plus the member loads'
// fixed-end forces (in the co-rotated frame, times the load factor): at a small load they equal
// linear_static's k u + fixed-end forces. Without the fixed-end forces the elements' end shears
// and moments would be off by q Le / 2 and q Le^2 / 12 (of order 1 here, relative).
TEST(DeadLoadPath, StepEndForcesIncludeTheMemberLoadsFixedEndForcesAsLinearStatic) {
  const double L = 1.0, E = 1e7, I = 1e-6, A = 1e-1;
  const double q = 1e-4 * E * I / (L * L * L), P = 0.3 * q * L;  // q L^3/EI = 1e-4: nearly linear
  json doc = test::cantilever(L, E, E / 2.6, A, I, I, 2 * I, 4);
  doc["loads"].push_back({{"element", "e"}, {"distributed", {0, 0, -q}}});
  doc["loads"].push_back({{"element", "e"}, {"point", {0, -P, 0}}, {"at", 0.3}});
  doc["loads"].push_back({{"element", "e"}, {"distributed", {0, q, 0}}, {"axes", "local"}, {"from", 0.5}, {"to", 0.9}});
  const Model m = test::model_from(doc);
  const LinearStaticResult lin = solve_linear_static(m);
  ASSERT_EQ(lin.status, SolveStatus::Succeeded);
  PathOptions o;
  o.target = 1.0;
  o.increments = 2;
  o.stability = false;
  const PathResult r = follow_path(m, o);
  ASSERT_TRUE(r.completed) << r.brief_report();
  const auto& step = r.steps.back();
  ASSERT_NEAR(step.load_factor, 1.0, 1e-12);
  double scale = 0.0;
  for (const auto& f : lin.end_forces) scale = std::max(scale, f.cwiseAbs().maxCoeff());
  ASSERT_GT(scale, 0.0);
  for (std::size_t e = 0; e < m.elements.size(); ++e)
    for (int k = 0; k < 12; ++k)
      // Geometric nonlinearity at q L^3/EI = 1e-4 changes end forces by ~q L^3/6EI = 2e-5 relative
      // (the load's axial component in the turned frame); the axial rounding of the co-rotated
      // elongation is ~1e-9 of EA/L x 1e-16 (below it).
      EXPECT_NEAR(step.end_forces[e][k], lin.end_forces[e][k], 1e-4 * scale) << "element " << e << " component " << k;
}

}  // namespace dead_load_path_test
