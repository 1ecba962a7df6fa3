// Member loads, self-weight, point masses, load cases and combinations in linear statics and
// buckling, against closed forms computed here.
//
// Beam formulas: Timoshenko & Gere, Mechanics of Materials, Appendix G (cantilever cases 1, 5;
// simple beam cases 1, 5); Greenhill (1881) / Timoshenko & Gere, Theory of Elastic Stability,
// 2nd ed., sec. 2.13: a clamped column under its own weight q buckles at q L^3 / EI = 7.837,
// i.e. (9/4) j^2 with j the first zero of the Bessel function J_{-1/3}.
#include <gtest/gtest.h>

#include <cmath>

#include "solvers/buckling.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/member_loading.hpp"
#include "support/models.hpp"

namespace member_loads_static_test {

using namespace beamfea;
using nlohmann::json;

namespace {
constexpr double L = 2.0, E = 2.1e11, G = 8.1e10, A = 1e-3, Iy = 2e-6, Iz = 3e-6, J = 1e-6;
// Exact nodal results (consistent loads): only round-off of the factorisation remains.
constexpr double kExact = 1e-9;

json simple_beam(int divisions) {
  json doc = test::cantilever(L, E, G, A, Iy, Iz, J, divisions);
  doc["supports"] = json::array({{{"node", "A"}, {"fix", {"ux", "uy", "uz", "rx"}}}, {{"node", "B"}, {"fix", {"uy", "uz"}}}});
  return doc;
}
int node(const Model& m, const std::string& id) { return m.find_node(id); }
}  // namespace

TEST(MemberLoadsStatic, SimplySupportedUniformLoadGivesFiveOver384AtMidspanAndEndSlopes) {
  // v(L/2) = 5 q L^4 / 384 EI, end slope q L^3 / 24 EI (Timoshenko & Gere, App. G, simple beam 1).
  const double q = 1500.0;
  json doc = simple_beam(2);
  doc["loads"].push_back({{"element", "e"}, {"distributed", {0, -q, 0}}});
  const Model m = test::model_from(doc);
  const auto r = solve_linear_static(m);
  ASSERT_EQ(r.status, SolveStatus::Succeeded);
  const double vmid = 5 * q * L * L * L * L / (384 * E * Iz);
  EXPECT_NEAR(r.u[6 * node(m, "e#1") + 1], -vmid, kExact * vmid);
  const double slope = q * L * L * L / (24 * E * Iz);
  EXPECT_NEAR(r.u[6 * node(m, "A") + 5], -slope, kExact * slope);
  EXPECT_NEAR(r.u[6 * node(m, "B") + 5], slope, kExact * slope);
  // Reactions q L / 2 each.
  EXPECT_NEAR(r.reactions[node(m, "A")][1], q * L / 2, 1e-9 * q * L);
}

TEST(MemberLoadsStatic, StationsGiveTheParabolicMomentOfASimplySupportedBeam) {
  // M(x) = q x (L - x) / 2 (sagging), V(x) = q (L/2 - x); stations from one element.
  const double q = 800.0;
  json doc = simple_beam(1);
  doc["loads"].push_back({{"element", "e"}, {"distributed", {0, -q, 0}}});
  const Model m = test::model_from(doc);
  const auto r = solve_linear_static(m);
  const auto st = member_stations(m, 0, r.end_forces, r.element_loads, 10);
  ASSERT_EQ(st.size(), 12u);  // two ends and ten interior points
  for (const auto& s : st) {
    const double M = q * s.x * (L - s.x) / 2;
    EXPECT_NEAR(s.forces[5], M, 1e-9 * q * L * L) << "x = " << s.x;   // Mz: sagging positive about +z
    EXPECT_NEAR(s.forces[1], -q * (L / 2 - s.x), 1e-9 * q * L) << "x = " << s.x;
  }
  EXPECT_NEAR(st[6].x - st[5].x, L / 11, 1e-12);
}

TEST(MemberLoadsStatic, CantileverSelfWeightGivesQL4Over8EI) {
  // q = rho A g; v = q L^4 / 8 EI, slope q L^3 / 6 EI (App. G, cantilever 1).
  const double rho = 7850.0, g = 9.81;
  json doc = test::cantilever(L, E, G, A, Iy, Iz, J, 1);
  doc["materials"][0]["density"] = rho;
  doc["gravity"] = {0, 0, -g};
  const auto r = solve_linear_static(test::model_from(doc));
  const double q = rho * A * g;
  const double w = q * L * L * L * L / (8 * E * Iy);
  EXPECT_NEAR(r.u[6 + 2], -w, kExact * w);
  EXPECT_NEAR(r.u[6 + 4], q * L * L * L / (6 * E * Iy), kExact * w / L);  // w' = -ry
  EXPECT_NEAR(r.reactions[0][2], q * L, 1e-9 * q * L);
  // Section forces at the root: shear q L, moment q L^2 / 2.
  EXPECT_NEAR(-r.end_forces[0][4], q * L * L / 2, 1e-9 * q * L * L);
}

TEST(MemberLoadsStatic, PointMassUnderGravityActsAsItsWeight) {
  // A massless cantilever with m at the tip: v = m g L^3 / 3 EI (App. G, cantilever 4).
  const double mass = 25.0, g = 9.81;
  json doc = test::cantilever(L, E, G, A, Iy, Iz, J, 3);
  doc["masses"] = json::array({{{"node", "B"}, {"mass", mass}, {"inertia", {{1, 0, 0}, {0, 2, 0}, {0, 0, 3}}}}});
  doc["gravity"] = {0, -g, 0};
  const auto r = solve_linear_static(test::model_from(doc));
  const double v = mass * g * L * L * L / (3 * E * Iz);
  EXPECT_NEAR(r.u[6 + 1], -v, kExact * v);
}

TEST(MemberLoadsStatic, PartialTrapezoidalLoadFollowsTheMemberOverItsSegments) {
  // Tip deflection of a cantilever under q(s) on [a, b]: int q(s) s^2 (3L - s) / 6EI ds (the
  // unit-load deflection of App. G cantilever 5), a polynomial of degree 4 integrated exactly by
  // 3-point Gauss here. The same member with 1 or 7 divisions gives the same (exact) tip.
  const double q1 = -1000.0, q2 = -3000.0, f = 0.25, t = 0.75;
  const double a = f * L, b = t * L;
  double want = 0.0;
  const double gx[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, gw[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  for (int k = 0; k < 3; ++k) {
    const double u = 0.5 * (1 + gx[k]), s = a + u * (b - a);
    want += 0.5 * (b - a) * gw[k] * (q1 + (q2 - q1) * u) * s * s * (3 * L - s) / (6 * E * Iy);
  }
  for (int div : {1, 7}) {
    json doc = test::cantilever(L, E, G, A, Iy, Iz, J, div);
    doc["loads"].push_back({{"element", "e"}, {"distributed", {0, 0, q1}}, {"distributed_end", {0, 0, q2}}, {"from", f}, {"to", t}});
    const Model m = test::model_from(doc);
    const auto r = solve_linear_static(m);
    EXPECT_NEAR(r.u[6 * node(m, "B") + 2], want, kExact * std::abs(want)) << div << " divisions";
    // The root reaction carries the whole load.
    EXPECT_NEAR(r.reactions[0][2], -0.5 * (q1 + q2) * (b - a), 1e-9 * std::abs(q2) * L);
  }
}

TEST(MemberLoadsStatic, PointLoadInsideASimpleBeamGivesTheTextbookEndSlope) {
  // theta_1 = P a b (L + b) / (6 E I L) (App. G, simple beam 5), one element, local axes.
  const double P = 2000.0, at = 0.3, a = at * L, b = L - a;
  json doc = simple_beam(1);
  doc["loads"].push_back({{"element", "e"}, {"point", {0, -P, 0}}, {"at", at}, {"axes", "local"}});
  const Model m = test::model_from(doc);
  const auto r = solve_linear_static(m);
  const double th = P * a * b * (L + b) / (6 * E * Iz * L);
  EXPECT_NEAR(r.u[5], -th, kExact * th);
  // Stations: a jump of P in Vy at x = a, moment P a b / L there.
  const auto st = member_stations(m, 0, r.end_forces, r.element_loads, 10);
  int jumps = 0;
  for (std::size_t k = 1; k < st.size(); ++k)
    if (std::abs(st[k].x - a) < 1e-12 && std::abs(st[k - 1].x - a) < 1e-12) {
      ++jumps;
      EXPECT_NEAR(st[k].forces[1] - st[k - 1].forces[1], P, 1e-9 * P);
      EXPECT_NEAR(st[k].forces[5], P * a * b / L, 1e-9 * P * L);
    }
  EXPECT_EQ(jumps, 1);
}

TEST(MemberLoadsStatic, ACombinationEqualsTheFactoredSumOfItsCases) {
  json doc = test::cantilever(L, E, G, A, Iy, Iz, J, 4);
  doc["materials"][0]["density"] = 7850.0;
  doc["load_cases"] = json::array({{{"id", "dead"}, {"gravity", {0, 0, -9.81}}},
                                   {{"id", "tool"}, {"loads", json::array({{{"node", "B"}, {"force", {0, 300, -500}}},
                                                                           {{"element", "e"}, {"point", {0, 0, -200}}, {"at", 0.6}}})}}});
  doc["combinations"] = json::array({{{"id", "uls"}, {"factors", {{"dead", 1.35}, {"tool", 1.5}}}}});
  const Model m = test::model_from(doc);
  const LinearSystem sys(m);
  const auto d = sys.solve(m.loads_for("dead"));
  const auto t = sys.solve(m.loads_for("tool"));
  const auto c = sys.solve(m.loads_for("uls"));
  EXPECT_EQ(sys.factorizations(), 1);
  const Eigen::VectorXd sum = 1.35 * d.u + 1.5 * t.u;
  EXPECT_LT((c.u - sum).cwiseAbs().maxCoeff(), 1e-12 * sum.cwiseAbs().maxCoeff());
  ASSERT_GT(sum.cwiseAbs().maxCoeff(), 0.0);
  for (std::size_t e = 0; e < m.elements.size(); ++e) {
    const Vec12 fs = 1.35 * d.end_forces[e] + 1.5 * t.end_forces[e];
    EXPECT_LT((c.end_forces[e] - fs).cwiseAbs().maxCoeff(), 1e-9 * fs.cwiseAbs().maxCoeff());
  }
}

namespace {
// J_nu(x) by its power series (Abramowitz & Stegun 9.1.10), enough terms for x < 3.
double bessel_j(double nu, double x) {
  double sum = 0.0;
  for (int m = 0; m < 40; ++m)
    sum += std::pow(-1.0, m) * std::pow(x / 2, 2 * m + nu) / (std::tgamma(m + 1.0) * std::tgamma(m + nu + 1.0));
  return sum;
}
// Greenhill's critical q L^3 / EI = (9/4) j^2, j the first zero of J_{-1/3} (bisection).
double greenhill() {
  double lo = 1.5, hi = 2.2;
  for (int k = 0; k < 80; ++k) {
    const double mid = 0.5 * (lo + hi);
    (bessel_j(-1.0 / 3.0, lo) * bessel_j(-1.0 / 3.0, mid) <= 0.0 ? hi : lo) = mid;
  }
  return 2.25 * lo * lo;
}
}  // namespace

TEST(MemberLoadsBuckling, ColumnUnderItsOwnWeightBucklesAtGreenhillsLoad) {
  const double want = greenhill();
  EXPECT_NEAR(want, 7.837, 5e-4);  // the textbook figure
  const double rho = 7850.0, g = 9.81, H = 10.0, I = 1e-6;  // Iy = Iz: either plane
  double prev_err = 1.0;
  for (int n : {4, 8, 16, 32}) {
    json doc{{"nodes", json::array({{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {0, 0, H}}}})},
             {"materials", json::array({{{"id", "m"}, {"E", E}, {"G", G}, {"density", rho}}})},
             {"sections", json::array({{{"id", "s"}, {"A", A}, {"Iy", I}, {"Iz", I}, {"J", 2 * I}}})},
             {"elements", json::array({{{"id", "col"}, {"type", "beam"}, {"nodes", {"A", "B"}}, {"material", "m"},
                                        {"section", "s"}, {"divisions", n}}})},
             {"supports", json::array({{{"node", "A"}, {"fix", "all"}}})},
             {"gravity", {0, 0, -g}}};
    const auto r = solve_buckling(test::model_from(doc), BucklingOptions{2});
    ASSERT_EQ(r.status, BucklingStatus::Succeeded);
    const double q = rho * A * g;
    const double got = r.load_factors[0] * q * H * H * H / (E * I);
    const double err = std::abs(got - want) / want;
    std::printf("Greenhill: %2d elements  q L^3/EI = %.5f  (exact %.5f, error %.2e)\n", n, got, want, err);
    EXPECT_LT(err, prev_err) << n << " elements";
    prev_err = err;
  }
  EXPECT_LT(prev_err, 1e-3);
}

}  // namespace member_loads_static_test
