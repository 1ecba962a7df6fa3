// Condensed (Cartesian) stiffness of a node: inverse of the analytic compliance, rank with
// passive joints, equality of a virtual-spring joint and the beam it stands for.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cstring>
#include <functional>
#include <thread>

#include "solvers/condensed_stiffness.hpp"
#include "solvers/structure_cache.hpp"
#include "support/models.hpp"

namespace condensed_stiffness_test {

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

// `eigenvalues` and `rank` (results.json's scaled_eigenvalues and rank) are those of the
// length-scaled matrix diag(1,1,1,1/L,1/L,1/L) K_c diag(...) (condensed_stiffness.hpp), L the
// model's length scale, computed here from K_c on its own: for a node whose DOFs are its own (the
// cantilever's tip: K_c by static condensation, the rank from K_z's own eigenvalues) and for nodes
// reached through joints (the SVD path, analyse_rank).
TEST(CondensedStiffness, TheScaledEigenvaluesAndRankAreThoseOfTheLengthScaledMatrix) {
  json sph = test::cantilever(L, E, G, A, Iy, Iz, J, 2);
  sph["nodes"].push_back({{"id", "P"}, {"xyz", {L, 0, 0}}});
  sph["joints"] = {{{"id", "S"}, {"type", "spherical"}, {"nodes", {"B", "P"}}}};
  json slanted = test::cantilever(L, E, G, A, Iy, Iz, J, 3);
  slanted["nodes"][1]["xyz"] = {L, 0.4 * L, 0.2 * L};  // every block of K_c coupled
  json sprung = sph;  // a revolute joint with a spring: rank 6 through a joint
  sprung["joints"] = {{{"id", "R"}, {"type", "revolute"}, {"nodes", {"B", "P"}}, {"axes", {{0, 0.6, 0.8}}}, {"stiffness", {250.0}}}};
  const std::vector<std::pair<json, std::string>> cases = {{test::cantilever(L, E, G, A, Iy, Iz, J, 5), "B"},
                                                           {slanted, "B"}, {sph, "P"}, {sprung, "P"}};
  for (const auto& [doc, node] : cases) {
    SCOPED_TRACE(node + " of " + doc.dump().substr(0, 120));
    const Model m = test::model_from(doc);
    const auto k = linear_node_stiffness(m, m.find_node(node));
    ASSERT_TRUE(k.ok) << k.message;
    const double Ls = m.length_scale();
    Vec6 s;
    s << 1, 1, 1, 1 / Ls, 1 / Ls, 1 / Ls;
    const Mat6 Ks = s.asDiagonal() * k.K * s.asDiagonal();
    Eigen::SelfAdjointEigenSolver<Mat6> es(0.5 * (Ks + Ks.transpose()));
    const double big = es.eigenvalues().cwiseAbs().maxCoeff();
    ASSERT_GT(big, 0.0);
    int rank = 0;
    for (int i = 0; i < 6; ++i) {
      EXPECT_NEAR(k.eigenvalues[i], es.eigenvalues()[i], 1e-12 * big) << i;
      rank += std::abs(es.eigenvalues()[i]) > 1e-9 * big ? 1 : 0;
    }
    EXPECT_EQ(k.rank, rank);
  }
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

// The per-thread cache of DofMap + LinearStructure (solvers/structure_cache.hpp) must never hand
// out a stale pair. A chain of two links on revolute joints with springs, a rigid link, a Timoshenko
// section, a prescribed rotation: every field of the key has a value to change.
namespace {

json cache_chain() {
  return {{"nodes", json::array({{{"id", "G"}, {"xyz", {0, 0, 0}}}, {{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {0.4, 0, 0}}},
                                 {{"id", "C"}, {"xyz", {0.4, 0, 0}}}, {{"id", "D"}, {"xyz", {0.7, 0.1, 0}}}, {{"id", "T"}, {"xyz", {0.8, 0.1, 0}}}})},
          {"materials", json::array({{{"id", "m"}, {"E", E}, {"G", G}}})},
          {"sections", json::array({{{"id", "s"}, {"A", A}, {"Iy", Iy}, {"Iz", Iz}, {"J", J}, {"ky", 1.2}, {"kz", 1.2}}})},
          {"elements", json::array({{{"id", "l1"}, {"type", "beam"}, {"nodes", {"A", "B"}}, {"material", "m"}, {"section", "s"}},
                                    {{"id", "l2"}, {"type", "beam"}, {"nodes", {"C", "D"}}, {"material", "m"}, {"section", "s"},
                                     {"theory", "timoshenko"}, {"orientation", {0, 0, 1}}},
                                    {{"id", "r"}, {"type", "rigid"}, {"nodes", {"D", "T"}}}})},
          {"joints", json::array({{{"id", "q1"}, {"type", "revolute"}, {"nodes", {"G", "A"}}, {"axes", {{0, 0, 1}}}, {"stiffness", {2e3}}},
                                  {{"id", "q2"}, {"type", "revolute"}, {"nodes", {"B", "C"}}, {"axes", {{0, 0, 1}}}, {"stiffness", {3e3}}}})},
          {"supports", json::array({{{"node", "G"}, {"fix", "all"}}})},
          {"prescribed", json::array({{{"joint", "q2"}, {"coordinate", 0}, {"value", 0.0}}})}};
}

// The node stiffness computed on a new thread (an empty cache: a map and structure built afresh).
CondensedStiffness fresh_stiffness(const Model& m, int node) {
  CondensedStiffness k;
  std::thread([&] { k = linear_node_stiffness(m, node); }).join();
  return k;
}

bool same_bits(const Mat6& a, const Mat6& b) { return std::memcmp(a.data(), b.data(), sizeof(double) * 36) == 0; }

}  // namespace

TEST(LinearStructureCache, ReusesItsPairOnlyForAModelEqualInEverythingThePairReads) {
  LinearStructureCache cache;
  const Model base = test::model_from(cache_chain());
  cache.get(base);
  EXPECT_FALSE(cache.last_was_hit());
  // An equal model read again (another object): reused, and bound to the asked model.
  const Model same = test::model_from(cache_chain());
  const auto& parts = cache.get(same);
  EXPECT_TRUE(cache.last_was_hit());
  EXPECT_EQ(&parts.structure.model(), &same);
  // Joint springs are not read by the pair: reused.
  json d = cache_chain();
  d["joints"][0]["stiffness"] = {5e3};
  const Model other_spring = test::model_from(d);
  cache.get(other_spring);
  EXPECT_TRUE(cache.last_was_hit());
  // Each change of a field that the map or the beams read: a new pair (the chain again between two
  // changes, so that each is compared with the base).
  const std::vector<std::function<void(json&)>> changes = {
      [](json& j) { j["nodes"][4]["xyz"][1] = 0.1000001; },
      [](json& j) { j["nodes"][4]["xyz"][2] = -0.0; },  // bits differ from 0.0
      [](json& j) { j["nodes"][5]["id"] = "T2"; j["elements"][2]["nodes"][1] = "T2"; },
      [](json& j) { j["materials"][0]["E"] = 2.0 * E; },
      [](json& j) { j["materials"][0]["G"] = 2.0 * G; },
      [](json& j) { j["sections"][0]["Iz"] = 2.0 * Iz; },
      [](json& j) { j["sections"][0]["ky"] = 1.3; },
      [](json& j) { j["elements"][1]["orientation"] = {0, 0.1, 1}; },
      [](json& j) { j["elements"][1]["theory"] = "euler_bernoulli"; },
      [](json& j) { j["elements"][1]["divisions"] = 2; },
      [](json& j) { j["elements"][2]["type"] = "beam"; j["elements"][2]["material"] = "m"; j["elements"][2]["section"] = "s"; },
      [](json& j) { j["joints"][1]["axes"] = {{0, 1, 0}}; },
      [](json& j) { j["joints"][1]["type"] = "universal"; j["joints"][1]["axes"] = {{0, 0, 1}, {0, 1, 0}}; j["joints"][1]["stiffness"] = {3e3, 0}; },
      [](json& j) { j["supports"][0]["fix"] = {"ux", "uy", "uz", "rx", "ry"}; },
      [](json& j) { j["prescribed"][0]["value"] = 0.01; },
      [](json& j) { j["prescribed"] = json::array(); },
  };
  for (std::size_t i = 0; i < changes.size(); ++i) {
    json c = cache_chain();
    changes[i](c);
    const Model changed = test::model_from(c);
    cache.get(changed);
    EXPECT_FALSE(cache.last_was_hit()) << "change " << i;
    cache.get(base);
    EXPECT_FALSE(cache.last_was_hit()) << "change " << i;
  }
}

// A sequence of models through the thread's cache (hits and misses in turn) gives, bit for bit,
// the stiffness of a map and structure built afresh; a hit takes the asked model's springs.
TEST(LinearStructureCache, NodeStiffnessThroughTheCacheIsBitForBitTheFreshOne) {
  std::vector<Model> models;
  for (double k : {2e3, 7e3}) {
    for (double y : {0.1, 0.15}) {
      json d = cache_chain();
      d["joints"][0]["stiffness"] = {k};
      d["nodes"][4]["xyz"][1] = y;
      d["nodes"][5]["xyz"][1] = y;
      models.push_back(test::model_from(d));
    }
  }
  const std::vector<int> order = {0, 2, 2, 0, 1, 3, 3, 1, 0};  // 0 -> 2 same geometry, 0 -> 1 not
  std::vector<Mat6> K(models.size());
  for (int i : order) {
    const Model& m = models[i];
    const int tip = m.find_node("T");
    const CondensedStiffness k = linear_node_stiffness(m, tip);
    const CondensedStiffness f = fresh_stiffness(m, tip);
    ASSERT_TRUE(k.ok) << k.message;
    EXPECT_TRUE(same_bits(k.K, f.K)) << "model " << i;
    EXPECT_TRUE(same_bits(k.compliance, f.compliance)) << "model " << i;
    EXPECT_EQ(k.rank, f.rank);
    EXPECT_EQ(k.message, f.message);
    EXPECT_EQ(k.statically_indeterminate, f.statically_indeterminate);
    K[i] = k.K;
  }
  // The springs reached the result: a stiffer base joint, a stiffer tip (same geometry).
  EXPECT_GT(K[2].norm(), K[0].norm() * (1 + 1e-6));
  EXPECT_GT(K[3].norm(), K[1].norm() * (1 + 1e-6));
}

}  // namespace condensed_stiffness_test
