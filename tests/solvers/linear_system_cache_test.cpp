// The LinearSystemCache (solvers/structure_cache.hpp) of linear_static in sweeps: a model whose
// structure is that of the last one reuses its factorised system whatever its loads, any change of
// a field the system is built from (joint springs included) builds a new one, and every solution
// through the cache, written over the last one, is bit for bit that of a fresh system.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <vector>

#include "solvers/linear_static.hpp"
#include "solvers/structure_cache.hpp"
#include "support/models.hpp"

namespace linear_system_cache_test {

using namespace beamfea;
using nlohmann::json;

namespace {

constexpr double E = 7e10, G = 2.6e10, A = 4e-4, Iy = 1.2e-8, Iz = 3.3e-8, J = 2e-8;

// Two links on revolute joints with springs, a rigid link, a Timoshenko section, a prescribed
// rotation, a density (self-weight under gravity): every field of the key has a value to change,
// and every kind of load one to vary.
json frame() {
  return {{"nodes", json::array({{{"id", "G"}, {"xyz", {0, 0, 0}}}, {{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {0.4, 0, 0}}},
                                 {{"id", "C"}, {"xyz", {0.4, 0, 0}}}, {{"id", "D"}, {"xyz", {0.7, 0.1, 0}}}, {{"id", "T"}, {"xyz", {0.8, 0.1, 0}}}})},
          {"materials", json::array({{{"id", "m"}, {"E", E}, {"G", G}, {"density", 2700.0}}})},
          {"sections", json::array({{{"id", "s"}, {"A", A}, {"Iy", Iy}, {"Iz", Iz}, {"J", J}, {"ky", 1.2}, {"kz", 1.2}}})},
          {"elements", json::array({{{"id", "l1"}, {"type", "beam"}, {"nodes", {"A", "B"}}, {"material", "m"}, {"section", "s"}, {"divisions", 2}},
                                    {{"id", "l2"}, {"type", "beam"}, {"nodes", {"C", "D"}}, {"material", "m"}, {"section", "s"},
                                     {"theory", "timoshenko"}, {"orientation", {0, 0, 1}}},
                                    {{"id", "r"}, {"type", "rigid"}, {"nodes", {"D", "T"}}}})},
          {"joints", json::array({{{"id", "q1"}, {"type", "revolute"}, {"nodes", {"G", "A"}}, {"axes", {{0, 0, 1}}}, {"stiffness", {2e3}}},
                                  {{"id", "q2"}, {"type", "revolute"}, {"nodes", {"B", "C"}}, {"axes", {{0, 0, 1}}}, {"stiffness", {3e3}}}})},
          {"supports", json::array({{{"node", "G"}, {"fix", "all"}}})},
          {"prescribed", json::array({{{"joint", "q2"}, {"coordinate", 0}, {"value", 0.0}}})},
          {"loads", json::array({{{"node", "T"}, {"force", {0, -10.0, 2.0}}},
                                 {{"element", "l1"}, {"distributed", {0, 0, -50.0}}}})},
          {"gravity", {0, -9.81, 0}}};
}

bool same_bits(const double* a, const double* b, std::size_t n) { return n == 0 || std::memcmp(a, b, sizeof(double) * n) == 0; }

// Every field of two solutions equal, doubles by their bits.
void expect_same(const LinearStaticResult& a, const LinearStaticResult& b, const std::string& what) {
  EXPECT_EQ(a.status, b.status) << what;
  EXPECT_EQ(a.message, b.message) << what;
  EXPECT_EQ(a.free_dofs, b.free_dofs) << what;
  ASSERT_EQ(a.u.size(), b.u.size()) << what;
  EXPECT_TRUE(same_bits(a.u.data(), b.u.data(), a.u.size())) << what;
  ASSERT_EQ(a.reactions.size(), b.reactions.size()) << what;
  for (std::size_t n = 0; n < a.reactions.size(); ++n) EXPECT_TRUE(same_bits(a.reactions[n].data(), b.reactions[n].data(), 6)) << what;
  EXPECT_EQ(a.supported, b.supported) << what;
  ASSERT_EQ(a.end_forces.size(), b.end_forces.size()) << what;
  for (std::size_t e = 0; e < a.end_forces.size(); ++e) EXPECT_TRUE(same_bits(a.end_forces[e].data(), b.end_forces[e].data(), 12)) << what;
  ASSERT_EQ(a.joint_forces.size(), b.joint_forces.size()) << what;
  for (std::size_t j = 0; j < a.joint_forces.size(); ++j) EXPECT_TRUE(same_bits(a.joint_forces[j].data(), b.joint_forces[j].data(), 6)) << what;
  ASSERT_EQ(a.element_loads.size(), b.element_loads.size()) << what;
  for (std::size_t e = 0; e < a.element_loads.size(); ++e) {
    EXPECT_EQ(a.element_loads[e].distributed.size(), b.element_loads[e].distributed.size()) << what;
    EXPECT_EQ(a.element_loads[e].points.size(), b.element_loads[e].points.size()) << what;
  }
  EXPECT_EQ(a.modes.size(), b.modes.size()) << what;
  EXPECT_EQ(a.statically_indeterminate, b.statically_indeterminate) << what;
}

}  // namespace

TEST(LinearSystemCache, ReusesItsSystemOnlyForAModelEqualInEverythingTheSystemReads) {
  LinearSystemCache cache;
  const Model base = test::model_from(frame());
  const auto first = cache.get(base);
  EXPECT_FALSE(cache.last_was_hit());
  ASSERT_EQ(first->factorizations(), 1);
  // An equal model read again (another object): reused, and bound to the asked model.
  const Model same = test::model_from(frame());
  const auto again = cache.get(same);
  EXPECT_TRUE(cache.last_was_hit());
  EXPECT_EQ(again.get(), first.get());
  EXPECT_EQ(&again->model(), &same);
  // Loads are not read by the system: reused.
  const std::vector<std::function<void(json&)>> loads = {
      [](json& j) { j["loads"][0]["force"][1] = -20.0; },
      [](json& j) { j["loads"][1]["distributed"][2] = -80.0; },
      [](json& j) { j["gravity"] = {0, 0, -9.81}; },
      [](json& j) { j["loads"] = json::array(); },
  };
  for (std::size_t i = 0; i < loads.size(); ++i) {
    json c = frame();
    loads[i](c);
    const Model changed = test::model_from(c);
    cache.get(changed);
    EXPECT_TRUE(cache.last_was_hit()) << "load change " << i;
  }
  // Other options: a new system.
  LinearStaticOptions other;
  other.singular_rcond = 1e-12;
  cache.get(base, other);
  EXPECT_FALSE(cache.last_was_hit());
  cache.get(base);
  EXPECT_FALSE(cache.last_was_hit());
  // Each change of a field that the map, the beams or the assembled stiffness read: a new system
  // (the frame again between two changes, so that each is compared with the base).
  const std::vector<std::function<void(json&)>> changes = {
      [](json& j) { j["nodes"][4]["xyz"][1] = 0.1000001; },
      [](json& j) { j["nodes"][4]["xyz"][2] = -0.0; },  // bits differ from 0.0
      [](json& j) { j["nodes"][5]["id"] = "T2"; j["elements"][2]["nodes"][1] = "T2"; j["loads"][0]["node"] = "T2"; },
      [](json& j) { j["materials"][0]["E"] = 2.0 * E; },
      [](json& j) { j["materials"][0]["G"] = 2.0 * G; },
      [](json& j) { j["materials"][0]["density"] = 2701.0; },
      [](json& j) { j["sections"][0]["Iz"] = 2.0 * Iz; },
      [](json& j) { j["sections"][0]["ky"] = 1.3; },
      [](json& j) { j["elements"][1]["orientation"] = {0, 0.1, 1}; },
      [](json& j) { j["elements"][1]["theory"] = "euler_bernoulli"; },
      [](json& j) { j["elements"][1]["divisions"] = 2; },
      [](json& j) { j["elements"][2]["type"] = "beam"; j["elements"][2]["material"] = "m"; j["elements"][2]["section"] = "s"; },
      [](json& j) { j["joints"][0]["stiffness"] = {2.5e3}; },  // a spring: in the assembled stiffness
      [](json& j) { j["joints"][1]["axes"] = {{0, 1, 0}}; },
      [](json& j) { j["joints"][1]["type"] = "universal"; j["joints"][1]["axes"] = {{0, 0, 1}, {0, 1, 0}}; j["joints"][1]["stiffness"] = {3e3, 4e3}; },
      [](json& j) { j["supports"][0]["fix"] = {"ux", "uy", "uz", "rx", "ry"}; },
      [](json& j) { j["prescribed"][0]["value"] = 0.01; },
      [](json& j) { j["prescribed"] = json::array(); },
  };
  for (std::size_t i = 0; i < changes.size(); ++i) {
    json c = frame();
    changes[i](c);
    const Model changed = test::model_from(c);
    cache.get(changed);
    EXPECT_FALSE(cache.last_was_hit()) << "change " << i;
    cache.get(base);
    EXPECT_FALSE(cache.last_was_hit()) << "change " << i;
  }
}

// A sequence of models through one cache, each solution written over the last one (hits and misses
// in turn), gives bit for bit the solution of a system built afresh; a hit takes the asked model's
// loads.
TEST(LinearSystemCache, SolutionsThroughTheCacheAreBitForBitFreshOnes) {
  std::vector<Model> models;
  for (double P : {-10.0, -25.0}) {
    for (double k : {2e3, 7e3}) {
      for (double y : {0.1, 0.15}) {
        json d = frame();
        d["loads"][0]["force"][1] = P;
        d["joints"][0]["stiffness"] = {k};
        d["nodes"][4]["xyz"][1] = y;
        d["nodes"][5]["xyz"][1] = y;
        models.push_back(test::model_from(d));
      }
    }
  }
  // 0 -> 4 only the load differs (a hit), 0 -> 2 the spring, 0 -> 1 the geometry (misses).
  const std::vector<int> order = {0, 4, 4, 0, 2, 6, 1, 5, 3, 7, 7, 0};
  LinearSystemCache cache;
  LinearStaticResult kept;
  LinearSolveScratch scratch;
  int hits = 0;
  for (int i : order) {
    const Model& m = models[i];
    cache.get(m)->solve(m.default_loads(), kept, scratch);
    hits += cache.last_was_hit();
    const LinearStaticResult fresh = LinearSystem(m).solve(m.default_loads());
    ASSERT_EQ(fresh.status, SolveStatus::Succeeded) << fresh.message;
    expect_same(kept, fresh, "model " + std::to_string(i));
  }
  EXPECT_EQ(hits, 7);  // 0 -> 4, 4 -> 4, 4 -> 0, 2 -> 6, 1 -> 5, 3 -> 7, 7 -> 7
  // The loads reached the result: twice and a half the tip load, a larger tip displacement.
  const Model& a = models[0];
  const Model& b = models[4];
  const int tip = a.find_node("T");
  const double va = LinearSystem(a).solve(a.default_loads()).u[6 * tip + 1];
  const double vb = cache.get(b)->solve(b.default_loads()).u[6 * tip + 1];
  EXPECT_LT(vb, va);
  EXPECT_LT(va, 0.0);
}

}  // namespace linear_system_cache_test
