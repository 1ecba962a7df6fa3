// Loads between the nodes of a beam element: equivalent nodal loads against the textbook tables
// of fixed-end forces, section forces by equilibrium, and the dead-load vector of a turned chord.
//
// Tables: AISC Steel Construction Manual, Table 3-23 (beam diagrams and formulas), cases 15-16
// (fixed-fixed, uniform and concentrated loads); Roark's Formulas for Stress and Strain, 7th ed.,
// Table 8.1 cases 2e (partial/linearly varying load) and 3e (concentrated moment), both ends
// fixed. The equivalent nodal loads are the negated fixed-end reactions.
#include <gtest/gtest.h>

#include <cmath>

#include "elements/span_loads.hpp"

namespace span_loads_test {

using namespace beamfea;

namespace {
constexpr double kRel = 1e-12;  // quadrature is exact: only round-off remains
constexpr double L = 2.5;

void expect_rel(double got, double want, double scale) { EXPECT_NEAR(got, want, kRel * scale) << "want " << want; }
}  // namespace

TEST(MemberLoads, UniformLoadGivesHalfTheLoadAndWL2Over12) {
  // AISC Table 3-23 case 15: R = wL/2, M = wL^2/12 at both fixed ends.
  const double w = 3.7;
  const Vec12 f = equivalent_nodal_loads(L, LocalDistributedLoad{0.0, L, Vec3(0, -w, 0), Vec3(0, -w, 0)});
  const double s = w * L * L;
  expect_rel(f[1], -w * L / 2, s);
  expect_rel(f[7], -w * L / 2, s);
  expect_rel(f[5], -w * L * L / 12, s);   // the clamp at node 1 pushes back counter-clockwise
  expect_rel(f[11], w * L * L / 12, s);
  // Same load along local z: w' = -ry flips the moments' signs.
  const Vec12 g = equivalent_nodal_loads(L, LocalDistributedLoad{0.0, L, Vec3(0, 0, -w), Vec3(0, 0, -w)});
  expect_rel(g[2], -w * L / 2, s);
  expect_rel(g[4], w * L * L / 12, s);
  expect_rel(g[10], -w * L * L / 12, s);
  // Axial: half to each node.
  const Vec12 a = equivalent_nodal_loads(L, LocalDistributedLoad{0.0, L, Vec3(w, 0, 0), Vec3(w, 0, 0)});
  expect_rel(a[0], w * L / 2, s);
  expect_rel(a[6], w * L / 2, s);
}

TEST(MemberLoads, TriangularLoadGivesThreeTwentiethsAndWL2Over30) {
  // Load rising from 0 at node 1 to w at node 2 (Roark Table 8.1 case 2e with wa = 0, a = 0):
  // R1 = 3wL/20, R2 = 7wL/20, M1 = wL^2/30, M2 = wL^2/20.
  const double w = 5.0;
  const Vec12 f = equivalent_nodal_loads(L, LocalDistributedLoad{0.0, L, Vec3::Zero(), Vec3(0, -w, 0)});
  const double s = w * L * L;
  expect_rel(f[1], -3 * w * L / 20, s);
  expect_rel(f[7], -7 * w * L / 20, s);
  expect_rel(f[5], -w * L * L / 30, s);
  expect_rel(f[11], w * L * L / 20, s);
}

TEST(MemberLoads, PartialUniformLoadEqualsTheIntegralOfThePointLoadFormulas) {
  // Uniform w on [x1, x2]: integrating the point-load reactions of AISC case 16 over the loaded
  // part gives R1 = w/L^3 [L^3 x - L x^3 + x^4/2], M1 = w/L^2 [L^2 x^2/2 - 2 L x^3/3 + x^4/4],
  // M2 = w/L^2 [L x^3/3 - x^4/4], each between x1 and x2.
  const double w = 2.0, x1 = 0.6, x2 = 1.9;
  const Vec12 f = equivalent_nodal_loads(L, LocalDistributedLoad{x1, x2, Vec3(0, -w, 0), Vec3(0, -w, 0)});
  auto R1 = [&](double x) { return (L * L * L * x - L * x * x * x + x * x * x * x / 2) / (L * L * L); };
  auto M1 = [&](double x) { return (L * L * x * x / 2 - 2 * L * x * x * x / 3 + x * x * x * x / 4) / (L * L); };
  auto M2 = [&](double x) { return (L * x * x * x / 3 - x * x * x * x / 4) / (L * L); };
  const double s = w * L * L;
  expect_rel(f[1], -w * (R1(x2) - R1(x1)), s);
  expect_rel(f[7], -w * (x2 - x1) + w * (R1(x2) - R1(x1)), s);
  expect_rel(f[5], -w * (M1(x2) - M1(x1)), s);
  expect_rel(f[11], w * (M2(x2) - M2(x1)), s);
}

TEST(MemberLoads, PointLoadInsideGivesPab2OverL2) {
  // AISC Table 3-23 case 16: R1 = P b^2 (3a + b)/L^3, M1 = P a b^2/L^2, R2 = P a^2 (a + 3b)/L^3,
  // M2 = P a^2 b/L^2.
  const double P = 10.0, a = 0.7, b = L - a;
  const Vec12 f = equivalent_nodal_loads(L, LocalPointLoad{a, Vec3(0, 0, -P), Vec3::Zero()});
  const double s = P * L;
  expect_rel(f[2], -P * b * b * (3 * a + b) / (L * L * L), s);
  expect_rel(f[8], -P * a * a * (a + 3 * b) / (L * L * L), s);
  expect_rel(f[4], P * a * b * b / (L * L), s);    // about y: w' = -ry
  expect_rel(f[10], -P * a * a * b / (L * L), s);
  // Axial and torque split by the lever rule.
  const Vec12 t = equivalent_nodal_loads(L, LocalPointLoad{a, Vec3(P, 0, 0), Vec3(P, 0, 0)});
  expect_rel(t[0], P * b / L, s);
  expect_rel(t[6], P * a / L, s);
  expect_rel(t[3], P * b / L, s);
  expect_rel(t[9], P * a / L, s);
}

TEST(MemberLoads, ConcentratedMomentInsideMatchesRoark) {
  // Roark Table 8.1 case 3e, both ends fixed, moment M0 at a: R1 = -6 M0 a b / L^3,
  // M1 = -M0 b (2a - b) / L^2 (as equivalent nodal loads: negated reactions).
  const double M0 = 4.0, a = 0.9, b = L - a;
  const Vec12 f = equivalent_nodal_loads(L, LocalPointLoad{a, Vec3::Zero(), Vec3(0, 0, M0)});
  const double s = M0;
  expect_rel(f[1], -6 * M0 * a * b / (L * L * L), s);
  expect_rel(f[7], 6 * M0 * a * b / (L * L * L), s);
  expect_rel(f[5], -M0 * b * (2 * a - b) / (L * L), s);
  expect_rel(f[11], -M0 * a * (2 * b - a) / (L * L), s);
  // Equilibrium of the element: nodal forces sum to zero, moments sum to M0.
  expect_rel(f[1] + f[7], 0.0, s);
  expect_rel(f[5] + f[11] + f[7] * L, M0, s);
}

TEST(MemberLoads, SectionForcesOfAClampedBeamUnderUniformLoadAreParabolic) {
  // Clamped-clamped, uniform w down along y: M(x) = w (6 L x - 6 x^2 - L^2) / 12 (sagging
  // positive in Mz here), Vy(x) = w (x - L/2); at the far end the section forces equal +F2.
  const double w = 1.3;
  ElementLoads loads;
  loads.distributed.push_back({0.0, L, Vec3(0, -w, 0), Vec3(0, -w, 0)});
  const Vec12 F = fixed_end_forces(L, loads);  // k u = 0: the clamped member
  for (int k = 0; k <= 10; ++k) {
    const double x = L * k / 10.0;
    const Vec6 sf = section_forces_at(x, F, loads);
    expect_rel(sf[5], w * (6 * L * x - 6 * x * x - L * L) / 12, w * L * L);
    expect_rel(sf[1], w * (x - L / 2), w * L);
  }
  const Vec6 end = section_forces_at(L, F, loads);
  for (int k = 0; k < 6; ++k) expect_rel(end[k], F[6 + k], w * L * L);
}

TEST(MemberLoads, PointLoadMakesAJumpInShearOfItsSize) {
  const double P = 7.0, a = 1.0;
  ElementLoads loads;
  loads.points.push_back({a, Vec3(0, 0, -P), Vec3::Zero()});
  const Vec12 F = fixed_end_forces(L, loads);
  const Vec6 before = section_forces_at(a, F, loads, CutSide::Before);
  const Vec6 after = section_forces_at(a, F, loads, CutSide::After);
  expect_rel(after[2] - before[2], P, P);
  expect_rel(after[4], before[4], P * L);  // moment continuous
  const Vec6 end = section_forces_at(L, F, loads);
  for (int k = 0; k < 6; ++k) expect_rel(end[k], F[6 + k], P * L);
}

TEST(MemberLoads, DeadLoadVectorEqualsTheLocalLoadsTurnedAndItsDerivativeTheFiniteDifference) {
  // A trapezoidal partial load and a point force and moment, global components, on a skew chord.
  const Vec3 x1(0.1, -0.2, 0.3), x2(1.3, 0.7, -0.4);
  const Mat3 R = beam_local_axes(x1, x2, Vec3(0.2, 1.0, 0.5));
  const double Le = (x2 - x1).norm(), a = 0.2 * Le, b = 0.8 * Le;
  const Vec3 qa(0.3, -1.0, 2.0), qb(-0.5, 0.4, -3.0), P(1.0, 2.0, -0.5), M(0.3, -0.7, 0.2);
  auto terms = dead_load_terms(Le, a, b, qa, qb);
  const auto pt = dead_load_terms(Le, 0.4 * Le, P, M);
  terms.insert(terms.end(), pt.begin(), pt.end());
  ElementLoads local;
  local.distributed.push_back({a, b, R * qa, R * qb});
  local.points.push_back({0.4 * Le, R * P, R * M});
  const Vec12 want = beam_transformation(R).transpose() * equivalent_nodal_loads(Le, local);
  const Vec12 got = dead_load_vector(terms, R.row(0).transpose());
  EXPECT_LT((got - want).cwiseAbs().maxCoeff(), 1e-12 * want.cwiseAbs().maxCoeff());

  const Vec3 d = x2 - x1;
  const auto D = dead_load_derivative(terms, d.normalized(), d.norm());
  const double h = 1e-6 * d.norm();
  for (int c = 0; c < 3; ++c) {
    Vec3 dp = d, dm = d;
    dp[c] += h;
    dm[c] -= h;
    const Vec12 fd = (dead_load_vector(terms, dp.normalized()) - dead_load_vector(terms, dm.normalized())) / (2 * h);
    EXPECT_LT((D.col(c) - fd).cwiseAbs().maxCoeff(), 1e-6 * want.cwiseAbs().maxCoeff() / d.norm()) << "column " << c;
  }
}

}  // namespace span_loads_test
