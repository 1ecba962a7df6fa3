// Closed kinematic loops and over-constrained mechanisms in the linear stiffness and buckling
// analyses (solvers/condensed_stiffness.hpp, solvers/buckling.hpp), against closed forms computed
// here (tests/solvers/loop_models.hpp).
#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "solvers/buckling.hpp"
#include "solvers/condensed_stiffness.hpp"
#include "solvers/linear_static.hpp"
#include "loop_models.hpp"

namespace closed_loop_test {

using namespace beamfea;
using namespace beamfea::test;

namespace {

// Relative error of the in-plane (ux, uy) block of a compliance against a 2 x 2 reference.
double planar_error(const Mat6& C, const Eigen::Matrix2d& ref) {
  return (C.topLeftCorner<2, 2>() - ref).norm() / ref.norm();
}

}  // namespace

// Five-bar, unloaded: the end point's compliance is J K^-1 J^T (J = dE/dq of the closed-form
// kinematics, K = diag(k1, k2)); the end point moves in a 2-D subspace of (ux, uy, rz) (its
// rotation is that of the distal link), so four directions are rigid, none free, rank 2. The same
// through the ground (supports on a slave) and through a joint closure (rigid ground link).
TEST(ClosedLoop, FiveBarUnloadedComplianceIsJKinvJT) {
  const FiveBar fb;
  const Eigen::Matrix2d J = fb.J(fb.q1, fb.q2);
  const Eigen::Matrix2d C = J * Eigen::Vector2d(1 / fb.k1, 1 / fb.k2).asDiagonal() * J.transpose();
  for (bool ground_link : {false, true}) {
    const Model m = read_model(five_bar_model(fb, ground_link));
    const CondensedStiffness k = linear_node_stiffness(m, m.find_node("E"));
    ASSERT_TRUE(k.ok) << k.message;
    EXPECT_LT(planar_error(k.compliance, C), 1e-10) << "ground link " << ground_link << "\n" << k.compliance;
    EXPECT_EQ(k.rank, 2);
    EXPECT_EQ(k.rigid_directions.size(), 4u);
    EXPECT_TRUE(k.null_space.empty());
    // Symmetric, and the matrix is the pseudo-inverse of the compliance: K C K = K.
    EXPECT_LT((k.compliance - k.compliance.transpose()).norm(), 1e-12 * k.compliance.norm());
    EXPECT_LT((k.K * k.compliance * k.K - k.K).norm(), 1e-9 * k.K.norm());
    // Out of plane the end point cannot move.
    for (int i = 2; i < 5; ++i) EXPECT_LT(k.compliance.row(i).norm(), 1e-12 * k.compliance.norm()) << i;
  }
}

// A supported node has a compliance too: zero, rank 0, six rigid directions.
TEST(ClosedLoop, HeldNodeHasZeroComplianceAndSixRigidDirections) {
  const Model m = read_model(five_bar_model(FiveBar{}));
  const CondensedStiffness k = linear_node_stiffness(m, m.find_node("A2"));
  ASSERT_TRUE(k.ok) << k.message;
  EXPECT_EQ(k.rank, 0);
  EXPECT_EQ(k.rigid_directions.size(), 6u);
  EXPECT_EQ(k.compliance.norm(), 0.0);
}

// Over-constrained (four parallel revolute axes: three closure rows redundant) and released
// (universal and spherical joints: none redundant) four-bars give the same compliance at the
// coupler point C; its in-plane part is (dC/dtheta) (dC/dtheta)^T / k.
TEST(ClosedLoop, OverConstrainedAndReleasedFourBarsHaveTheSameCompliance) {
  const FourBar fb;
  const Eigen::Vector2d dC = fb.dC(fb.theta0);
  const Eigen::Matrix2d ref = dC * dC.transpose() / fb.k;
  Mat6 first = Mat6::Zero();
  int count = 0;
  for (bool ground_link : {false, true})
    for (bool released : {false, true}) {
      const Model m = read_model(four_bar_model(fb, ground_link, released));
      const CondensedStiffness k = linear_node_stiffness(m, m.find_node("C"));
      ASSERT_TRUE(k.ok) << k.message;
      EXPECT_LT(planar_error(k.compliance, ref), 1e-10) << ground_link << released << "\n" << k.compliance;
      if (count++ == 0) first = k.compliance;
      EXPECT_LT((k.compliance - first).norm(), 1e-10 * first.norm()) << ground_link << released;
      EXPECT_EQ(k.rank, 1);
      EXPECT_EQ(k.rigid_directions.size(), 5u);
    }
}

// Sway frame of rigid columns on base springs tied by a pinned rigid beam (a loop through the
// ground with three redundant rows): linear buckling at P = k / h per column.
// The same with a rigid ground link between the bases: the rigid beam closes the loop.
TEST(ClosedLoop, SwayFrameBucklesAtKOverH) {
  const double h = 2.0, w = 1.5, k = 30.0;
  for (bool ground_link : {false, true}) {
  SCOPED_TRACE(ground_link ? "closed by the beam" : "closed through the ground");
  const Model m = read_model(sway_frame_model(h, w, k, 1.0, ground_link));
  const BucklingResult b = solve_buckling(m);
  ASSERT_EQ(b.status, BucklingStatus::Succeeded) << b.message;
  EXPECT_NEAR(b.load_factors[0], k / h, 1e-9 * k / h);
  // The sway mode: both tops move sideways alike.
  const Eigen::VectorXd& phi = b.modes[0];
  EXPECT_NEAR(phi[6 * m.find_node("T1")], phi[6 * m.find_node("T2")], 1e-9);
  EXPECT_NEAR(std::abs(phi[6 * m.find_node("T1")]), 1.0, 1e-12);
  }
}

// Over-constrained loops are solved exactly and their redundant rows named as statically
// indeterminate (three out-of-plane rows for a planar loop of parallel revolute axes); the released
// model has none. The crank then carries k theta = F dx_C/dtheta (virtual work, linear).
TEST(ClosedLoop, LinearStaticNamesTheStaticallyIndeterminateRows) {
  const FourBar fb;
  const double F = 0.01;
  for (bool ground_link : {false, true})
    for (bool released : {false, true}) {
      SCOPED_TRACE(::testing::Message() << "ground link " << ground_link << ", released " << released);
      json d = four_bar_model(fb, ground_link, released);
      d["loads"] = json::array({load("C", F, 0, 0)});
      const Model m = read_model(d);
      const LinearStaticResult r = solve_linear_static(m);
      ASSERT_EQ(r.status, SolveStatus::Succeeded) << r.message;
      EXPECT_EQ(r.statically_indeterminate.size(), released ? 0u : 3u);
      const DofMap map(m);
      const double theta = r.u[map.raw_joint(m.find_joint("jA"), 0)];
      EXPECT_NEAR(fb.k * theta, F * fb.dC(fb.theta0).x(), 1e-12 * F);
    }
}

// A loop that cannot close is bad input naming the link: the two ends of a rigid link that closes a
// loop (the four-bar's coupler, with the ground link) prescribed apart.
TEST(ClosedLoop, InconsistentPrescribedValuesOnALoopNameTheLink) {
  json d = four_bar_model(FourBar{}, true, false);
  d["prescribed"] = json::array({{{"node", "D"}, {"dof", "ux"}, {"value", 0.01}}});
  d["supports"] = json::array({fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"})});
  d["loads"] = json::array({load("C", 1, 0, 0)});
  const Model m = read_model(d);
  try {
    solve_linear_static(m);
    FAIL() << "an inconsistent prescription was accepted";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("element 'ground'"), std::string::npos) << e.what();
  }
}

}  // namespace closed_loop_test
