// The chord corrector of path steps (solvers/path/corrector.hpp) against full Newton (KINSOL at
// every iteration, PathOptions::chord_corrector = false): the same converged points to the tolerance
// of the convergence test, the same stability counts and critical points, with fewer LU
// factorisations. Under every control: arc length (the bordered system by block elimination),
// displacement control with loads (bordered too), load control and imposed motion (the start
// factor is the step's own system).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>

#include "path_models.hpp"
#include "solvers/path_following.hpp"

namespace path_chord_test {

using namespace beamfea;
using namespace beamfea::test;

namespace {

constexpr double pi = 3.14159265358979323846;

PathResult run(const Model& m, PathOptions o, bool chord) {
  o.chord_corrector = chord;
  if (std::getenv("BEAMFEA_TEST_VERBOSE")) o.progress = [](const std::string& s) { std::cerr << s << "\n"; };
  PathResult r = follow_path(m, o);
  std::cout << (chord ? "chord " : "newton") << ": " << r.steps.size() - 1 << " steps, " << r.factorizations
            << " factorisations, " << r.chord_steps << " chord steps, " << r.chord_fallbacks << " fall-backs; "
            << r.brief_report() << "\n";
  return r;
}

// Arc length fixed at ds (min = max, so both correctors take the same steps) for `steps` steps, the
// apex of Williams' toggle tracked.
PathOptions fixed_arc_length(const Model& m, double ds, int steps) {
  PathOptions o;
  o.control = PathControl::ArcLength;
  o.arc_length = ds;
  o.min_arc_length = o.max_arc_length = ds;
  o.track = {m.find_node("apex")};
  o.stop_steps = steps;
  return o;
}

}  // namespace

// Williams' toggle (16 elements per member, P = 1) under arc length with a fixed ds = 1 (min = max):
// both correctors solve the same steps from the same predictors, so every converged point agrees to
// the convergence test's tolerance (forces at 1e-9 of the reference load: displacements and load
// factors to ~1e-9 relative; asserted 1e-6), through the load maximum (33.98,
// tests/solvers/path_benchmarks_test.cpp) and the minimum after it (31.38), with the same inertia at
// every step and the same critical points. Some of these steps the chord solves, on others it gives
// up and full Newton solves them: both paths are exercised.
TEST(PathChord, ArcLengthStepsEqualFullNewtonsThroughWilliamsToggleLimitPoints) {
  const Model m = read_model(williams_toggle(16, 1.0));
  const PathOptions o = fixed_arc_length(m, 1.0, 14);
  const PathResult rn = run(m, o, false), rc = run(m, o, true);
  ASSERT_TRUE(rn.completed) << rn.brief_report();
  ASSERT_TRUE(rc.completed) << rc.brief_report();
  ASSERT_EQ(rn.steps.size(), rc.steps.size());
  double lmax = 0.0;
  for (const auto& s : rn.steps) lmax = std::max(lmax, std::abs(s.load_factor));
  const double L = 2 * 12.943;
  double worst_l = 0.0, worst_u = 0.0;
  for (std::size_t i = 0; i < rn.steps.size(); ++i) {
    const PathStep &a = rn.steps[i], &b = rc.steps[i];
    worst_l = std::max(worst_l, std::abs(a.load_factor - b.load_factor) / lmax);
    worst_u = std::max(worst_u, (a.track[0] - b.track[0]).head<3>().cwiseAbs().maxCoeff() / L);
    EXPECT_NEAR(a.load_factor, b.load_factor, 1e-6 * lmax) << "step " << i;
    EXPECT_LT((a.track[0] - b.track[0]).head<3>().cwiseAbs().maxCoeff(), 1e-6 * L) << "step " << i;
    EXPECT_LT((a.track[0] - b.track[0]).tail<3>().cwiseAbs().maxCoeff(), 1e-6) << "step " << i;
    EXPECT_EQ(a.negative_eigenvalues, b.negative_eigenvalues) << "step " << i;
  }
  std::cout << "max |dlambda| / lambda_max = " << worst_l << ", max |du| / L = " << worst_u << "\n";
  ASSERT_EQ(rn.critical_points.size(), rc.critical_points.size());
  ASSERT_GE(rn.critical_points.size(), 2u);
  for (std::size_t i = 0; i < rn.critical_points.size(); ++i) {
    EXPECT_EQ(rn.critical_points[i].type, rc.critical_points[i].type);
    EXPECT_NEAR(rn.critical_points[i].load_factor, rc.critical_points[i].load_factor, 1e-6 * lmax);
  }
  EXPECT_NEAR(rc.critical_points[0].load_factor, 33.98, 1e-3 * 33.98);
  EXPECT_GT(rc.chord_steps, 0);
  EXPECT_GT(rc.chord_fallbacks, 0);
  EXPECT_LT(rc.factorizations, rn.factorizations);
}

// Williams' toggle under displacement control of the apex to -0.3 (the steps adapt to the iteration
// counts, so the two paths take their own steps): the load factor at the target and the limit load
// (33.98 with 16 elements per member, tests/solvers/path_benchmarks_test.cpp) agree.
TEST(PathChord, DisplacementControlReachesTheSameTargetAndLimitPoint) {
  const Model m = read_model(williams_toggle(16, 1.0));
  PathOptions o;
  o.control = PathControl::Displacement;
  o.control_node = m.find_node("apex");
  o.control_dof = 1;
  o.target = -0.3;
  o.increments = 10;
  o.track = {m.find_node("apex")};
  const PathResult rn = run(m, o, false), rc = run(m, o, true);
  ASSERT_TRUE(rn.completed) << rn.brief_report();
  ASSERT_TRUE(rc.completed) << rc.brief_report();
  EXPECT_NEAR(rc.steps.back().load_factor, rn.steps.back().load_factor, 1e-7 * std::abs(rn.steps.back().load_factor));
  EXPECT_NEAR(rc.steps.back().track[0][1], -0.3, 1e-12);
  ASSERT_FALSE(rn.critical_points.empty());
  ASSERT_EQ(rn.critical_points.size(), rc.critical_points.size());
  // Located by bisection to 1e-3 of the step: at the flat top of the load the error is quadratic.
  EXPECT_NEAR(rc.critical_points[0].load_factor, rn.critical_points[0].load_factor, 1e-4 * rn.critical_points[0].load_factor);
  EXPECT_NEAR(rc.critical_points[0].load_factor, 33.98, 0.01 * 33.98);
  EXPECT_GT(rc.chord_steps, 0);
  EXPECT_LT(rc.factorizations, rn.factorizations);
}

// Load control: the cantilever rolled into a full circle by M = 2 pi EI / L (tests/solvers/path_test.cpp):
// the same final state (tip back at the root, R = I) by both correctors. Its steps (0.6 rad at the tip)
// are beyond the chord (the start tangent is far from the converged one): the chord gives up at every
// step and full Newton solves it from the same predictor, so the fall-back is what this test checks.
TEST(PathChord, LoadControlRollsTheCantileverIntoTheSameCircle) {
  const double L = 10.0, EI = 100.0;
  json d = rolled_cantilever(L, EI);
  const Model m = read_model(d);
  PathOptions o;
  o.control = PathControl::LoadFactor;
  o.target = 1.0;
  o.increments = 10;
  o.track = {m.find_node("B")};
  const PathResult rn = run(m, o, false), rc = run(m, o, true);
  ASSERT_TRUE(rn.completed) << rn.brief_report();
  ASSERT_TRUE(rc.completed) << rc.brief_report();
  const int B = m.find_node("B");
  const NonlinearState &a = rn.steps.back().state, &b = rc.steps.back().state;
  EXPECT_LT((a.x[B] - b.x[B]).norm(), 1e-7 * L);
  EXPECT_LT((a.R[B] - b.R[B]).norm(), 1e-7);
  EXPECT_LT(b.x[B].norm(), 1e-6 * L);
  EXPECT_GT(rc.chord_fallbacks, 0);
  EXPECT_EQ(rc.steps.size(), rn.steps.size());
  for (std::size_t i = 0; i < rc.steps.size(); ++i) EXPECT_EQ(rc.steps[i].iterations, rn.steps[i].iterations) << "step " << i;
}

// Imposed motion (no loads): a rigid link on a spring pushed sideways to y; the reaction
// k q / (L cos q), q = asin(y / L), by both correctors (the factor is of the step's own system).
TEST(PathChord, ImposedMotionGivesTheSameReaction) {
  const double L = 0.5, k = 20.0, y = 0.3;
  const Model m = read_model(rigid_chain(1, L, k));
  PathOptions o;
  o.control = PathControl::Displacement;
  o.control_node = m.find_node("N1");
  o.control_dof = 1;
  o.target = y;
  o.increments = 6;
  o.track = {m.find_node("N1")};
  const PathResult rn = run(m, o, false), rc = run(m, o, true);
  ASSERT_TRUE(rn.completed) << rn.brief_report();
  ASSERT_TRUE(rc.completed) << rc.brief_report();
  const double q = std::asin(y / L), exact = k * q / (L * std::cos(q));
  EXPECT_NEAR(rc.steps.back().reaction, exact, 1e-8 * exact);
  EXPECT_NEAR(rc.steps.back().reaction, rn.steps.back().reaction, 1e-8 * exact);
  EXPECT_GT(rc.chord_steps, 0);
}

// Small steps (Williams' toggle, fixed ds = 0.03, before its limit point): the chord solves every
// step, and the path factorises once per step, the tangent of the state the step starts from (which
// also gives the predictor and the stability analysis); full Newton adds one LU per iteration.
TEST(PathChord, OneFactorisationPerStepWhereTheChordConverges) {
  const Model m = read_model(williams_toggle(16, 1.0));
  const PathOptions o = fixed_arc_length(m, 0.03, 20);
  const PathResult rn = run(m, o, false), rc = run(m, o, true);
  ASSERT_TRUE(rc.completed) << rc.brief_report();
  ASSERT_EQ(rc.steps.size(), 21u);
  EXPECT_EQ(rc.chord_steps, 20);
  EXPECT_EQ(rc.chord_fallbacks, 0);
  EXPECT_EQ(rc.factorizations, 20);
  EXPECT_GE(rn.factorizations, 40);
  for (std::size_t i = 1; i < rc.steps.size(); ++i) {
    EXPECT_EQ(rc.steps[i].iterations, 0) << "step " << i;
    EXPECT_GE(rc.steps[i].chord_iterations, 1) << "step " << i;
    EXPECT_NEAR(rc.steps[i].load_factor, rn.steps[i].load_factor, 1e-6 * std::abs(rn.steps[i].load_factor));
  }
}

}  // namespace path_chord_test
