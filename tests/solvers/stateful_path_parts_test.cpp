// The path solver's parts in isolation (solvers/path/): the immutable system description shared by
// two factor caches, its scales, and a branch switch's result.
#include <gtest/gtest.h>

#include <cmath>

#include "path_models.hpp"
#include "solvers/kinsol_solver.hpp"
#include "solvers/path/corrector.hpp"
#include "solvers/path/critical_points.hpp"
#include "solvers/path/equilibrium.hpp"
#include "solvers/path/factor_cache.hpp"
#include "solvers/path/predictor.hpp"
#include "solvers/path/stability.hpp"

namespace stateful_path_parts_test {

using namespace beamfea;
using namespace beamfea::test;

namespace {
constexpr double pi = 3.14159265358979323846;

// A cantilever along x of length L (EI = 1 in both planes), fixed at A, in n elements, end load
// (fx, fy) at B.
Model cantilever(int n, double L, double fx, double fy) {
  json d = straight_member(L, n, 1.0, 1.0, 1e4, 1.0, 1.0, 1.0);
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  d["loads"].push_back(load("B", fx, fy, 0));
  return read_model(d);
}

// The free coordinate of node `node`'s raw DOF `comp`.
int free_coordinate(const PathSystem& sys, int node, int comp) {
  const int raw = sys.structure().reference_map().raw_node(node, comp);
  return sys.free_index(sys.structure().gen_of_raw(raw));
}
}  // namespace

// The tangent at the reference state per unit load factor is the linear response: the tip of a
// cantilever under a transverse end load P deflects P L^3 / (3 EI) (Euler-Bernoulli; exact for the
// cubic beam element). One const description serves two caches: the same tangent from each, one
// factorisation each, none more when the state is asked again.
TEST(PathParts, OneConstSystemServesTwoFactorCachesAlike) {
  const double L = 2.0, P = 1e-3;
  const Model m = cantilever(4, L, 0.0, -P);
  PathOptions o;
  const PathSystem sys(m, o);
  FactorCache a, b;
  KinsolSolver kin(o.newton);
  const StepSolution start = initial_state(sys, a, kin);
  ASSERT_TRUE(start.converged) << start.report;
  const Eigen::VectorXd ta = a.tangent(sys, start.state);
  const Eigen::VectorXd tb = b.tangent(sys, start.state);
  ASSERT_EQ(ta.size(), sys.nf());
  EXPECT_EQ(ta, tb);
  const int tip = free_coordinate(sys, m.find_node("B"), 1);
  ASSERT_GE(tip, 0);
  EXPECT_NEAR(ta[tip], -P * L * L * L / 3.0, 1e-9 * P * L * L * L);
  EXPECT_EQ(a.factorizations(), 1);
  EXPECT_EQ(b.factorizations(), 1);
  a.tangent(sys, start.state);
  EXPECT_EQ(a.factorizations(), 1);
  EXPECT_EQ(a.factor_rows(start.state), sys.nf());
  // Another state in one cache: its own factorisation, the other cache untouched.
  Converged loaded = start.state;
  loaded.lambda = 0.5;
  a.tangent(sys, loaded);
  EXPECT_EQ(a.factorizations(), 2);
  EXPECT_EQ(a.factor_rows(start.state), -1);
  EXPECT_EQ(b.factorizations(), 1);
  EXPECT_EQ(b.factor_rows(start.state), sys.nf());
}

// with_scales sets the force scale of the convergence test to the reference load at lambda_ref
// (largest component P here, far above the round-off floor) and psi^2, and keeps the numbering.
TEST(PathParts, ScalesAreSetOnceOnTheSameNumbering) {
  const Model m = cantilever(4, 2.0, 0.0, -1.0);
  PathOptions o;
  const PathSystem unscaled(m, o);
  EXPECT_DOUBLE_EQ(unscaled.force_scale(), 1.0);
  EXPECT_EQ(unscaled.psi2(), 0.0);
  const PathSystem scaled = PathSystem(m, o).with_scales(3.0, 0.5);
  EXPECT_DOUBLE_EQ(scaled.force_scale(), 3.0);
  EXPECT_DOUBLE_EQ(scaled.psi2(), 0.25);
  EXPECT_EQ(scaled.nf(), unscaled.nf());
  EXPECT_EQ(scaled.free_gens(), unscaled.free_gens());
  // A load factor scale that is not positive keeps the reference load's force scale.
  EXPECT_DOUBLE_EQ(PathSystem(m, o).with_scales(0.0, 0.5).force_scale(), 1.0);
}

// A branch switch from a stable state just below the Euler load of a cantilever column along its
// critical mode: the result carries the first secondary state, the arc length used and the step's
// direction. The state lies on the elastica (Timoshenko & Gere 1961, sec. 2.7: with k = sin(alpha/2),
// alpha the tip rotation, P / P_cr = (2 K(k) / pi)^2), and the step meets the arc-length constraint.
TEST(PathParts, ABranchSwitchReturnsTheSecondaryStateItsArcLengthAndDirection) {
  const double L = 1.0, EI = 1.0;
  const Model m = cantilever(16, L, -pi * pi * EI / (4 * L * L), 0.0);
  PathOptions o;
  o.control = PathControl::ArcLength;
  const PathSystem sys(m, o);
  FactorCache factors;
  KinsolSolver kin(o.newton);
  Corrector corrector(sys, factors, kin, ChordIterations::On);
  StabilityAnalyzer stability(sys, factors);
  Predictor predictor(sys, factors);
  const CriticalPointParts parts{o, sys, factors, corrector, stability, predictor};
  const StepSolution start = initial_state(sys, factors, kin);
  ASSERT_TRUE(start.converged) << start.report;
  const StepPrediction to_below = predictor.predict(start.state, PathControl::LoadFactor, 0.99);
  const StepSolution below = corrector.solve(start.state, to_below.spec, to_below.u);
  ASSERT_TRUE(below.converged) << below.report;
  const StabilityAnalysis st = stability.analyse(below.state, {.mode = CriticalMode::Wanted});
  ASSERT_EQ(st.info.negative, 0);
  ASSERT_EQ(st.info.mode.size(), sys.nf());

  const double h = 0.1;
  const BranchSwitch bs = switch_branch(parts, below.state, st.info.mode, h);
  ASSERT_TRUE(bs.switched) << bs.report;
  EXPECT_FALSE(bs.report.empty());
  EXPECT_GT(bs.ds, 0.0);
  EXPECT_LE(bs.ds, h);
  ASSERT_EQ(bs.direction.size(), sys.nf() + 1);
  EXPECT_EQ(bs.direction.head(sys.nf()), st.info.mode);
  EXPECT_EQ(bs.direction[sys.nf()], bs.state.lambda - below.state.lambda);
  // |Delta|_W^2 + psi^2 dlambda^2 = ds^2 (psi = 0: the system is not scaled here).
  const Eigen::VectorXd step = sys.increment(below.state, bs.state);
  EXPECT_NEAR(std::sqrt(sys.weighted_dot(step, step)), bs.ds, 1e-6 * bs.ds);
  // On the elastica, off the straight primary path.
  const int B = m.find_node("B");
  const double alpha = std::abs(log_so3(bs.state.state.R[B])[2]);
  // (ds = 0.1 spreads over the column's 16 nodes and their rotations: the tip moves by some L / 50.)
  EXPECT_GT(std::abs(bs.state.state.x[B][1]), 0.01 * L);
  const double k = std::sin(alpha / 2);
  // Within 2e-3 (the column's axial strain, 2.5e-4, and its small rotation leave some 1e-3): the
  // start, 1 % below the Euler load, would miss it.
  EXPECT_NEAR(bs.state.lambda, std::pow(2 * std::comp_ellint_1(k) / pi, 2), 2e-3);
}

}  // namespace stateful_path_parts_test
