// Path following (solvers/path_following.hpp) against closed forms and published benchmarks.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/errors.hpp"
#include "solvers/buckling.hpp"
#include "solvers/condensed_stiffness.hpp"
#include "solvers/path_following.hpp"
#include "path_models.hpp"

#include <cstdlib>
#include <iostream>

namespace path_test {

using namespace beamfea;
using namespace beamfea::test;

namespace {
constexpr double pi = 3.14159265358979323846;

// Cantilever column along x, fixed at A, compressive end load P_cr at B (lambda = P / P_cr).
// Out-of-plane bending 10x stiffer so that the column buckles in the x-y plane.
json elastica_column(int n, double L, double EI) {
  json d = straight_member(L, n, 1.0, 1.0, 1e4 * EI / (L * L) * 100, 10 * EI, EI, 10 * EI);
  d["materials"][0]["E"] = 1.0;
  d["materials"][0]["G"] = 1.0;
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  d["loads"].push_back(load("B", -pi * pi * EI / (4 * L * L), 0, 0));
  return d;
}

// Elastica of the cantilever (Timoshenko & Gere 1961, sec. 2.7): with k = sin(alpha/2), alpha the
// tip rotation, P / P_cr = (2 K(k) / pi)^2, tip deflection y/L = 2k/K(k), end shortening
// delta/L = 2 - 2 E(k)/K(k).
double elastica_load(double alpha) {
  const double k = std::sin(alpha / 2), K = std::comp_ellint_1(k);
  return std::pow(2 * K / pi, 2);
}
double elastica_shortening(double alpha) {
  const double k = std::sin(alpha / 2);
  return 2.0 - 2.0 * std::comp_ellint_2(k) / std::comp_ellint_1(k);
}

void check_elastica(const PathResult& r, double L, double tol, int& compared) {
  compared = 0;
  double worst_p = 0.0, worst_d = 0.0;
  for (const auto& s : r.steps) {
    const double alpha = std::abs(s.track[0][5]);
    if (alpha < 0.4 || alpha > 2.5) continue;
    ++compared;
    worst_p = std::max(worst_p, std::abs(s.load_factor / elastica_load(alpha) - 1.0));
    worst_d = std::max(worst_d, std::abs(-s.track[0][0] / L - elastica_shortening(alpha)));
    EXPECT_NEAR(s.load_factor / elastica_load(alpha), 1.0, tol) << "alpha " << alpha;
    EXPECT_NEAR(-s.track[0][0] / L, elastica_shortening(alpha), tol * 2) << "alpha " << alpha;
  }
  std::cout << "elastica: " << compared << " steps, max |P/P_exact - 1| = " << worst_p
            << ", max |delta/L - exact| = " << worst_d << "\n";
}
}  // namespace

// The elastica reached by automatic branch switching at the Euler bifurcation of a perfect column.
TEST(PathFollowing, ElasticaByBranchSwitchingMatchesEllipticIntegrals) {
  const double L = 1.0, EI = 1.0;
  const Model m = read_model(elastica_column(16, L, EI));
  PathOptions o;
  o.control = PathControl::ArcLength;
  o.arc_length = 0.1;
  o.max_arc_length = 0.15;
  o.branch_switch = true;
  o.track = {m.find_node("B")};
  o.max_steps = 60;
  o.stop_load_factor = 2.0;
  if (std::getenv("BEAMFEA_TEST_VERBOSE")) o.progress = [](const std::string& s) { std::cerr << s << "\n"; };
  const PathResult r = follow_path(m, o);
  ASSERT_GE(r.critical_points.size(), 1u) << r.brief_report();
  EXPECT_EQ(r.critical_points[0].type, CriticalPointType::Bifurcation);
  EXPECT_NEAR(r.critical_points[0].load_factor, 1.0, 2e-3);
  EXPECT_TRUE(r.critical_points[0].branch_switched);
  int compared = 0;
  check_elastica(r, L, 3e-3, compared);
  EXPECT_GE(compared, 5) << r.brief_report();
  // The post-buckling branch of the elastica is stable.
  for (const auto& s : r.steps)
    if (std::abs(s.track[0][5]) > 0.4) {
      EXPECT_TRUE(s.stable) << "step " << s.step;
    }
}

// The same curve through an imperfection: buckling mode 1 at 1e-3 L; at rotations above 0.4 rad
// the imperfect column is within 1 % of the perfect elastica.
TEST(PathFollowing, ElasticaByImperfectionApproachesEllipticIntegrals) {
  const double L = 1.0, EI = 1.0;
  const Model m = read_model(elastica_column(16, L, EI));
  PathOptions o;
  o.control = PathControl::ArcLength;
  o.arc_length = 0.1;
  o.max_arc_length = 0.15;
  o.imperfection_mode = 1;
  o.imperfection_amplitude = 1e-3 * L;
  o.track = {m.find_node("B")};
  o.max_steps = 60;
  o.stop_load_factor = 2.0;
  if (std::getenv("BEAMFEA_TEST_VERBOSE")) o.progress = [](const std::string& s) { std::cerr << s << "\n"; };
  const PathResult r = follow_path(m, o);
  int compared = 0;
  check_elastica(r, L, 1e-2, compared);
  EXPECT_GE(compared, 5) << r.brief_report();
}

// A cantilever rolled into a full circle by the end moment M = 2 pi EI / L (the classic test of
// finite rotations, e.g. Simo & Vu-Quoc 1986; Battini & Pacoste 2002): the tip returns to the root
// with its rotation a full turn (R = I). Co-rotational elements of zero axial strain close the
// polygon of chords exactly.
TEST(PathFollowing, CantileverRollsIntoAFullCircle) {
  const double L = 10.0, EI = 100.0;
  json d = rolled_cantilever(L, EI);
  const Model m = read_model(d);
  PathOptions o;
  o.control = PathControl::LoadFactor;
  o.target = 1.0;
  o.increments = 10;
  o.track = {m.find_node("B")};
  if (std::getenv("BEAMFEA_TEST_VERBOSE")) o.progress = [](const std::string& s) { std::cerr << s << "\n"; };
  const PathResult r = follow_path(m, o);
  ASSERT_TRUE(r.completed) << r.brief_report();
  ASSERT_NEAR(r.steps.back().load_factor, 1.0, 1e-12);
  const NonlinearState& s = r.steps.back().state;
  EXPECT_LT(s.x[m.find_node("B")].norm(), 1e-6 * L);
  EXPECT_LT((s.R[m.find_node("B")] - Mat3::Identity()).norm(), 1e-6);
  // Half way the tip is at the top of the circle: (0, L/pi).
  for (const auto& st : r.steps)
    if (std::abs(st.load_factor - 0.5) < 1e-9) {
      EXPECT_LT((st.state.x[m.find_node("B")] - Vec3(0, L / pi, 0)).norm(), 1e-3 * L);
    }
}

// Lee's frame (Lee, Manuel & Rossow 1968), with the data of Schweizerhof & Wriggers (1986):
// E = 7.2e6, A = 6, I = 2, L = 120, load 24 from the corner, pinned ends, 10 + 10 elements; their
// first limit load is P = 1.85e4 (the non-dimensional P L^2 / EI = 18.5 of Lee et al.; with
// E = 720 the same frame has P = 1.85). The path passes the first limit point, the snap-back (the
// vertical displacement of the load point turns back) and the second limit point (negative load).
TEST(PathFollowing, LeesFrameThroughBothLimitPointsAndSnapBack) {
  const json d = lees_frame(1e4);  // lambda in units of 1e4 (tests/solvers/path_models.hpp)
  const Model m = read_model(d);
  PathOptions o;
  o.control = PathControl::ArcLength;
  o.arc_length = 10.0;
  o.max_arc_length = 40.0;
  o.track = {m.find_node("P")};
  o.max_steps = 300;
  o.stop_steps = 70;
  if (std::getenv("BEAMFEA_TEST_VERBOSE")) o.progress = [](const std::string& s) { std::cerr << s << "\n"; };
  const PathResult r = follow_path(m, o);
  ASSERT_TRUE(r.completed) << r.brief_report();
  std::vector<const CriticalPoint*> limits;
  for (const auto& c : r.critical_points)
    if (c.type == CriticalPointType::LimitPoint) limits.push_back(&c);
  ASSERT_GE(limits.size(), 2u) << r.critical_points.size() << " critical points; " << r.brief_report();
  EXPECT_NEAR(limits[0]->load_factor, 1.85, 0.02 * 1.85);
  EXPECT_LT(limits[1]->load_factor, 0.0);  // the second limit point lies under a negative load
  double lmax = -1e300;  // up to the second limit point (beyond it the path may rise again)
  for (const auto& s : r.steps)
    if (s.step <= limits[1]->step) lmax = std::max(lmax, s.load_factor);
  EXPECT_NEAR(lmax, limits[0]->load_factor, 2e-3 * lmax);  // located by bisection, above every step
  // Snap-back: the vertical displacement of the load point is not monotone along the path.
  bool turned = false;
  for (std::size_t i = 2; i < r.steps.size(); ++i) {
    const double a = r.steps[i - 1].track[0][1] - r.steps[i - 2].track[0][1];
    const double b = r.steps[i].track[0][1] - r.steps[i - 1].track[0][1];
    if (a < 0 && b > 0) turned = true;
  }
  EXPECT_TRUE(turned);
  // Unstable between the limit points.
  bool unstable = false;
  for (const auto& s : r.steps) unstable = unstable || !s.stable;
  EXPECT_TRUE(unstable);
}

// Displacement control of the end of a rigid chain on springs (the lumped-model use): no loads, the
// tip pushed along the chain; the reaction (the force applied at the controlled DOF) balances the spring. For one
// link of length L on a spring k pushed sideways to y, q = asin(y / L) and R_y = k q / (L cos q).
TEST(PathFollowing, ImposedMotionOfAChainEndGivesTheSpringReaction) {
  const double L = 0.5, k = 20.0;
  const json d = rigid_chain(1, L, k);
  const Model m = read_model(d);
  PathOptions o;
  o.control = PathControl::Displacement;
  o.control_node = m.find_node("N1");
  o.control_dof = 1;
  o.target = 0.3;
  o.increments = 6;
  o.track = {m.find_node("N1")};
  o.stiffness_node = m.find_node("N1");
  if (std::getenv("BEAMFEA_TEST_VERBOSE")) o.progress = [](const std::string& s) { std::cerr << s << "\n"; };
  const PathResult r = follow_path(m, o);
  ASSERT_TRUE(r.completed) << r.brief_report();
  const auto& s = r.steps.back();
  const double q = std::asin(0.3 / L);
  EXPECT_NEAR(s.track[0][1], 0.3, 1e-10);
  EXPECT_NEAR(s.reaction, k * q / (L * std::cos(q)), 1e-8 * k);
  // Loaded Cartesian stiffness of the tip (one joint: rank one). The tip moves by t dq,
  // t = (-L sin q, L cos q, 0, 0, 0, 1); the loaded joint stiffness is k_q = k + F L sin q (spring
  // plus the curvature of the link under the tip force F held fixed); K_c = k_q t t^T / |t|^4, the
  // pseudo-inverse of the compliance t t^T / k_q.
  ASSERT_TRUE(s.stiffness.has_value());
  const double F = k * q / (L * std::cos(q));
  const double kq = k + F * L * std::sin(q);
  const Vec6 t = (Vec6() << -L * std::sin(q), L * std::cos(q), 0, 0, 0, 1.0).finished();
  const Mat6 expected = kq * t * t.transpose() / std::pow(t.squaredNorm(), 2);
  EXPECT_LT((*s.stiffness - expected).cwiseAbs().maxCoeff(), 1e-8 * expected.cwiseAbs().maxCoeff());
}

// A deep pinned circular arch (half-angle 60 deg, R = 100, 20 elements) under a crown load: on the
// symmetric primary path the asymmetric bifurcation comes first, then the symmetric limit point
// (Timoshenko & Gere 1961, sec. 7.5: for deep two-hinged arches the antisymmetric buckling load is
// below the symmetric snap-through load). Without branch switching the path stays symmetric and
// passes both: the first is a bifurcation (its mode, antisymmetric, does no work on the crown
// load), the second a limit point (symmetric mode); the bifurcation lies within 2 % of the
// linearised buckling factor.
TEST(PathFollowing, ArchBifurcationThenLimitPointAreClassified) {
  const double R = 100.0, a = 60.0 * pi / 180.0;
  const int n = 20;
  json d;
  d["nodes"] = json::array();
  d["elements"] = json::array();
  for (int i = 0; i <= n; ++i) {
    const double t = -a + 2 * a * i / n;
    d["nodes"].push_back({{"id", name("n", i)}, {"xyz", {R * std::sin(t), R * std::cos(t) - R * std::cos(a), 0}}});
  }
  for (int i = 0; i < n; ++i)
    d["elements"].push_back({{"id", name("e", i)}, {"type", "beam"},
                             {"nodes", {name("n", i), name("n", i + 1)}}, {"material", "m"},
                             {"section", "s"}, {"orientation", {0, 0, 1}}});
  d["materials"] = json::array({{{"id", "m"}, {"E", 1e4}, {"G", 4e3}}});
  d["sections"] = json::array({{{"id", "s"}, {"A", 10.0}, {"Iy", 1000.0}, {"Iz", 1.0}, {"J", 1000.0}}});
  d["supports"] = json::array({fix("n0", {"ux", "uy", "uz", "rx", "ry"}), fix("n20", {"ux", "uy", "uz", "rx", "ry"})});
  d["loads"] = json::array({load("n10", 0, -1.0, 0)});
  const Model m = read_model(d);
  const BucklingResult b = solve_buckling(m);
  ASSERT_EQ(b.status, BucklingStatus::Succeeded);
  PathOptions o;
  o.control = PathControl::ArcLength;
  o.arc_length = 100.0;
  o.max_arc_length = 200.0;
  o.track = {m.find_node("n10")};
  o.max_steps = 25;
  if (std::getenv("BEAMFEA_TEST_VERBOSE")) o.progress = [](const std::string& s) { std::cerr << s << "\n"; };
  const PathResult r = follow_path(m, o);
  ASSERT_GE(r.critical_points.size(), 2u) << r.brief_report();
  const auto& bif = r.critical_points[0];
  const auto& lim = r.critical_points[1];
  EXPECT_EQ(bif.type, CriticalPointType::Bifurcation);
  EXPECT_EQ(lim.type, CriticalPointType::LimitPoint);
  EXPECT_LT(bif.load_factor, lim.load_factor);
  EXPECT_NEAR(bif.load_factor / b.load_factors[0], 1.0, 0.02);
  const int crown = 6 * m.find_node("n10");
  EXPECT_GT(std::abs(bif.mode[crown + 0]), 10 * std::abs(bif.mode[crown + 1]));  // sways: antisymmetric
  EXPECT_GT(std::abs(lim.mode[crown + 1]), 10 * std::abs(lim.mode[crown + 0]));  // drops: symmetric
}

// A lumped model (Pashkevich et al.'s VJM): two rigid links joined by 6-D virtual springs with full
// stiffness matrices, the end pushed by imposed motion. At the unloaded start the loaded Cartesian
// stiffness equals the linear condensed stiffness of analysis "stiffness" (eq. 28 reduces to the
// unloaded K_C when F = 0), and along the path the reaction is the loaded stiffness's work: a
// small imposed step du gives reaction ~ K_c du.
TEST(PathFollowing, VirtualSpringChainStiffnessAtStartEqualsLinearStiffness) {
  json d;
  d["nodes"] = json::array({{{"id", "B"}, {"xyz", {0, 0, 0}}}, {{"id", "B1"}, {"xyz", {0, 0, 0}}},
                            {{"id", "M"}, {"xyz", {0.4, 0.1, 0.0}}}, {{"id", "M1"}, {"xyz", {0.4, 0.1, 0.0}}},
                            {{"id", "E"}, {"xyz", {0.8, 0.0, 0.2}}}});
  json K = json::array();
  for (int i = 0; i < 6; ++i) {
    json row = json::array();
    for (int j = 0; j < 6; ++j) row.push_back(i == j ? (i < 3 ? 1e5 : 50.0) : (std::abs(i - j) == 3 ? 300.0 : 0.0));
    K.push_back(row);
  }
  d["joints"] = json::array({{{"id", "v1"}, {"type", "virtual_spring"}, {"nodes", {"B", "B1"}}, {"stiffness", K}},
                             {{"id", "v2"}, {"type", "virtual_spring"}, {"nodes", {"M", "M1"}}, {"stiffness", K}}});
  d["elements"] = json::array({{{"id", "l1"}, {"type", "rigid"}, {"nodes", {"B1", "M"}}},
                               {{"id", "l2"}, {"type", "rigid"}, {"nodes", {"M1", "E"}}}});
  d["supports"] = json::array({fix("B", {"ux", "uy", "uz", "rx", "ry", "rz"})});
  d["loads"] = json::array();
  const Model m = read_model(d);
  const CondensedStiffness lin = linear_node_stiffness(m, m.find_node("E"));
  ASSERT_TRUE(lin.ok) << lin.message;
  PathOptions o;
  o.control = PathControl::Displacement;
  o.control_node = m.find_node("E");
  o.control_dof = 2;
  o.target = 1e-6;
  o.increments = 1;
  o.track = {m.find_node("E")};
  o.stiffness_node = m.find_node("E");
  const PathResult r = follow_path(m, o);
  ASSERT_TRUE(r.completed) << r.brief_report();
  ASSERT_TRUE(r.steps[0].stiffness.has_value());
  const Mat6& Kc = *r.steps[0].stiffness;
  EXPECT_LT((Kc - lin.K).cwiseAbs().maxCoeff(), 1e-8 * lin.K.cwiseAbs().maxCoeff());
  // The reaction of a tiny imposed uz: the uz-uz entry of the stiffness with the node's other DOFs
  // free, i.e. 1 / (K_c^-1)_zz.
  const double kzz = 1.0 / Kc.inverse()(2, 2);
  EXPECT_NEAR(r.steps.back().reaction / 1e-6, kzz, 1e-4 * kzz);
}

// Bad input that reaches the path solver directly (beamfea check rejects it first) names its
// entity, never an empty one: a model without loads under load control, a buckling mode that
// does not exist for the imperfection, a rigid link whose ends are held apart.
TEST(PathFollowing, BadInputNamesItsEntity) {
  auto entity_of = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const ModelError& e) {
      EXPECT_FALSE(e.entity().empty()) << e.what();
      return e.entity();
    }
    return std::string("(no ModelError)");
  };
  json d = straight_member(1.0, 2, 2.1e11, 8.1e10, 1e-3, 2e-6, 3e-6, 1e-6);
  d["supports"] = json::array({{{"node", "A"}, {"fix", "all"}}});
  const Model unloaded = read_model(d);
  EXPECT_EQ(entity_of([&] { follow_path(unloaded, PathOptions{}); }), "loads");

  d["loads"] = json::array({{{"node", "B"}, {"force", {-1000, 0, 0}}}});
  const Model loaded = read_model(d);
  EXPECT_EQ(entity_of([&] { imperfect_model(loaded, 999, 1e-3); }), "imperfection mode 999");

  // A rigid link from the clamped node A to a node C prescribed to move (the bad_rigid_body
  // case of the fuzz corpus).
  d["nodes"].push_back({{"id", "C"}, {"xyz", {0, 1, 0}}});
  d["elements"].push_back({{"id", "r"}, {"type", "rigid"}, {"nodes", {"A", "C"}}});
  d["prescribed"] = json::array({{{"node", "C"}, {"dof", "uz"}, {"value", 0.01}}});
  const Model held_apart = read_model(d);
  EXPECT_EQ(entity_of([&] { follow_path(held_apart, PathOptions{}); }), "supports and prescribed values");
}

}  // namespace path_test
