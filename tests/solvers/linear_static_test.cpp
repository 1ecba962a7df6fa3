// Linear statics against closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "solvers/linear_static.hpp"
#include "support/models.hpp"

namespace linear_static_test {

using namespace beamfea;
using nlohmann::json;

namespace {
constexpr double L = 2.0, E = 2.1e11, G = 8.1e10, A = 1e-3, Iy = 2e-6, Iz = 3e-6, J = 1e-6;

LinearStaticResult solve_with_load(const json& load, int divisions = 1) {
  json doc = test::cantilever(L, E, G, A, Iy, Iz, J, divisions);
  doc["loads"].push_back(load);
  return solve_linear_static(test::model_from(doc));
}
Vec6 tip(const LinearStaticResult& r) { return r.u.segment<6>(6); }  // node B is the second node
}  // namespace

// Cantilever formulas: Timoshenko & Gere, Mechanics of Materials, Appendix G (cases 1 and 4):
// tip force P: v = P L^3 / 3EI, slope = P L^2 / 2EI; tip moment M: v = M L^2 / 2EI, slope = M L / EI.
TEST(CantileverLinearStatic, TipForceInLocalYBendsAboutZ) {
  const double P = 1000.0;
  const auto r = solve_with_load({{"node", "B"}, {"force", {0, P, 0}}});
  ASSERT_EQ(r.status, SolveStatus::Succeeded);
  EXPECT_NEAR(tip(r)[1], P * L * L * L / (3 * E * Iz), 1e-12);
  EXPECT_NEAR(tip(r)[5], P * L * L / (2 * E * Iz), 1e-12);
  EXPECT_NEAR(tip(r)[2], 0.0, 1e-15);
}

TEST(CantileverLinearStatic, TipForceInLocalZBendsAboutY) {
  const double P = -700.0;
  const auto r = solve_with_load({{"node", "B"}, {"force", {0, 0, P}}});
  EXPECT_NEAR(tip(r)[2], P * L * L * L / (3 * E * Iy), 1e-12);
  EXPECT_NEAR(tip(r)[4], -P * L * L / (2 * E * Iy), 1e-12);  // w' = -ry
}

TEST(CantileverLinearStatic, TipMomentsInBothBendingPlanes) {
  const double M = 350.0;
  const auto rz = solve_with_load({{"node", "B"}, {"moment", {0, 0, M}}});
  EXPECT_NEAR(tip(rz)[5], M * L / (E * Iz), 1e-12);
  EXPECT_NEAR(tip(rz)[1], M * L * L / (2 * E * Iz), 1e-12);
  const auto ry = solve_with_load({{"node", "B"}, {"moment", {0, M, 0}}});
  EXPECT_NEAR(tip(ry)[4], M * L / (E * Iy), 1e-12);
  EXPECT_NEAR(tip(ry)[2], -M * L * L / (2 * E * Iy), 1e-12);
}

TEST(CantileverLinearStatic, TorsionAndAxial) {
  const auto t = solve_with_load({{"node", "B"}, {"moment", {120.0, 0, 0}}});
  EXPECT_NEAR(tip(t)[3], 120.0 * L / (G * J), 1e-12);  // phi = T L / GJ
  const auto a = solve_with_load({{"node", "B"}, {"force", {5e4, 0, 0}}});
  EXPECT_NEAR(tip(a)[0], 5e4 * L / (E * A), 1e-14);    // u = P L / EA
}

TEST(CantileverLinearStatic, MeshedMemberGivesTheSameExactTipAndReactions) {
  // Euler-Bernoulli elements are exact for nodal loads: any mesh gives the closed form.
  const double P = 1000.0;
  const auto r = solve_with_load({{"node", "B"}, {"force", {0, P, 0}}}, 7);
  ASSERT_EQ(r.status, SolveStatus::Succeeded);
  const Vec6 t = r.u.segment<6>(6);
  EXPECT_NEAR(t[1], P * L * L * L / (3 * E * Iz), 1e-12);
  // Support reaction balances the load: force -P, moment -P L about z.
  EXPECT_NEAR(r.reactions[0][1], -P, 1e-6);
  EXPECT_NEAR(r.reactions[0][5], -P * L, 1e-6);
}

TEST(CantileverLinearStatic, InclinedMemberMatchesRotatedClosedForm) {
  // The same cantilever along a skew direction with a load normal to it.
  const Vec3 ex = Vec3(1, 2, 2).normalized();
  const Vec3 ez = Vec3(0, -1, 1).normalized();  // in the local x-z plane, orthogonal to ex
  const Vec3 ey = ez.cross(ex);
  json doc = test::cantilever(L, E, G, A, Iy, Iz, J);
  doc["nodes"][1]["xyz"] = {L * ex.x(), L * ex.y(), L * ex.z()};
  doc["elements"][0]["orientation"] = {ez.x(), ez.y(), ez.z()};
  const double P = 900.0;
  doc["loads"].push_back({{"node", "B"}, {"force", {P * ey.x(), P * ey.y(), P * ey.z()}}});
  const auto r = solve_linear_static(test::model_from(doc));
  const Vec3 u = r.u.segment<3>(6);
  EXPECT_NEAR(u.dot(ey), P * L * L * L / (3 * E * Iz), 1e-12);
  EXPECT_NEAR(u.dot(ez), 0.0, 1e-14);
}

// Fixed-base portal frame under a lateral load H at the beam level, axially rigid members
// (A large). Slope-deflection (e.g. Hibbeler, Structural Analysis, ch. 11), antisymmetric sway:
//   joint:  (2 a)(2 theta - 3 D/h) + 6 b theta = 0,    a = E Ic / h, b = E Ib / Lb
//   shear:  H = 2 (2 a / h)(6 D / h - 3 theta)
TEST(PortalFrame, SwayMatchesSlopeDeflection) {
  const double h = 3.0, Lb = 5.0, Ic = 4e-6, Ib = 9e-6, H = 10e3, big = 1e3;
  json doc = {
      {"nodes", json::array({{{"id", 1}, {"xyz", {0, 0, 0}}}, {{"id", 2}, {"xyz", {0, h, 0}}},
                             {{"id", 3}, {"xyz", {Lb, h, 0}}}, {{"id", 4}, {"xyz", {Lb, 0, 0}}}})},
      {"materials", json::array({{{"id", "m"}, {"E", E}, {"G", G}}})},
      {"sections", json::array({{{"id", "c"}, {"A", big}, {"Iy", Ic}, {"Iz", Ic}, {"J", J}},
                                {{"id", "b"}, {"A", big}, {"Iy", Ib}, {"Iz", Ib}, {"J", J}}})},
      {"elements", json::array({{{"id", "c1"}, {"type", "beam"}, {"nodes", {1, 2}}, {"material", "m"}, {"section", "c"}, {"orientation", {0, 0, 1}}},
                                {{"id", "bm"}, {"type", "beam"}, {"nodes", {2, 3}}, {"material", "m"}, {"section", "b"}, {"orientation", {0, 0, 1}}},
                                {{"id", "c2"}, {"type", "beam"}, {"nodes", {4, 3}}, {"material", "m"}, {"section", "c"}, {"orientation", {0, 0, 1}}}})},
      {"supports", json::array({{{"node", 1}, {"fix", "all"}}, {{"node", 4}, {"fix", "all"}}})},
      {"loads", json::array({{{"node", 2}, {"force", {H, 0, 0}}}})}};
  const auto r = solve_linear_static(test::model_from(doc));
  ASSERT_EQ(r.status, SolveStatus::Succeeded);
  const double a = E * Ic / h, b = E * Ib / Lb;
  // theta = 3 a D / (h (2a + 3b)); H = (4a/h)(6D/h - 3 theta)  =>  D = H / ((4a/h)(6/h - 9a/(h(2a+3b))))
  const double D = H / ((4 * a / h) * (6 / h - 9 * a / (h * (2 * a + 3 * b))));
  const double theta = 3 * a * D / (h * (2 * a + 3 * b));
  EXPECT_NEAR(r.u[6 * 1 + 0], D, 1e-6 * D);
  EXPECT_NEAR(r.u[6 * 2 + 0], D, 1e-6 * D);
  EXPECT_NEAR(-r.u[6 * 1 + 5], theta, 1e-5 * theta);  // clockwise joint rotation
  // Base reactions balance H.
  EXPECT_NEAR(r.reactions[0][0] + r.reactions[3][0], -H, 1e-6 * H);
}

// L-shaped space frame (two members at a right angle in the x-y plane, fixed at one end, load
// normal to the plane at the free end): bending of both members plus torsion of the first,
//   delta = P a^3 / 3EIy + P b^3 / 3EIy + P a b^2 / GJ   (Roark's Formulas, 7th ed., Table 8.1
// with the torsion of the first leg; a standard grid/frame hand calculation).
TEST(SpaceFrame, BentCantileverCombinesBendingAndTorsion) {
  const double a = 1.5, b = 1.0, P = -800.0;
  json doc = {
      {"nodes", json::array({{{"id", "O"}, {"xyz", {0, 0, 0}}}, {{"id", "K"}, {"xyz", {a, 0, 0}}}, {{"id", "C"}, {"xyz", {a, b, 0}}}})},
      {"materials", json::array({{{"id", "m"}, {"E", E}, {"G", G}}})},
      {"sections", json::array({{{"id", "s"}, {"A", A}, {"Iy", Iy}, {"Iz", Iz}, {"J", J}}})},
      {"elements", json::array({{{"id", "1"}, {"type", "beam"}, {"nodes", {"O", "K"}}, {"material", "m"}, {"section", "s"}, {"orientation", {0, 0, 1}}, {"divisions", 3}},
                                {{"id", "2"}, {"type", "beam"}, {"nodes", {"K", "C"}}, {"material", "m"}, {"section", "s"}, {"orientation", {0, 0, 1}}, {"divisions", 2}}})},
      {"supports", json::array({{{"node", "O"}, {"fix", "all"}}})},
      {"loads", json::array({{{"node", "C"}, {"force", {0, 0, P}}}})}};
  const Model m = test::model_from(doc);
  const auto r = solve_linear_static(m);
  const double expected = P * a * a * a / (3 * E * Iy) + P * b * b * b / (3 * E * Iy) + P * a * b * b / (G * J);
  EXPECT_NEAR(r.u[6 * m.find_node("C") + 2], expected, 1e-10 * std::abs(expected));
  // Torsion of the first member equals P b.
  EXPECT_NEAR(std::abs(r.end_forces[m.members[0].elements[0]][3]), std::abs(P * b), 1e-6);
}

TEST(PrescribedDisplacement, TipDisplacementGivesItsReaction) {
  json doc = test::cantilever(L, E, G, A, Iy, Iz, J);
  const double d = -0.01;
  doc["prescribed"] = {{{"node", "B"}, {"dof", "uy"}, {"value", d}}};
  const auto r = solve_linear_static(test::model_from(doc));
  ASSERT_EQ(r.status, SolveStatus::Succeeded);
  EXPECT_DOUBLE_EQ(r.u[6 + 1], d);
  EXPECT_NEAR(r.reactions[1][1], 3 * E * Iz * d / (L * L * L), 1e-6);  // k = 3EI/L^3
  EXPECT_NEAR(r.reactions[0][1], -3 * E * Iz * d / (L * L * L), 1e-6);
}

// Rigid offset: beam A-B along x, rigid link B-C along y (length d), force P along x at C.
// The beam carries N = P and M_z = -P d:  u_C,x = P L / EA + P d^2 L / E Iz,  u_C,y = -P d L^2 / 2 E Iz.
TEST(RigidLink, OffsetLoadTransfersForceAndMomentExactly) {
  const double d = 0.4, P = 2e3;
  json doc = test::cantilever(L, E, G, A, Iy, Iz, J);
  doc["nodes"].push_back({{"id", "C"}, {"xyz", {L, d, 0}}});
  doc["elements"].push_back({{"id", "r"}, {"type", "rigid"}, {"nodes", {"B", "C"}}});
  doc["loads"].push_back({{"node", "C"}, {"force", {P, 0, 0}}});
  const auto r = solve_linear_static(test::model_from(doc));
  ASSERT_EQ(r.status, SolveStatus::Succeeded);
  EXPECT_NEAR(r.u[12 + 0], P * L / (E * A) + P * d * d * L / (E * Iz), 1e-12);
  EXPECT_NEAR(r.u[12 + 1], -P * d * L * L / (2 * E * Iz), 1e-12);
  EXPECT_NEAR(r.u[12 + 5], r.u[6 + 5], 1e-15);  // the rigid body rotates as one
}

// Two rigid links closing a loop (a rigid triangle hung on a cantilever): the loop constraint is
// redundant but consistent; the result equals the same load applied through one link.
TEST(RigidLink, ClosedLoopOfRigidLinksIsHandled) {
  const double P = 1e3;
  json doc = test::cantilever(L, E, G, A, Iy, Iz, J);
  doc["nodes"].push_back({{"id", "C"}, {"xyz", {L, 0.5, 0}}});
  doc["nodes"].push_back({{"id", "D"}, {"xyz", {L + 0.3, 0.2, 0.1}}});
  doc["elements"].push_back({{"id", "r1"}, {"type", "rigid"}, {"nodes", {"B", "C"}}});
  doc["elements"].push_back({{"id", "r2"}, {"type", "rigid"}, {"nodes", {"C", "D"}}});
  doc["elements"].push_back({{"id", "r3"}, {"type", "rigid"}, {"nodes", {"D", "B"}}});
  doc["loads"].push_back({{"node", "D"}, {"force", {0, P, 0}}});
  const auto r = solve_linear_static(test::model_from(doc));
  ASSERT_EQ(r.status, SolveStatus::Succeeded);
  // Equivalent load at B: force P y and moment (D - B) x F.
  json ref = test::cantilever(L, E, G, A, Iy, Iz, J);
  const Vec3 m = Vec3(0.3, 0.2, 0.1).cross(Vec3(0, P, 0));
  ref["loads"].push_back({{"node", "B"}, {"force", {0, P, 0}}, {"moment", {m.x(), m.y(), m.z()}}});
  const auto r2 = solve_linear_static(test::model_from(ref));
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(r.u[6 + k], r2.u[6 + k], 1e-12) << k;
  EXPECT_NEAR(r.reactions[0][1], -P, 1e-6);
}

// Joints: a cantilever of total length L = L1 + L2 with a joint at L1 and a rotational spring k
// about the bending axis: delta = P L^3 / 3EI + P L2^2 / k (the hinge rotation P L2 / k times L2).
class JointChain : public ::testing::Test {
 protected:
  static constexpr double L1 = 1.2, L2 = 0.8;
  json doc(const json& joint) {
    json d = {
        {"nodes", json::array({{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {L1, 0, 0}}},
                               {{"id", "C"}, {"xyz", {L1, 0, 0}}}, {{"id", "D"}, {"xyz", {L1 + L2, 0, 0}}}})},
        {"materials", json::array({{{"id", "m"}, {"E", E}, {"G", G}}})},
        {"sections", json::array({{{"id", "s"}, {"A", A}, {"Iy", Iy}, {"Iz", Iz}, {"J", J}}})},
        {"elements", json::array({{{"id", "ab"}, {"type", "beam"}, {"nodes", {"A", "B"}}, {"material", "m"}, {"section", "s"}, {"orientation", {0, 0, 1}}},
                                  {{"id", "cd"}, {"type", "beam"}, {"nodes", {"C", "D"}}, {"material", "m"}, {"section", "s"}, {"orientation", {0, 0, 1}}}})},
        {"joints", json::array({joint})},
        {"supports", json::array({{{"node", "A"}, {"fix", "all"}}})},
        {"loads", json::array()}};
    return d;
  }
};

TEST_F(JointChain, RevoluteSpringAddsHingeRotation) {
  const double k = 5e4, P = 300.0;
  json d = doc({{"id", "j"}, {"type", "revolute"}, {"nodes", {"B", "C"}}, {"axes", {{0, 0, 1}}}, {"stiffness", {k}}});
  d["loads"].push_back({{"node", "D"}, {"force", {0, P, 0}}});
  const Model m = test::model_from(d);
  const auto r = solve_linear_static(m);
  ASSERT_EQ(r.status, SolveStatus::Succeeded);
  const double Lt = L1 + L2;
  EXPECT_NEAR(r.u[6 * 3 + 1], P * Lt * Lt * Lt / (3 * E * Iz) + P * L2 * L2 / k, 1e-12);
  // The joint coordinate is the hinge rotation; the joint transmits force P and moment P L2 (spring).
  const int qj = 6 * 4;
  EXPECT_NEAR(r.u[qj], P * L2 / k, 1e-12);
  EXPECT_NEAR(r.joint_forces[0][1], -P, 1e-6);  // body 1 holds body 2 against the load
  EXPECT_NEAR(r.joint_forces[0][5], -P * L2, 1e-6);
  // Out of plane the revolute joint is rigid: a z load gives the plain cantilever.
  json dz = doc({{"id", "j"}, {"type", "revolute"}, {"nodes", {"B", "C"}}, {"axes", {{0, 0, 1}}}, {"stiffness", {k}}});
  dz["loads"].push_back({{"node", "D"}, {"force", {0, 0, P}}});
  const auto rz = solve_linear_static(test::model_from(dz));
  EXPECT_NEAR(rz.u[6 * 3 + 2], P * Lt * Lt * Lt / (3 * E * Iy), 1e-12);
}

TEST_F(JointChain, UniversalFreesTwoAxesAndTransmitsTorsion) {
  const double ky = 2e4, kz = 7e4, P = 200.0, T = 50.0;
  json d = doc({{"id", "u"}, {"type", "universal"}, {"nodes", {"B", "C"}}, {"axes", {{0, 1, 0}, {0, 0, 1}}}, {"stiffness", {ky, kz}}});
  d["loads"].push_back({{"node", "D"}, {"force", {0, P, P}}, {"moment", {T, 0, 0}}});
  const auto r = solve_linear_static(test::model_from(d));
  ASSERT_EQ(r.status, SolveStatus::Succeeded);
  const double Lt = L1 + L2;
  EXPECT_NEAR(r.u[6 * 3 + 1], P * Lt * Lt * Lt / (3 * E * Iz) + P * L2 * L2 / kz, 1e-12);
  EXPECT_NEAR(r.u[6 * 3 + 2], P * Lt * Lt * Lt / (3 * E * Iy) + P * L2 * L2 / ky, 1e-12);
  EXPECT_NEAR(r.u[6 * 3 + 3], T * Lt / (G * J), 1e-12);  // torsion passes the cross rigidly
}

TEST_F(JointChain, SphericalSpringsActOnAllThreeRotations) {
  const double k = 3e4, T = 40.0, P = 100.0;
  json d = doc({{"id", "s"}, {"type", "spherical"}, {"nodes", {"B", "C"}}, {"stiffness", {k, k, k}}});
  d["loads"].push_back({{"node", "D"}, {"force", {0, P, 0}}, {"moment", {T, 0, 0}}});
  const auto r = solve_linear_static(test::model_from(d));
  ASSERT_EQ(r.status, SolveStatus::Succeeded);
  const double Lt = L1 + L2;
  EXPECT_NEAR(r.u[6 * 3 + 3], T * Lt / (G * J) + T / k, 1e-12);
  EXPECT_NEAR(r.u[6 * 3 + 1], P * Lt * Lt * Lt / (3 * E * Iz) + P * L2 * L2 / k, 1e-12);
}

TEST_F(JointChain, ReversedJointDirectionGivesTheSameAnswer) {
  // The joint written from C to B (the slave side is then nodes[0]): same structure.
  const double k = 5e4, P = 300.0;
  json d = doc({{"id", "j"}, {"type", "revolute"}, {"nodes", {"C", "B"}}, {"axes", {{0, 0, 1}}}, {"stiffness", {k}}});
  d["loads"].push_back({{"node", "D"}, {"force", {0, P, 0}}});
  const auto r = solve_linear_static(test::model_from(d));
  const double Lt = L1 + L2;
  EXPECT_NEAR(r.u[6 * 3 + 1], P * Lt * Lt * Lt / (3 * E * Iz) + P * L2 * L2 / k, 1e-12);
  EXPECT_NEAR(r.u[6 * 4], -P * L2 / k, 1e-12);  // q measured from body 1 (now C's side)
}

TEST_F(JointChain, PassiveRevoluteUnderLoadIsDiagnosedAsMechanism) {
  json d = doc({{"id", "j"}, {"type", "revolute"}, {"nodes", {"B", "C"}}, {"axes", {{0, 0, 1}}}});
  d["loads"].push_back({{"node", "D"}, {"force", {0, 1, 0}}});
  const auto r = solve_linear_static(test::model_from(d));
  ASSERT_EQ(r.status, SolveStatus::Mechanism);
  ASSERT_EQ(r.modes.size(), 1u);
  EXPECT_NE(r.message.find("joint 'j' coordinate 0"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("'cd'"), std::string::npos) << r.message;
}

// A member between two spherical joints can spin about its own axis: one zero-energy mode that
// involves that member and both joints.
TEST(Mechanism, MemberBetweenTwoSphericalJointsSpins) {
  json d = {
      {"nodes", json::array({{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {1, 0, 0}}}, {{"id", "C"}, {"xyz", {1, 0, 0}}},
                             {{"id", "D"}, {"xyz", {2, 0, 0}}}, {{"id", "E"}, {"xyz", {2, 0, 0}}}, {{"id", "F"}, {"xyz", {3, 0, 0}}}})},
      {"materials", json::array({{{"id", "m"}, {"E", E}, {"G", G}}})},
      {"sections", json::array({{{"id", "s"}, {"A", A}, {"Iy", Iy}, {"Iz", Iz}, {"J", J}}})},
      {"elements", json::array({{{"id", "ab"}, {"type", "beam"}, {"nodes", {"A", "B"}}, {"material", "m"}, {"section", "s"}},
                                {{"id", "strut"}, {"type", "beam"}, {"nodes", {"C", "D"}}, {"material", "m"}, {"section", "s"}},
                                {{"id", "ef"}, {"type", "beam"}, {"nodes", {"E", "F"}}, {"material", "m"}, {"section", "s"}}})},
      {"joints", json::array({{{"id", "s1"}, {"type", "spherical"}, {"nodes", {"B", "C"}}},
                              {{"id", "s2"}, {"type", "spherical"}, {"nodes", {"D", "E"}}}})},
      {"supports", json::array({{{"node", "A"}, {"fix", "all"}}, {{"node", "F"}, {"fix", "all"}}})},
      {"loads", json::array({{{"node", "C"}, {"force", {0, 0, 10}}}})}};
  const auto r = solve_linear_static(test::model_from(d));
  ASSERT_EQ(r.status, SolveStatus::Mechanism);
  ASSERT_EQ(r.modes.size(), 1u) << r.message;
  EXPECT_NE(r.message.find("'strut'"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("node 'C' dof rx"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("joint 's1'"), std::string::npos) << r.message;
}

// A node with nothing attached and a load on it: every DOF is a zero-energy mode; diagnosed,
// never handed to the factorisation.
TEST(Mechanism, LoneNodeWithoutElementsIsDiagnosedNotCrashedOn) {
  json d = {{"nodes", json::array({{{"id", 1}, {"xyz", {0, 0, 0}}}})},
            {"loads", json::array({{{"node", 1}, {"force", {1, 0, 0}}}})}};
  const auto r = solve_linear_static(test::model_from(d));
  EXPECT_EQ(r.status, SolveStatus::Mechanism);
  EXPECT_EQ(r.modes.size(), 6u) << r.message;
  EXPECT_NE(r.message.find("node '1' dof ux"), std::string::npos) << r.message;
}

}  // namespace linear_static_test
