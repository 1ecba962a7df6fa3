// Condensed (Cartesian) stiffness of a node: inverse of the analytic compliance, rank with
// passive joints, equality of a virtual-spring joint and the beam it stands for.
#include <gtest/gtest.h>

#include "solvers/condensed_stiffness.hpp"
#include "support/models.hpp"

using namespace beamfea;
using nlohmann::json;

namespace {
constexpr double L = 1.5, E = 7e10, G = 2.6e10, A = 4e-4, Iy = 1.2e-8, Iz = 3.3e-8, J = 2e-8;
}

// The tip compliance of a cantilever (Timoshenko & Gere, Mechanics of Materials, App. G):
//   u: L/EA; v-rz: [L^3/3EIz, L^2/2EIz; L^2/2EIz, L/EIz]; w-ry: [L^3/3EIy, -L^2/2EIy; ., L/EIy];
//   rx: L/GJ.
TEST(CondensedStiffness, CantileverTipIsTheInverseOfItsAnalyticCompliance) {
  const Model m = test::model_from(test::cantilever(L, E, G, A, Iy, Iz, J, 5));
  const auto k = linear_node_stiffness(m, m.find_node("B"));
  ASSERT_TRUE(k.ok) << k.message;
  Mat6 C = Mat6::Zero();
  C(0, 0) = L / (E * A);
  C(1, 1) = L * L * L / (3 * E * Iz);
  C(1, 5) = C(5, 1) = L * L / (2 * E * Iz);
  C(5, 5) = L / (E * Iz);
  C(2, 2) = L * L * L / (3 * E * Iy);
  C(2, 4) = C(4, 2) = -L * L / (2 * E * Iy);
  C(4, 4) = L / (E * Iy);
  C(3, 3) = L / (G * J);
  const Mat6 K = C.inverse();
  EXPECT_EQ(k.rank, 6);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) EXPECT_NEAR(k.K(i, j), K(i, j), 1e-8 * K.cwiseAbs().maxCoeff()) << i << "," << j;
}

TEST(CondensedStiffness, ChainEndingInASphericalJointHasRankThree) {
  json d = test::cantilever(L, E, G, A, Iy, Iz, J, 2);
  d["nodes"].push_back({{"id", "P"}, {"xyz", {L, 0, 0}}});
  d["joints"] = {{{"id", "S"}, {"type", "spherical"}, {"nodes", {"B", "P"}}}};
  const Model m = test::model_from(d);
  const auto k = linear_node_stiffness(m, m.find_node("P"));
  ASSERT_TRUE(k.ok) << k.message;
  EXPECT_EQ(k.rank, 3);
  ASSERT_EQ(k.null_space.size(), 3u);
  for (const auto& v : k.null_space) EXPECT_NEAR(v.head<3>().norm(), 0.0, 1e-9);  // rotations are free
  // The translational block is the inverse of the translational compliance.
  EXPECT_NEAR(k.K(0, 0), E * A / L, 1e-6 * E * A / L);
  EXPECT_NEAR(k.K(1, 1), 3 * E * Iz / (L * L * L), 1e-6 * 3 * E * Iz / (L * L * L));
}

TEST(CondensedStiffness, UniversalThenRevolutePassiveChainLosesThreeDirections) {
  // Base -> universal (y, z) -> link -> revolute (z) -> link -> spherical -> platform P.
  json d = {
      {"nodes", json::array({{{"id", "G"}, {"xyz", {0, 0, 0}}}, {{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {1, 0, 0}}},
                             {{"id", "C"}, {"xyz", {1, 0, 0}}}, {{"id", "D"}, {"xyz", {2, 0.3, 0}}}, {{"id", "P"}, {"xyz", {2, 0.3, 0}}}})},
      {"materials", json::array({{{"id", "m"}, {"E", E}, {"G", G}}})},
      {"sections", json::array({{{"id", "s"}, {"A", A}, {"Iy", Iy}, {"Iz", Iz}, {"J", J}}})},
      {"elements", json::array({{{"id", "l1"}, {"type", "beam"}, {"nodes", {"A", "B"}}, {"material", "m"}, {"section", "s"}},
                                {{"id", "l2"}, {"type", "beam"}, {"nodes", {"C", "D"}}, {"material", "m"}, {"section", "s"}}})},
      {"joints", json::array({{{"id", "U"}, {"type", "universal"}, {"nodes", {"G", "A"}}, {"axes", {{0, 1, 0}, {0, 0, 1}}}},
                              {{"id", "R"}, {"type", "revolute"}, {"nodes", {"B", "C"}}, {"axes", {{0, 0, 1}}}, {"stiffness", {1e3}}},
                              {{"id", "S"}, {"type", "spherical"}, {"nodes", {"D", "P"}}}})},
      {"supports", json::array({{{"node", "G"}, {"fix", "all"}}})}};
  const Model m = test::model_from(d);
  const auto k = linear_node_stiffness(m, m.find_node("P"));
  ASSERT_TRUE(k.ok) << k.message;
  // Translations of P: the U joint lets P move on a sphere about G (2 directions) but the chain
  // resists along G->P; rotations are free at the spherical joint.
  EXPECT_EQ(k.rank, 1);
  const Vec3 gp = Vec3(2, 0.3, 0).normalized();
  Vec6 dir;
  dir << gp, Vec3::Zero();
  for (const auto& v : k.null_space) EXPECT_NEAR(v.dot(dir), 0.0, 1e-8);
}

// A rigid link with a virtual spring whose stiffness is the cantilever tip stiffness of a beam
// (Pashkevich et al. 2010, eq. 39) has exactly the tip stiffness of that beam.
TEST(CondensedStiffness, VirtualSpringFromBeamEqualsTheBeamTipStiffness) {
  const Model beam = test::model_from(test::cantilever(L, E, G, A, Iy, Iz, J));
  json d = test::cantilever(L, E, G, A, Iy, Iz, J);
  d["elements"] = {{{"id", "link"}, {"type", "rigid"}, {"nodes", {"A", "B"}}}};
  d["nodes"].push_back({{"id", "T"}, {"xyz", {L, 0, 0}}});
  d["joints"] = {{{"id", "vj"}, {"type", "virtual_spring"}, {"nodes", {"B", "T"}},
                  {"stiffness_from_beam", {{"material", "m"}, {"section", "s"}, {"length", L}}}}};
  const Model vjm = test::model_from(d);
  const auto kb = linear_node_stiffness(beam, beam.find_node("B"));
  const auto kv = linear_node_stiffness(vjm, vjm.find_node("T"));
  ASSERT_TRUE(kv.ok) << kv.message;
  EXPECT_EQ(kv.rank, 6);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) EXPECT_NEAR(kv.K(i, j), kb.K(i, j), 1e-8 * kb.K.cwiseAbs().maxCoeff()) << i << "," << j;
}
