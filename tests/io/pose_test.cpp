// Poses (solvers/pose.hpp, docs/poses.md): a model moved to joint coordinates or node targets by exact
// rigid-body kinematics, then analysed about the posed geometry.
//
// 1. A planar two-link arm with revolute joint springs k1, k2 and flexible links (Euler-Bernoulli
//    beams), posed by joint angles only. Its in-plane tip compliance (ux, uy, rz) is the sum over
//    the joints and the links of B^T c B: B carries the tip's wrench to the joint or the link's end
//    (M_end = M + r x F, r = tip - end), c = 1/k about z for a joint, R c_beam R^T for a link with the
//    cantilever compliance c_beam = [[L/EA, 0, 0], [0, L^3/3EI, L^2/2EI], [0, L^2/2EI, L/EI]]
//    (Gere & Timoshenko, Mechanics of Materials, tip load and tip moment). The joint terms are
//    J K^-1 J^T with J's columns (-(r_y), r_x, 1).
// 2. A five-bar (two cranks on revolute actuators, two distal links, passive elbows and end joint)
//    driven by its end point E: the solved actuator angles equal the closed-form inverse kinematics
//    (each leg's crank angle alpha +/- beta by the law of cosines, the sign of the reference's
//    assembly), and with rigid links E's translational compliance equals J K^-1 J^T with J the
//    inverse of the inverse kinematics' Jacobian (central differences of the closed form).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "io/run.hpp"
#include "solvers/pose.hpp"

namespace pose_test {

using nlohmann::json;

// Two-link arm: ground G, shoulder q1 at the origin, link1 along x (length L1), elbow q2, link2 (L2).
constexpr double L1 = 0.4, L2 = 0.3, E = 7.0e10, A = 8.0e-4, I = 1.1e-7, k1 = 2000.0, k2 = 1000.0;

json two_link_arm() {
  return json{
      {"nodes", {{{"id", "G"}, {"xyz", {0, 0, 0}}}, {{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "E1"}, {"xyz", {L1, 0, 0}}},
                 {{"id", "E2"}, {"xyz", {L1, 0, 0}}}, {{"id", "T"}, {"xyz", {L1 + L2, 0, 0}}}}},
      {"materials", {{{"id", "al"}, {"E", E}, {"G", E / 2.6}}}},
      {"sections", {{{"id", "s"}, {"A", A}, {"Iy", I}, {"Iz", I}, {"J", 2 * I}}}},
      {"elements",
       {{{"id", "link1"}, {"type", "beam"}, {"nodes", {"A", "E1"}}, {"material", "al"}, {"section", "s"}},
        {{"id", "link2"}, {"type", "beam"}, {"nodes", {"E2", "T"}}, {"material", "al"}, {"section", "s"}}}},
      {"joints",
       {{{"id", "q1"}, {"type", "revolute"}, {"nodes", {"G", "A"}}, {"axes", {{0, 0, 1}}}, {"stiffness", {k1}}},
        {{"id", "q2"}, {"type", "revolute"}, {"nodes", {"E1", "E2"}}, {"axes", {{0, 0, 1}}}, {"stiffness", {k2}}}}},
      {"supports", {{{"node", "G"}, {"fix", "all"}}}},
      {"analyses", {{{"id", "K"}, {"type", "stiffness"}, {"node", "T"}}}}};
}

beamfea::ojson run(const json& doc) {
  const beamfea::Model model = beamfea::load_and_check(doc);
  beamfea::RunReport report = beamfea::run_document(model, doc, {});
  EXPECT_FALSE(report.failed) << report.results.dump();
  return report.results;
}

// The planar transfer of a tip wrench (Fx, Fy, Mz) to a point at r from the tip's side.
Eigen::Matrix3d transfer(const Eigen::Vector2d& r) {
  Eigen::Matrix3d B = Eigen::Matrix3d::Identity();
  B(2, 0) = -r.y();
  B(2, 1) = r.x();
  return B;
}

Eigen::Matrix3d cantilever(double L) {
  Eigen::Matrix3d c;
  c << L / (E * A), 0, 0, 0, L * L * L / (3 * E * I), L * L / (2 * E * I), 0, L * L / (2 * E * I), L / (E * I);
  return c;
}

Eigen::Matrix3d planar_rotation(double phi) {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  R.topLeftCorner<2, 2>() << std::cos(phi), -std::sin(phi), std::sin(phi), std::cos(phi);
  return R;
}

TEST(Pose, TwoLinkArmTipComplianceAtJointAnglesIsJointSpringsPlusCantilevers) {
  for (const auto& [t1, t2] : {std::pair{0.3, 0.8}, {-1.0, 1.5}, {2.0, -2.2}, {0.0, 0.0}}) {
    json doc = two_link_arm();
    doc["pose"] = {{"joints", {{"q1", t1}, {"q2", t2}}}};
    const beamfea::ojson res = run(doc);
    // Forward kinematics of the posed nodes.
    const Eigen::Vector2d e1(L1 * std::cos(t1), L1 * std::sin(t1));
    const Eigen::Vector2d tip = e1 + Eigen::Vector2d(L2 * std::cos(t1 + t2), L2 * std::sin(t1 + t2));
    EXPECT_NEAR(res["pose"]["joints"]["q1"].get<double>(), t1, 1e-15);
    EXPECT_NEAR(res["pose"]["joints"]["q2"].get<double>(), t2, 1e-15);
    for (int i = 0; i < 2; ++i) {
      EXPECT_NEAR(res["pose"]["nodes"]["T"][i].get<double>(), tip[i], 1e-14);
      EXPECT_NEAR(res["pose"]["nodes"]["E2"][i].get<double>(), e1[i], 1e-14);
    }
    // Closed-form compliance over (ux, uy, rz).
    const Eigen::Vector3d ez(0, 0, 1);
    Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
    auto add = [&](const Eigen::Vector2d& at, const Eigen::Matrix3d& c) {
      const Eigen::Matrix3d B = transfer(tip - at);
      C += B.transpose() * c * B;
    };
    add(Eigen::Vector2d::Zero(), ez * ez.transpose() / k1);
    add(e1, ez * ez.transpose() / k2);
    add(e1, planar_rotation(t1) * cantilever(L1) * planar_rotation(t1).transpose());
    add(tip, planar_rotation(t1 + t2) * cantilever(L2) * planar_rotation(t1 + t2).transpose());
    const auto& K = res["analyses"]["K"];
    ASSERT_EQ(K["status"], "ok") << K.dump();
    const int dof[3] = {0, 1, 5};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(K["compliance"][dof[r]][dof[c]].get<double>(), C(r, c), 1e-9 * C.cwiseAbs().maxCoeff())
            << "pose (" << t1 << ", " << t2 << ") entry " << r << "," << c;
  }
}

// Five-bar: bases B1 = (0, 0), B2 = (d, 0); cranks a, distal links b; reference end point E0.
constexpr double d = 0.2, a = 0.15, b = 0.25, ka1 = 500.0, ka2 = 800.0;
const Eigen::Vector2d B[2] = {{0.0, 0.0}, {d, 0.0}};
const Eigen::Vector2d E0(0.1, 0.25);
const double kSign[2] = {1.0, -1.0};  // leg 1 elbow out to the left, leg 2 to the right

// Crank angle of leg i for end point e: alpha + sign beta (law of cosines).
double crank_angle(int i, const Eigen::Vector2d& e) {
  const Eigen::Vector2d D = e - B[i];
  const double delta = D.norm();
  const double beta = std::acos((a * a + delta * delta - b * b) / (2 * a * delta));
  return std::atan2(D.y(), D.x()) + kSign[i] * beta;
}

json five_bar(bool rigid) {
  json nodes = json::array(), elements = json::array(), joints = json::array(), supports = json::array();
  auto node = [&](const std::string& id, const Eigen::Vector2d& x) { nodes.push_back({{"id", id}, {"xyz", {x.x(), x.y(), 0.0}}}); };
  auto link = [&](const std::string& id, const std::string& n0, const std::string& n1) {
    json e = {{"id", id}, {"nodes", {n0, n1}}};
    if (rigid) e["type"] = "rigid";
    else e.update({{"type", "beam"}, {"material", "al"}, {"section", "s"}});
    elements.push_back(e);
  };
  auto revolute = [&](const std::string& id, const std::string& n0, const std::string& n1, double k) {
    joints.push_back({{"id", id}, {"type", "revolute"}, {"nodes", {n0, n1}}, {"axes", {{0, 0, 1}}}, {"stiffness", {k}}});
  };
  for (int i = 0; i < 2; ++i) {
    const std::string s = std::to_string(i + 1);
    const double phi = crank_angle(i, E0);
    const Eigen::Vector2d P = B[i] + a * Eigen::Vector2d(std::cos(phi), std::sin(phi));
    node("G" + s, B[i]);
    node("C" + s, B[i]);
    node("P" + s, P);
    node("D" + s, P);
    node(i == 0 ? "E" : "F", E0);
    link("crank" + s, "C" + s, "P" + s);
    link("distal" + s, "D" + s, i == 0 ? "E" : "F");
    revolute("q" + s, "G" + s, "C" + s, i == 0 ? ka1 : ka2);
    revolute("elbow" + s, "P" + s, "D" + s, 0.0);
    supports.push_back({{"node", "G" + s}, {"fix", "all"}});
  }
  revolute("end", "E", "F", 0.0);
  return json{{"nodes", nodes},
              {"materials", {{{"id", "al"}, {"E", E}, {"G", E / 2.6}}}},
              {"sections", {{{"id", "s"}, {"A", A}, {"Iy", I}, {"Iz", I}, {"J", 2 * I}}}},
              {"elements", elements},
              {"joints", joints},
              {"supports", supports},
              {"analyses", {{{"id", "K"}, {"type", "stiffness"}, {"node", "E"}}}}};
}

json target(const Eigen::Vector2d& e) { return {{"nodes", {{{"node", "E"}, {"xyz", {e.x(), e.y(), 0.0}}}}}}; }

TEST(Pose, FiveBarDrivenByItsEndPointSolvesTheClosedFormInverseKinematics) {
  for (const Eigen::Vector2d& e : {Eigen::Vector2d(0.13, 0.27), Eigen::Vector2d(0.04, 0.31), Eigen::Vector2d(0.16, 0.19),
                                   Eigen::Vector2d(-0.05, 0.22)}) {
    json doc = five_bar(false);
    doc["pose"] = target(e);
    const beamfea::ojson res = run(doc);
    for (int i = 0; i < 2; ++i) {
      const double q = crank_angle(i, e) - crank_angle(i, E0);
      EXPECT_NEAR(res["pose"]["joints"][i == 0 ? "q1" : "q2"].get<double>(), q, 1e-10) << e.transpose();
    }
    EXPECT_NEAR(res["pose"]["nodes"]["E"][0].get<double>(), e.x(), 1e-12);
    EXPECT_NEAR(res["pose"]["nodes"]["F"][1].get<double>(), e.y(), 1e-12);
    EXPECT_EQ(res["analyses"]["K"]["status"], "ok");
  }
}

TEST(Pose, ALargeMoveInManyStepsStaysOnTheReferencesBranch) {
  // End points far from E0 (the continuation takes many steps, each converged loosely but the
  // last): the crank angles are the closed form's on the reference's branch (kSign), not the
  // mirrored assembly alpha -/+ beta, which differs by 2 beta (over 0.5 rad here).
  json reference = five_bar(false);
  const beamfea::Model at_reference = beamfea::load_and_check(reference);
  for (const Eigen::Vector2d& e : {Eigen::Vector2d(-0.08, 0.16), Eigen::Vector2d(0.27, 0.2)}) {
    json doc = reference;
    doc["pose"] = target(e);
    beamfea::Pose pose = beamfea::load_and_check(doc).pose;
    pose.solved.clear();
    const beamfea::PoseSolution s = beamfea::solve_pose(at_reference, pose);
    EXPECT_GE(s.steps, 4) << e.transpose();
    for (int i = 0; i < 2; ++i) {
      const double q = crank_angle(i, e) - crank_angle(i, E0);
      EXPECT_NEAR(s.q[at_reference.find_joint(i == 0 ? "q1" : "q2")][0], q, 1e-10) << e.transpose();
    }
  }
}

TEST(Pose, FiveBarWithRigidLinksHasTheComplianceOfItsActuatorSprings) {
  const double h = 1e-6;
  for (const Eigen::Vector2d& e : {Eigen::Vector2d(0.13, 0.27), Eigen::Vector2d(0.06, 0.2)}) {
    json doc = five_bar(true);
    doc["pose"] = target(e);
    const beamfea::ojson res = run(doc);
    // dq = G dE (the inverse kinematics' Jacobian), so dE = G^-1 dq = J dq and C = J K^-1 J^T.
    Eigen::Matrix2d G;
    for (int c = 0; c < 2; ++c) {
      Eigen::Vector2d step = Eigen::Vector2d::Zero();
      step[c] = h;
      for (int i = 0; i < 2; ++i) G(i, c) = (crank_angle(i, e + step) - crank_angle(i, e - step)) / (2 * h);
    }
    const Eigen::Matrix2d J = G.inverse();
    const Eigen::Matrix2d C = J * Eigen::Vector2d(1 / ka1, 1 / ka2).asDiagonal() * J.transpose();
    const auto& K = res["analyses"]["K"];
    ASSERT_EQ(K["status"], "ok") << K.dump();
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c)
        EXPECT_NEAR(K["compliance"][r][c].get<double>(), C(r, c), 1e-6 * C.cwiseAbs().maxCoeff()) << e.transpose();
  }
}

TEST(Pose, AnArmTargetWithARotationSolvesItsThreeActuators) {
  // A three-link planar arm: the two-link arm with its elbow bent by beta0 in the reference and a
  // rigid hand of length Lh along link2 behind a wrist joint q3, driven by the hand's end H to a
  // position and an absolute hand angle phi. Closed form: the wrist W = H - Lh (cos phi, sin phi),
  // the elbow angle by the law of cosines with the reference's sign (beta0 > 0), then q1, q3.
  const double beta0 = 0.5, Lh = 0.1;
  json doc = two_link_arm();
  const Eigen::Vector2d u(std::cos(beta0), std::sin(beta0));
  const Eigen::Vector2d t0 = Eigen::Vector2d(L1, 0) + L2 * u, h0 = t0 + Lh * u;
  doc["nodes"][4]["xyz"] = {t0.x(), t0.y(), 0};
  doc["nodes"].push_back({{"id", "W1"}, {"xyz", {t0.x(), t0.y(), 0}}});
  doc["nodes"].push_back({{"id", "H"}, {"xyz", {h0.x(), h0.y(), 0}}});
  doc["elements"].push_back({{"id", "hand"}, {"type", "rigid"}, {"nodes", {"W1", "H"}}});
  doc["joints"].push_back({{"id", "q3"}, {"type", "revolute"}, {"nodes", {"T", "W1"}}, {"axes", {{0, 0, 1}}}, {"stiffness", {300}}});
  doc["analyses"][0]["node"] = "H";
  const double phi = 0.9;
  const Eigen::Vector2d h(0.35, 0.42);
  const Eigen::Matrix3d R = planar_rotation(phi - beta0);  // relative to the reference
  doc["pose"] = {{"nodes",
                  {{{"node", "H"},
                    {"xyz", {h.x(), h.y(), 0}},
                    {"rotation", {{R(0, 0), R(0, 1), 0}, {R(1, 0), R(1, 1), 0}, {0, 0, 1}}}}}}};
  const beamfea::ojson res = run(doc);
  const Eigen::Vector2d w = h - Lh * Eigen::Vector2d(std::cos(phi), std::sin(phi));
  const double elbow = std::acos((w.squaredNorm() - L1 * L1 - L2 * L2) / (2 * L1 * L2));  // > 0: the reference's
  const double q1 = std::atan2(w.y(), w.x()) - std::atan2(L2 * std::sin(elbow), L1 + L2 * std::cos(elbow));
  EXPECT_NEAR(res["pose"]["joints"]["q1"].get<double>(), q1, 1e-9);
  EXPECT_NEAR(res["pose"]["joints"]["q2"].get<double>(), elbow - beta0, 1e-9);
  EXPECT_NEAR(res["pose"]["joints"]["q3"].get<double>(), phi - q1 - elbow, 1e-9);
  EXPECT_NEAR(res["pose"]["nodes"]["H"][0].get<double>(), h.x(), 1e-12);
  EXPECT_EQ(res["analyses"]["K"]["status"], "ok");
}

TEST(Pose, ABeamsSectionTurnsWithItsBody) {
  // A cantilever along x behind a stiff revolute about x, its section stiffer in local z bending
  // (Iz = 4 Iy, orientation z). Turned by 90 degrees about x, local z points along -y: a tip force
  // along y bends it about local y, uy = P L^3 / (3 E Iy), and one along z about local z,
  // uz = P L^3 / (3 E Iz) (the joint, about the beam's axis, takes no part).
  constexpr double L = 1.2, Iy = 1e-7, Iz = 4e-7;
  json doc = {{"nodes", {{{"id", "G"}, {"xyz", {0, 0, 0}}}, {{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "T"}, {"xyz", {L, 0, 0}}}}},
              {"materials", {{{"id", "m"}, {"E", E}, {"G", E / 2.6}}}},
              {"sections", {{{"id", "s"}, {"A", A}, {"Iy", Iy}, {"Iz", Iz}, {"J", 2 * Iy}}}},
              {"elements", {{{"id", "b"}, {"type", "beam"}, {"nodes", {"A", "T"}}, {"material", "m"}, {"section", "s"}, {"orientation", {0, 0, 1}}}}},
              {"joints", {{{"id", "r"}, {"type", "revolute"}, {"nodes", {"G", "A"}}, {"axes", {{1, 0, 0}}}, {"stiffness", {1e6}}}}},
              {"supports", {{{"node", "G"}, {"fix", "all"}}}},
              {"pose", {{"joints", {{"r", M_PI / 2}}}}},
              {"analyses", {{{"id", "K"}, {"type", "stiffness"}, {"node", "T"}}}}};
  const beamfea::ojson res = run(doc);
  const auto& K = res["analyses"]["K"];
  ASSERT_EQ(K["status"], "ok") << K.dump();
  const double uy = L * L * L / (3 * E * Iy), uz = L * L * L / (3 * E * Iz);
  EXPECT_NEAR(K["compliance"][1][1].get<double>(), uy, 1e-9 * uy);
  EXPECT_NEAR(K["compliance"][2][2].get<double>(), uz, 1e-9 * uz);
}

// Bad poses: ModelError or InputError naming the joint or node.
std::string error_of(const json& doc) {
  try {
    beamfea::load_and_check(doc);
  } catch (const beamfea::Error& e) {
    return e.what();
  }
  return "";
}

TEST(Pose, BadPosesNameTheJointOrNodeAtFault) {
  json doc = five_bar(false);
  doc["pose"] = target({0.1, 2.0});
  std::string m = error_of(doc);
  EXPECT_NE(m.find("node 'E'"), std::string::npos) << m;
  EXPECT_NE(m.find("beyond reach"), std::string::npos) << m;

  // The first leg's elbow given too: its end E then runs on a circle about P1 that meets the
  // circle of radius b about P2 only at the reference and its mirror, not at a 2 rad turn.
  doc["pose"] = {{"joints", {{"q1", 0.0}, {"elbow1", 2.0}, {"q2", 0.0}}}};
  m = error_of(doc);
  EXPECT_NE(m.find("joint 'end'"), std::string::npos) << m;
  EXPECT_NE(m.find("cannot close"), std::string::npos) << m;

  doc["pose"] = {{"joints", {{"q9", 0.1}}}};
  m = error_of(doc);
  EXPECT_NE(m.find("/pose/joints/q9"), std::string::npos) << m;
  EXPECT_NE(m.find("unknown joint 'q9'"), std::string::npos) << m;

  json passive = five_bar(false);  // no actuator: the loop's five passive angles, three equations
  for (auto& j : passive["joints"]) j["stiffness"] = {0.0};
  passive["pose"] = {{"joints", json::object()}};
  m = error_of(passive);
  EXPECT_NE(m.find("does not determine"), std::string::npos) << m;
  EXPECT_NE(m.find("joint '"), std::string::npos) << m;

  json limited = five_bar(false);
  limited["joints"][0]["limits"] = {{-0.1, 0.1}};  // q1
  limited["pose"] = {{"joints", {{"q1", 0.2}}}};
  m = error_of(limited);
  EXPECT_NE(m.find("/pose/joints/q1"), std::string::npos) << m;
  EXPECT_NE(m.find("limits [-0.1, 0.1]"), std::string::npos) << m;
  limited["pose"] = target({0.2, 0.3});  // a solved coordinate beyond the limit
  m = error_of(limited);
  EXPECT_NE(m.find("joint 'q1' coordinate 0"), std::string::npos) << m;
  EXPECT_NE(m.find("outside its limits"), std::string::npos) << m;
}

}  // namespace pose_test
