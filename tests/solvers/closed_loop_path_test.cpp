// Closed kinematic loops in path following (solvers/path_following.hpp): closures as nonlinear
// equality constraints with multipliers, redundant rows dropped, stability on the null space of the
// independent constraints, loaded compliance of any node; against closed forms computed here.
#include <gtest/gtest.h>

#include <cstdio>

#include "solvers/path_following.hpp"
#include "loop_models.hpp"

namespace closed_loop_path_test {

using namespace beamfea;
using namespace beamfea::test;

// Four-bar with a crank spring k under a horizontal force F at the coupler point C: at every
// converged step the virtual work gives k theta = lambda F dx_C/dtheta (theta the crank rotation,
// dx_C/dtheta from the closed-form kinematics at theta0 + theta), and C lies where the closed-form
// kinematics puts it. Crank rotations beyond 0.5 rad. All four models (closed through the ground or
// by a rigid link; parallel axes with three redundant rows, or released) give the same answers.
TEST(ClosedLoopPath, FourBarSatisfiesVirtualWorkAtEveryStep) {
  const FourBar fb;
  const double F = 12.0;
  std::vector<double> final_theta;
  for (bool ground_link : {false, true})
    for (bool released : {false, true}) {
      SCOPED_TRACE(::testing::Message() << "ground link " << ground_link << ", released " << released);
      json d = four_bar_model(fb, ground_link, released);
      d["loads"] = json::array({load("C", F, 0, 0)});
      const Model m = read_model(d);
      PathOptions o;
      o.control = PathControl::LoadFactor;
      o.target = 1.0;
      o.increments = 10;
      o.track = {m.find_node("C")};
      o.stiffness_node = m.find_node("C");
      const PathResult r = follow_path(m, o);
      ASSERT_TRUE(r.completed) << r.brief_report();
      ASSERT_GE(r.steps.size(), 5u);
      const int jA = m.find_joint("jA");
      double worst_vw = 0.0, worst_pos = 0.0;
      for (const auto& st : r.steps) {
        const double th = st.state.q[jA][0];
        const double t = fb.theta0 + th;
        worst_vw = std::max(worst_vw, std::abs(fb.k * th - st.load_factor * F * fb.dC(t).x()) / (fb.k * 0.5));
        const Eigen::Vector2d C = fb.C(t) - fb.C(fb.theta0);
        worst_pos = std::max(worst_pos, (st.track[0].head<2>() - C).norm() + std::abs(st.track[0][2]));
        EXPECT_TRUE(st.stable);
      }
      EXPECT_LT(worst_vw, 1e-8);
      EXPECT_LT(worst_pos, 1e-9);
      const double th = r.steps.back().state.q[jA][0];
      EXPECT_GT(std::abs(th), 0.5);
      std::printf("four-bar (ground link %d, released %d): %zu steps, final crank rotation %.6f rad, worst virtual-work "
                  "residual %.2e, worst position error %.2e\n",
                  ground_link, released, r.steps.size() - 1, th, worst_vw, worst_pos);
      final_theta.push_back(th);
      if (released) EXPECT_TRUE(r.statically_indeterminate.empty());
      else EXPECT_EQ(r.statically_indeterminate.size(), 3u);
    }
  for (double th : final_theta) EXPECT_NEAR(th, final_theta[0], 1e-10);
}

// Five-bar under a force at the end point E: the equilibrium and the loaded compliance at every step
// equal the exact equilibrium k_i (q_i - q_i0) = (J^T F)_i solved here, and its derivative in F by
// central differences (the loaded compliance), for the loop closed through the ground and by a joint.
TEST(ClosedLoopPath, FiveBarLoadedEquilibriumAndComplianceMatchTheExactEquilibrium) {
  const FiveBar fb;
  const Eigen::Vector2d F(0.8, -1.5);
  for (bool ground_link : {false, true}) {
    SCOPED_TRACE(ground_link ? "joint closure" : "closed through the ground");
    json d = five_bar_model(fb, ground_link);
    d["loads"] = json::array({load("E", F.x(), F.y(), 0)});
    const Model m = read_model(d);
    PathOptions o;
    o.target = 1.0;
    o.increments = 5;
    o.track = {m.find_node("E")};
    o.stiffness_node = m.find_node("E");
    const PathResult r = follow_path(m, o);
    ASSERT_TRUE(r.completed) << r.brief_report();
    const Eigen::Vector2d E0 = fb.E(fb.q1, fb.q2);
    double worst_e = 0.0, worst_c = 0.0;
    for (const auto& st : r.steps) {
      const Eigen::Vector2d Fl = st.load_factor * F;
      const Eigen::Vector2d q = fb.equilibrium(Fl);
      worst_e = std::max(worst_e, (st.track[0].head<2>() - (fb.E(q[0], q[1]) - E0)).norm());
      Eigen::Matrix2d Cx;
      const double h = 1e-4;
      for (int j = 0; j < 2; ++j) {
        Eigen::Vector2d dF = Eigen::Vector2d::Zero();
        dF[j] = h;
        const Eigen::Vector2d qp = fb.equilibrium(Fl + dF), qm = fb.equilibrium(Fl - dF);
        Cx.col(j) = (fb.E(qp[0], qp[1]) - fb.E(qm[0], qm[1])) / (2 * h);
      }
      ASSERT_TRUE(st.node_stiffness.has_value());
      worst_c = std::max(worst_c, (st.node_stiffness->compliance.topLeftCorner<2, 2>() - Cx).norm() / Cx.norm());
      EXPECT_EQ(st.node_stiffness->rigid_directions.size(), 4u);
    }
    EXPECT_LT(worst_e, 1e-9);
    EXPECT_LT(worst_c, 1e-6);
    std::printf("five-bar (ground link %d): %zu steps, worst end-point error %.2e, worst loaded-compliance error %.2e\n",
                ground_link, r.steps.size() - 1, worst_e, worst_c);
  }
}

// Sway frame of rigid columns on base springs tied by a pinned rigid beam: a bifurcation at the load
// factor k / (h P); after branch switching, P lambda = k theta / (h sin theta) on a stable branch.
TEST(ClosedLoopPath, SwayFramePostBucklingAfterBranchSwitching) {
  const double h = 2.0, w = 1.5, k = 30.0, P = 10.0;  // critical load factor k / (h P) = 1.5
  for (bool ground_link : {false, true}) {
    SCOPED_TRACE(ground_link ? "closed by the beam" : "closed through the ground");
    const Model m = read_model(sway_frame_model(h, w, k, P, ground_link));
    PathOptions o;
    o.control = PathControl::ArcLength;
    o.arc_length = 0.3;
    o.max_arc_length = 0.3;
    o.branch_switch = true;
    o.stop_steps = 40;
    o.track = {m.find_node("T1")};
    const PathResult r = follow_path(m, o);
    ASSERT_FALSE(r.critical_points.empty()) << r.brief_report();
    const auto& cp = r.critical_points.front();
    EXPECT_EQ(std::string(to_string(cp.type)), "bifurcation");
    EXPECT_NEAR(cp.load_factor, k / (h * P), 2e-3 * k / (h * P));
    EXPECT_TRUE(cp.branch_switched);
    const int base = m.find_joint("base1");
    int post = 0;
    double worst = 0.0, max_theta = 0.0;
    for (const auto& st : r.steps) {
      const double th = st.state.q[base][0];
      if (std::abs(th) < 0.05) continue;
      ++post;
      max_theta = std::max(max_theta, std::abs(th));
      worst = std::max(worst, std::abs(P * st.load_factor - k * th / (h * std::sin(th))) / (k / h));
      EXPECT_TRUE(st.stable) << "theta " << th;
    }
    EXPECT_GE(post, 5);
    EXPECT_GT(max_theta, 0.5);
    EXPECT_LT(worst, 1e-8);
    std::printf("sway frame (ground link %d): critical load factor %.6f (k/(hP) = %.6f), %d post-buckling steps up to "
                "theta %.3f, worst |P lambda - k theta/(h sin theta)|/(k/h) %.2e\n",
                ground_link, cp.load_factor, k / (h * P), post, max_theta, worst);
  }
}

}  // namespace closed_loop_path_test
