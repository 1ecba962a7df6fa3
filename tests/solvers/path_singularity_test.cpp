// Singular poses of closed loops along a path (solvers/path/singularity.hpp): located, reported as
// "singularity" critical points naming the loop's passive joints, passed where the path goes on, or
// the path's end; against equilibria and kinematics computed here.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "loop_models.hpp"
#include "solvers/path_following.hpp"

namespace path_singularity_test {

using namespace beamfea;
using namespace beamfea::test;

namespace {

using Vec2 = Eigen::Vector2d;

// Bu's planar 3-RRR at pose P1 (W. Bu, "On the Stiffness Affected by the Allocation of Actuators of a
// Parallel Manipulator", Open Mech. Eng. J., 2012, Fig. 8): base J1 = (-0.5, 0), J6 = (0.5, 0); links
// J1J2 0.9, J2J3 1.0, platform J3J4 0.8 with P = (0, 1.1) at its middle, J4J5 1.0, J5J6 0.6; both
// elbows outward; actuator springs k = 1 at J1 J2 J3, J4 J5 J6 passive.
struct Bu {
  double l12 = 0.9, l23 = 1.0, l34 = 0.8, l45 = 1.0, l56 = 0.6, k = 1.0;
  Vec2 J1{-0.5, 0.0}, J6{0.5, 0.0}, P{0.0, 1.1};
  Vec2 J3() const { return P - Vec2(0.5 * l34, 0.0); }
  Vec2 J4() const { return P + Vec2(0.5 * l34, 0.0); }
  Vec2 J2() const { return circle_intersection(J1, l12, J3(), l23); }  // left of J1 -> J3: outward
  Vec2 J5() const { return circle_intersection(J4(), l45, J6, l56); }  // left of J4 -> J6: outward
};

json bu_model(const Bu& bu) {
  const std::vector<std::pair<std::string, Vec2>> pts = {{"J1", bu.J1},   {"J2", bu.J2()}, {"J3", bu.J3()},
                                                         {"J4", bu.J4()}, {"J5", bu.J5()}, {"J6", bu.J6}};
  json d;
  d["nodes"] = json::array();
  d["joints"] = json::array();
  for (const auto& [id, p] : pts) {
    d["nodes"].push_back({{"id", id + "a"}, {"xyz", xyz(p.x(), p.y())}});
    d["nodes"].push_back({{"id", id + "b"}, {"xyz", xyz(p.x(), p.y())}});
    const bool active = id == "J1" || id == "J2" || id == "J3";
    d["joints"].push_back({{"id", id}, {"type", "revolute"}, {"nodes", {id + "a", id + "b"}},
                           {"axes", {json::array({0, 0, 1})}}, {"stiffness", {active ? bu.k : 0.0}}});
  }
  d["nodes"].push_back({{"id", "P"}, {"xyz", xyz(bu.P.x(), bu.P.y())}});
  d["elements"] = json::array();
  for (const auto& [id, a, b] : std::vector<std::array<std::string, 3>>{{"J1J2", "J1b", "J2a"}, {"J2J3", "J2b", "J3a"},
                                                                         {"J3P", "J3b", "P"},    {"PJ4", "P", "J4a"},
                                                                         {"J4J5", "J4b", "J5a"}, {"J5J6", "J5b", "J6a"}})
    d["elements"].push_back({{"id", id}, {"type", "rigid"}, {"nodes", {a, b}}});
  d["supports"] = json::array({fix("J1a", {"ux", "uy", "uz", "rx", "ry", "rz"}),
                               fix("J6b", {"ux", "uy", "uz", "rx", "ry", "rz"})});
  d["loads"] = json::array({load("P", 0.0, -1.0, 0.0)});
  return d;
}

Vec2 dir(double a) { return {std::cos(a), std::sin(a)}; }

// The serial chain J1 J2 J3 + platform alone (the passive dyad carries no force before it folds):
// absolute link angles a = q0 + cumulative joint rotations; the equilibrium under the force (0, -f)
// at P is k dq_i = -f (P - J_i)_x (virtual work, Bu eq. 21's columns [1, -r_y, r_x]), solved by
// Newton with central differences. Returns J4 there.
struct Chain {
  Bu bu;
  Eigen::Vector3d q0;  // absolute angles of J1J2, J2J3 and the platform at the reference
  explicit Chain(const Bu& b) : bu(b) {
    const Vec2 d12 = bu.J2() - bu.J1, d23 = bu.J3() - bu.J2();
    q0 << std::atan2(d12.y(), d12.x()), std::atan2(d23.y(), d23.x()), 0.0;
  }
  // Joint positions J1, J2, J3, P, J4 for joint rotations dq.
  std::array<Vec2, 5> pose(const Eigen::Vector3d& dq) const {
    const double a1 = q0[0] + dq[0], a2 = q0[1] + dq[0] + dq[1], a3 = q0[2] + dq[0] + dq[1] + dq[2];
    const Vec2 J2 = bu.J1 + bu.l12 * dir(a1), J3 = J2 + bu.l23 * dir(a2);
    return {bu.J1, J2, J3, J3 + 0.5 * bu.l34 * dir(a3), J3 + bu.l34 * dir(a3)};
  }
  Eigen::Vector3d residual(const Eigen::Vector3d& dq, double f) const {
    const auto p = pose(dq);
    Eigen::Vector3d r;
    for (int i = 0; i < 3; ++i) r[i] = bu.k * dq[i] + f * (p[3] - p[i]).x();
    return r;
  }
  Eigen::Vector3d equilibrium(double f) const {
    Eigen::Vector3d dq = Eigen::Vector3d::Zero();
    for (int it = 0; it < 50; ++it) {
      const Eigen::Vector3d r = residual(dq, f);
      if (r.norm() < 1e-14) break;
      Eigen::Matrix3d H;
      for (int j = 0; j < 3; ++j) {
        const Eigen::Vector3d e = 1e-6 * Eigen::Vector3d::Unit(j);
        H.col(j) = (residual(dq + e, f) - residual(dq - e, f)) / 2e-6;
      }
      dq -= H.lu().solve(r);
    }
    return dq;
  }
  // |J4 J6| under the force f: the dyad straightens at l45 + l56 and folds at |l45 - l56|.
  double reach(double f) const { return (pose(equilibrium(f))[4] - bu.J6).norm(); }
  // The smallest force at which the dyad straightens or folds: scanned in steps of 0.01, then bisected.
  double fold_force() const {
    const double outer = bu.l45 + bu.l56, inner = std::abs(bu.l45 - bu.l56);
    const auto outside = [&](double f) { const double d = reach(f); return d >= outer || d <= inner; };
    double lo = 0.0, hi = 0.01;
    while (!outside(hi) && hi < 10.0) lo = hi, hi += 0.01;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (outside(mid) ? hi : lo) = mid;
    }
    return 0.5 * (lo + hi);
  }
};

std::vector<std::string> joint_ids(const Model& m, const std::vector<int>& joints) {
  std::vector<std::string> out;
  for (int j : joints) out.push_back(m.joints[j].id);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

// Bu's lumped 3-RRR at P1 under a growing downward force on the platform: the path ends where the
// passive dyad J4-J5-J6 straightens, reported as a singularity naming J4 J5 J6 (not as "no
// convergence"), at the load factor where the serial chain's own equilibrium brings |J4 J6| to the
// dyad's reach (found here by bisection on the load).
TEST(PathSingularity, BuDyadStraightensUnderPlatformLoad) {
  const Bu bu;
  const Model m = read_model(bu_model(bu));
  PathOptions o;
  o.control = PathControl::LoadFactor;
  o.target = 1.0;
  o.increments = 20;
  o.track = {m.find_node("P")};
  const PathResult r = follow_path(m, o);
  EXPECT_EQ(r.termination, PathTermination::Singularity) << r.brief_report();
  EXPECT_FALSE(r.completed);
  ASSERT_FALSE(r.critical_points.empty());
  const CriticalPoint& c = r.critical_points.back();
  EXPECT_EQ(c.type, CriticalPointType::Singularity);
  EXPECT_FALSE(c.passed);
  EXPECT_EQ(joint_ids(m, c.joints), (std::vector<std::string>{"J4", "J5", "J6"}));
  EXPECT_EQ(c.nodes.size(), 6u);
  EXPECT_DOUBLE_EQ(c.control, c.load_factor);  // load control: the control is the load factor

  // The reference: the load factor where the serial chain's equilibrium reaches the dyad's bound.
  const Chain chain(bu);
  const double f_star = chain.fold_force();
  ASSERT_LT(f_star, 1.0);
  EXPECT_NEAR(c.load_factor, f_star, 1e-4 * f_star);
  // Before the fold the path is the serial chain's equilibrium: P where the chain puts it.
  double worst = 0.0;
  for (const auto& st : r.steps) {
    const Vec2 P = chain.pose(chain.equilibrium(st.load_factor))[3] - bu.P;
    worst = std::max(worst, (st.track[0].head<2>() - P).norm());
  }
  EXPECT_LT(worst, 1e-8);
  std::printf("Bu 3-RRR at P1: singularity at load factor %.8f (serial chain: %.8f), %zu steps, worst P error %.1e: %s\n",
              c.load_factor, f_star, r.steps.size() - 1, worst, r.brief_report().c_str());
}

// A four-bar at its change point (crank + ground = coupler + rocker: 0.3 + 0.7 = 0.5 + 0.5) driven by
// a prescribed crank rotation through theta = pi, where coupler and rocker lie on the ground line:
// the passive dyad B-C-D straightens there. The path reports the singularity at crank angle pi (the
// passive joints jB jC jD), passes it, and follows the closed-form kinematics on both sides.
TEST(PathSingularity, FourBarDrivenThroughItsTogglePosition) {
  FourBar fb;
  fb.a = 0.3, fb.g = 0.7, fb.b = 0.5, fb.c = 0.5, fb.theta0 = 2.6;
  const Model m = read_model(four_bar_model(fb, false, false));
  PathOptions o;
  o.control = PathControl::Displacement;
  o.control_node = m.find_node("A1");
  o.control_dof = 5;
  o.target = 3.6 - fb.theta0;  // past pi
  o.increments = 10;
  o.track = {m.find_node("C")};
  const PathResult r = follow_path(m, o);
  ASSERT_TRUE(r.completed) << r.brief_report();
  int singular = 0;
  for (const auto& c : r.critical_points) {
    if (c.type != CriticalPointType::Singularity) continue;
    ++singular;
    EXPECT_TRUE(c.passed);
    EXPECT_EQ(joint_ids(m, c.joints), (std::vector<std::string>{"jB", "jC", "jD"}));
    // Located to critical_tolerance of the step (0.1 rad).
    EXPECT_NEAR(c.control, M_PI - fb.theta0, 1e-3 * 0.1);
  }
  EXPECT_EQ(singular, 1);
  // Every state on the linkage: |BC| = b and |CD| = c with B at the crank's angle.
  double worst = 0.0;
  for (const auto& st : r.steps) {
    const double t = fb.theta0 + st.control;
    const Vec2 C = fb.C(fb.theta0) + st.track[0].head<2>();
    worst = std::max({worst, std::abs((C - fb.B(t)).norm() - fb.b), std::abs((C - fb.D()).norm() - fb.c)});
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_NEAR(r.steps.back().control, o.target, 1e-9);
}

// A change-point four-bar (crank 2, coupler 1, rocker 2, ground 3: shortest + longest = the other
// two) built flat, every link on the x axis: there the loop's closure row along the links vanishes to
// first order, so the rank-revealing selection at the reference drops it as redundant, but away from
// the flat pose it is independent (the coupler's length is cos-like in the angles). Solved with the
// reference's rows alone, the coupler would shorten as the linkage rises (to 0.865 of its length at
// load factor 2.7 before this was caught): the path must stop at its first step, naming the row,
// instead of reporting a loop that does not close.
TEST(PathSingularity, ARowDroppedAtAFlatReferencePoseThatDepartsStopsThePath) {
  json d;
  const auto node = [](const std::string& id, double x) { return json{{"id", id}, {"xyz", xyz(x, 0.0)}}; };
  d["nodes"] = json::array({node("A", 0), node("Ap", 0), node("B", 2), node("Bc", 2), node("C", 1), node("Cc", 1),
                            node("D", 3), node("Dp", 3), node("M", 1.5)});
  d["elements"] = json::array({{{"id", "crank"}, {"type", "rigid"}, {"nodes", {"Ap", "B"}}},
                               {{"id", "coupler"}, {"type", "rigid"}, {"nodes", {"Bc", "Cc"}}},
                               {{"id", "middle"}, {"type", "rigid"}, {"nodes", {"Bc", "M"}}},
                               {{"id", "rocker"}, {"type", "rigid"}, {"nodes", {"Dp", "C"}}}});
  const json z = json::array({0, 0, 1});
  d["joints"] = json::array({{{"id", "jA"}, {"type", "revolute"}, {"nodes", {"A", "Ap"}}, {"axes", {z}}, {"stiffness", {100.0}}},
                             {{"id", "jB"}, {"type", "revolute"}, {"nodes", {"B", "Bc"}}, {"axes", {z}}},
                             {{"id", "jC"}, {"type", "revolute"}, {"nodes", {"C", "Cc"}}, {"axes", {z}}},
                             {{"id", "jD"}, {"type", "revolute"}, {"nodes", {"D", "Dp"}}, {"axes", {z}}, {"stiffness", {100.0}}}});
  d["supports"] = json::array({fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}), fix("D", {"ux", "uy", "uz", "rx", "ry", "rz"}),
                               fix("Ap", {"uz", "rx", "ry"}), fix("Dp", {"uz", "rx", "ry"})});
  d["loads"] = json::array({load("M", 0.0, 10.0, 0.0)});
  const Model m = read_model(d);
  PathOptions o;
  o.control = PathControl::ArcLength;
  o.arc_length = 0.05;
  o.max_steps = 40;
  const PathResult r = follow_path(m, o);
  EXPECT_EQ(r.termination, PathTermination::RankChanged) << r.brief_report();
  EXPECT_FALSE(r.completed);
  EXPECT_EQ(r.steps.size(), 1u) << "a step with the loop open was taken";
  EXPECT_NE(r.brief_report().find("element 'coupler' ux"), std::string::npos) << r.brief_report();
}


// Bennett's linkage (G. T. Bennett, "A new mechanism", Engineering 76, 1903): four revolute joints in
// a spatial loop, mobile although Gruebler gives it -2 degrees of freedom. With Denavit-Hartenberg
// frames T_{i+1} = T_i Rz(theta_i) Tx(a_i) Rx(alpha_i), links a, b, a, b of twists alpha, beta,
// alpha, beta, a sin(beta) = b sin(alpha), the loop closes for theta_3 = 2 pi - theta_1,
// theta_4 = 2 pi - theta_2 and tan(theta_1 / 2) tan(theta_2 / 2) = sin((beta + alpha) / 2) /
// sin((beta - alpha) / 2) (checked here: frames(t) closes to 1e-12 for every t used).
struct Bennett {
  double a = 1.0, alpha = M_PI / 3, beta = M_PI / 2, theta0 = 100.0 * M_PI / 180.0;
  double b() const { return a * std::sin(beta) / std::sin(alpha); }
  double theta2(double t1) const {
    return 2.0 * std::atan(std::sin((beta + alpha) / 2) / std::sin((beta - alpha) / 2) / std::tan(t1 / 2));
  }
  // The frames of joints 1..4 and the closing frame (the identity when the loop closes).
  std::array<Eigen::Matrix4d, 5> frames(double t1) const {
    const double t2 = theta2(t1);
    const std::array<double, 4> th{t1, t2, 2 * M_PI - t1, 2 * M_PI - t2}, len{a, b(), a, b()}, tw{alpha, beta, alpha, beta};
    std::array<Eigen::Matrix4d, 5> F;
    F[0].setIdentity();
    for (int i = 0; i < 4; ++i) {
      Eigen::Matrix4d Rz = Eigen::Matrix4d::Identity(), Tx = Eigen::Matrix4d::Identity(), Rx = Eigen::Matrix4d::Identity();
      Rz.topLeftCorner<2, 2>() << std::cos(th[i]), -std::sin(th[i]), std::sin(th[i]), std::cos(th[i]);
      Tx(0, 3) = len[i];
      Rx.block<2, 2>(1, 1) << std::cos(tw[i]), -std::sin(tw[i]), std::sin(tw[i]), std::cos(tw[i]);
      F[i + 1] = F[i] * Rz * Tx * Rx;
    }
    return F;
  }
  Eigen::Vector3d joint(int i, double t1) const { return frames(t1)[i].topRightCorner<3, 1>(); }
  Eigen::Vector3d axis(int i, double t1) const { return frames(t1)[i].block<3, 1>(0, 2); }
  // The middle of link 2 (joints 2 and 3), where the force acts.
  Eigen::Vector3d middle(double t1) const { return 0.5 * (joint(1, t1) + joint(2, t1)); }
};

// Ground link 4 (joints 4 and 1) fixed, a spring k at joint 1, joints 2-4 passive; the load: a moment
// k about joint 1's axis on link 1 and a force f on the middle of link 2. The linkage has one degree
// of freedom theta_1, so equilibrium is one equation (virtual work): k (theta_1 - theta_0) =
// lambda (k + f . dM/dtheta_1).
json bennett_model(const Bennett& be, double k, const Eigen::Vector3d& f, double lambda_end, int increments) {
  const double t = be.theta0;
  const auto p = [](const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); };
  json d;
  d["nodes"] = json::array({{{"id", "J1g"}, {"xyz", p(be.joint(0, t))}}, {{"id", "J1l"}, {"xyz", p(be.joint(0, t))}},
                            {{"id", "J2a"}, {"xyz", p(be.joint(1, t))}}, {{"id", "J2b"}, {"xyz", p(be.joint(1, t))}},
                            {{"id", "J3a"}, {"xyz", p(be.joint(2, t))}}, {{"id", "J3b"}, {"xyz", p(be.joint(2, t))}},
                            {{"id", "J4a"}, {"xyz", p(be.joint(3, t))}}, {{"id", "J4g"}, {"xyz", p(be.joint(3, t))}},
                            {{"id", "M"}, {"xyz", p(be.middle(t))}}});
  d["elements"] = json::array({{{"id", "l1"}, {"type", "rigid"}, {"nodes", {"J1l", "J2a"}}},
                               {{"id", "l2"}, {"type", "rigid"}, {"nodes", {"J2b", "J3a"}}},
                               {{"id", "l2m"}, {"type", "rigid"}, {"nodes", {"J2b", "M"}}},
                               {{"id", "l3"}, {"type", "rigid"}, {"nodes", {"J3b", "J4a"}}}});
  const auto joint = [&](const std::string& id, const std::string& n0, const std::string& n1, int i) {
    json j{{"id", id}, {"type", "revolute"}, {"nodes", {n0, n1}}, {"axes", {p(be.axis(i, t))}}};
    if (i == 0) j["stiffness"] = {k};
    return j;
  };
  d["joints"] = json::array({joint("j1", "J1g", "J1l", 0), joint("j2", "J2a", "J2b", 1), joint("j3", "J3a", "J3b", 2),
                             joint("j4", "J4a", "J4g", 3)});
  d["supports"] = json::array({fix("J1g", {"ux", "uy", "uz", "rx", "ry", "rz"}), fix("J4g", {"ux", "uy", "uz", "rx", "ry", "rz"})});
  const Eigen::Vector3d m = k * be.axis(0, t);
  d["loads"] = json::array({load("J1l", 0, 0, 0, m.x(), m.y(), m.z()), load("M", f.x(), f.y(), f.z())});
  d["analyses"] = json::array({{{"id", "p"}, {"type", "path"}, {"track", {"J3a", "M"}},
                                {"control", {{"load_factor", lambda_end}, {"increments", increments}}}}});
  return d;
}

// The virtual-work residual of equilibrium at theta_1 under the load factor lambda, over k (dM/dtheta by
// central differences of the closed-form kinematics).
double bennett_residual(const Bennett& be, double k, const Eigen::Vector3d& f, double lambda, double t) {
  const Eigen::Vector3d dM = (be.middle(t + 1e-6) - be.middle(t - 1e-6)) / 2e-6;
  return (k * (t - be.theta0) - lambda * (k + f.dot(dM))) / k;
}

// The load factor of the Bennett paths: 150 degrees of joint 1 under the moment alone.
constexpr double kBennettLoadFactor = 150.0 * M_PI / 180.0;

// The rank-revealing choice of three of the closure's six rows at the reference (100 degrees) keeps
// its three rotation rows, which lose rank at theta_1 = 180 degrees (the four joint axes fall into
// one plane there, beta = 90 degrees) while the loop's six rows keep rank three: a pose the linkage
// passes smoothly, and where its passive Jacobian keeps full rank. The path must choose its rows
// afresh (and say which it drops from that step on), report no singular pose (the passive Jacobian
// restricted to the rotation rows changes sign there: three passive axes in a plane), and follow the
// linkage to 240 degrees with the loop closed and in equilibrium.
// `control`: the path's control (the load factor to 150 degrees' worth, or an arc length stopped there).
void expect_bennett_followed(const PathOptions& control) {
  const Bennett be;
  for (double t : {be.theta0, M_PI, 250.0 * M_PI / 180.0})
    ASSERT_LT((be.frames(t)[4] - Eigen::Matrix4d::Identity()).cwiseAbs().maxCoeff(), 1e-12);
  const double k = 10.0;
  const Eigen::Vector3d f(0.0, 0.0, -2.0);
  const Model m = read_model(bennett_model(be, k, f, kBennettLoadFactor, 30));
  PathOptions o = control;
  o.track = {m.find_node("J3a"), m.find_node("M"), m.find_node("J1l")};
  o.stability = true;
  const PathResult r = follow_path(m, o);
  ASSERT_TRUE(r.completed) << r.brief_report();
  EXPECT_EQ(r.statically_indeterminate.size(), 3u);
  for (const auto& c : r.critical_points) EXPECT_NE(c.type, CriticalPointType::Singularity) << c.what;
  int changes = 0;
  double worst = 0.0, worst_residual = 0.0, theta_end = 0.0;
  for (const auto& st : r.steps) {
    // Joint 1's axis is z: its angle is the rotation of link 1 about z.
    const double t = be.theta0 + st.track[2][5];
    worst_residual = std::max(worst_residual, std::abs(bennett_residual(be, k, f, st.load_factor, t)));
    worst = std::max({worst, (be.joint(2, be.theta0) + st.track[0].head<3>() - be.joint(2, t)).norm(),
                      (be.middle(be.theta0) + st.track[1].head<3>() - be.middle(t)).norm()});
    if (st.statically_indeterminate) {
      ++changes;
      EXPECT_EQ(st.statically_indeterminate->size(), 3u);
      // The first change leaves the reference's rows (later ones may return to them).
      if (changes == 1) {
        EXPECT_NE(*st.statically_indeterminate, r.statically_indeterminate) << "step " << st.step;
      }
    }
    theta_end = t;
  }
  EXPECT_GE(changes, 1);
  // Newton's tolerance is 1e-9 of the model length (about 2) and of the force scale.
  EXPECT_LT(worst, 1e-7);
  EXPECT_LT(worst_residual, 1e-6);
  EXPECT_GT(theta_end, 240.0 * M_PI / 180.0);
}

TEST(PathRedundancy, ABennettLinkageHasItsRedundantRowsChosenAfreshWhereTheReferencesLoseRank) {
  PathOptions o;
  o.control = PathControl::LoadFactor;
  o.target = kBennettLoadFactor;
  o.increments = 30;
  expect_bennett_followed(o);
}

// The same under an automatic arc length: a model of rigid links and joints has no free translation,
// so its scales come from the rotation per unit load factor.
TEST(PathRedundancy, ABennettLinkageUnderAnAutomaticArcLength) {
  PathOptions o;
  o.control = PathControl::ArcLength;
  o.arc_length_auto = true;
  o.stop_load_factor = kBennettLoadFactor;
  expect_bennett_followed(o);
}

// Other Bennett linkages (twists 60 and 75 or 120 degrees), built at 30, 100 and 250 degrees and turned
// 300 degrees by the moment alone (theta_1 = theta_0 + lambda, the passive joints unloaded), under an
// automatic arc length: the closed form has no singular pose (the passive Jacobian over the six rows
// keeps full rank), and none may be reported however the rows kept turn; every state on the linkage.
TEST(PathRedundancy, BennettLinkagesOfOtherTwistsReportNoSingularPose) {
  for (double beta_deg : {75.0, 120.0})
    for (double theta0_deg : {30.0, 100.0, 250.0}) {
      Bennett be;
      be.beta = beta_deg * M_PI / 180.0;
      be.theta0 = theta0_deg * M_PI / 180.0;
      const double turn = 300.0 * M_PI / 180.0;
      const Model m = read_model(bennett_model(be, 10.0, Eigen::Vector3d::Zero(), turn, 40));
      PathOptions o;
      o.control = PathControl::ArcLength;
      o.arc_length_auto = true;
      o.stop_load_factor = turn;
      o.track = {m.find_node("J3a")};
      const PathResult r = follow_path(m, o);
      const std::string what = fmt::format("beta {} theta0 {}", beta_deg, theta0_deg);
      ASSERT_TRUE(r.completed) << what << ": " << r.brief_report();
      for (const auto& c : r.critical_points) EXPECT_NE(c.type, CriticalPointType::Singularity) << what << ": " << c.what;
      double worst = 0.0;
      for (const auto& st : r.steps)
        worst = std::max(worst, (be.joint(2, be.theta0) + st.track[0].head<3>() - be.joint(2, be.theta0 + st.load_factor)).norm());
      EXPECT_LT(worst, 1e-7) << what;
    }
}

}  // namespace path_singularity_test
