// The "indices" of a stiffness result, end to end (input spec to results), on a cantilever A-B
// (A clamped, length L along x). Closed forms (Euler-Bernoulli cantilever, end loads at B, the
// other end loads free): ux = P L / (E A), uy = P L^3 / (3 E Iz), uz = P L^3 / (3 E Iy); end
// moments: rx = M L / (G J), ry = M L / (E Iy), rz = M L / (E Iz); the coupling of a force Py and
// a moment Mz: uy = Mz L^2 / (2 E Iz), rz = Py L^2 / (2 E Iz) (Gere & Goodno, Mechanics of
// Materials, table G-1, cases 4 and 6).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "io/run.hpp"
#include "support/errors.hpp"
#include "support/models.hpp"

namespace stiffness_indices_output_test {

using nlohmann::json;

constexpr double L = 2.0, E = 2.1e11, G = 8.0e10, A = 1.0e-3, Iy = 2.0e-6, Iz = 3.0e-6, J = 4.0e-6;
constexpr double kRel = 1e-9;  // the condensation's rounding on a one-element cantilever

json cantilever_with(const json& analysis) {
  json doc = beamfea::test::cantilever(L, E, G, A, Iy, Iz, J);
  doc["analyses"] = json::array({analysis});
  return doc;
}

beamfea::ojson indices_of(const json& doc) {
  const beamfea::Model model = beamfea::load_and_check(doc);
  const beamfea::RunReport report = beamfea::run_document(model, doc, {});
  EXPECT_FALSE(report.failed);
  const beamfea::ojson& k = report.results["analyses"]["k"];
  EXPECT_EQ(k["status"], "ok") << k.dump();
  return k["indices"];
}

void expect_direction(const beamfea::ojson& d, double x, double y, double z) {
  ASSERT_EQ(d.size(), 3u);
  EXPECT_NEAR(d[0].get<double>(), x, 1e-9);
  EXPECT_NEAR(d[1].get<double>(), y, 1e-9);
  EXPECT_NEAR(d[2].get<double>(), z, 1e-9);
}

TEST(StiffnessIndicesOutput, ACantileverTipHasTheReciprocalsOfItsTipCompliancesAsIndices) {
  const beamfea::ojson ix = indices_of(cantilever_with({{"id", "k"}, {"type", "stiffness"}, {"node", "B"}}));
  const double k_axial = E * A / L, k_z = 3 * E * Iy / (L * L * L);
  const auto& t = ix["translational"];
  EXPECT_NEAR(t["min"].get<double>(), k_z, kRel * k_z);  // Iy < Iz: the softest is z
  EXPECT_NEAR(t["max"].get<double>(), k_axial, kRel * k_axial);
  expect_direction(t["directions"][0], 0, 0, 1);
  expect_direction(t["directions"][1], 1, 0, 0);
  EXPECT_NEAR(ix["condition_translational"].get<double>(), k_axial / k_z, kRel * k_axial / k_z);
  EXPECT_TRUE(t["blocked"].empty());
  EXPECT_TRUE(t["free"].empty());
  // Moments: G J = 3.2e5 < E Iy = 4.2e5 < E Iz = 6.3e5.
  const auto& r = ix["rotational"];
  EXPECT_NEAR(r["min"].get<double>(), G * J / L, kRel * G * J / L);
  EXPECT_NEAR(r["max"].get<double>(), E * Iz / L, kRel * E * Iz / L);
  expect_direction(r["directions"][0], 1, 0, 0);
  expect_direction(r["directions"][1], 0, 0, 1);
  EXPECT_NEAR(ix["condition_rotational"].get<double>(), E * Iz / (G * J), kRel * E * Iz / (G * J));
  EXPECT_FALSE(ix.contains("along"));
  EXPECT_FALSE(ix.contains("deflection"));
}

TEST(StiffnessIndicesOutput, AlongAndDeflectionFollowTheTipCompliance) {
  const json spec = {{"id", "k"},
                     {"type", "stiffness"},
                     {"node", "B"},
                     {"directions", {{1, 1, 0}, {0, 0, 3}}},
                     {"reference_wrench", {0, 100, 0, 0, 0, 50}}};
  const beamfea::ojson ix = indices_of(cantilever_with(spec));
  const double cx = L / (E * A), cy = L * L * L / (3 * E * Iz), cz = L * L * L / (3 * E * Iy);
  // d = (1, 1, 0) / sqrt 2: d^T C d = (cx + cy) / 2.
  ASSERT_EQ(ix["along"].size(), 2u);
  EXPECT_NEAR(ix["along"][0].get<double>(), 2 / (cx + cy), kRel * 2 / (cx + cy));
  EXPECT_NEAR(ix["along"][1].get<double>(), 1 / cz, kRel / cz);
  // Py = 100 and Mz = 50 at the tip.
  const double uy = 100 * cy + 50 * L * L / (2 * E * Iz), rz = 100 * L * L / (2 * E * Iz) + 50 * L / (E * Iz);
  const auto& u = ix["deflection"];
  ASSERT_EQ(u.size(), 6u);
  EXPECT_NEAR(u[1].get<double>(), uy, kRel * uy);
  EXPECT_NEAR(u[5].get<double>(), rz, kRel * rz);
  for (int i : {0, 2, 3, 4}) EXPECT_NEAR(u[i].get<double>(), 0.0, 1e-12 * uy);
  EXPECT_NEAR(ix["deflection_norm"].get<double>(), uy, kRel * uy);
}

TEST(StiffnessIndicesOutput, ASupportedDirectionIsLeftOutOfMinMaxAndCondition) {
  json doc = cantilever_with({{"id", "k"}, {"type", "stiffness"}, {"node", "B"}, {"directions", {{1, 0, 0}}}});
  doc["supports"].push_back({{"node", "B"}, {"fix", {"ux"}}});
  const beamfea::ojson ix = indices_of(doc);
  const double k_y = 3 * E * Iz / (L * L * L), k_z = 3 * E * Iy / (L * L * L);
  const auto& t = ix["translational"];
  EXPECT_NEAR(t["min"].get<double>(), k_z, kRel * k_z);
  EXPECT_NEAR(t["max"].get<double>(), k_y, kRel * k_y);  // not E A / L, nor infinite
  EXPECT_NEAR(ix["condition_translational"].get<double>(), Iz / Iy, kRel * Iz / Iy);
  ASSERT_EQ(t["blocked"].size(), 1u);
  expect_direction(t["blocked"][0], 1, 0, 0);
  EXPECT_TRUE(ix["along"][0].is_null());  // infinitely stiff along ux
}

TEST(StiffnessIndicesOutput, AClampedNodeHasNoIndices) {
  const beamfea::ojson ix = indices_of(cantilever_with({{"id", "k"}, {"type", "stiffness"}, {"node", "A"}}));
  for (const char* b : {"translational", "rotational"}) {
    EXPECT_TRUE(ix[b]["min"].is_null());
    EXPECT_TRUE(ix[b]["max"].is_null());
    EXPECT_TRUE(ix[b]["directions"].empty());
    EXPECT_EQ(ix[b]["blocked"].size(), 3u);
  }
  EXPECT_TRUE(ix["condition_translational"].is_null());
  EXPECT_TRUE(ix["condition_rotational"].is_null());
}

// C behind a spherical joint at B spins freely; D, on a rigid link C-D of length a along y, then
// moves freely across the link (x and z) and along it as the tip B does (uy).
TEST(StiffnessIndicesOutput, FreeDirectionsMakeMinZeroAndTheConditionNull) {
  json doc = cantilever_with({{"id", "k"}, {"type", "stiffness"}, {"node", "D"}, {"reference_wrench", {0, 0, 1, 0, 0, 0}}});
  const double a = 0.5;
  doc["nodes"].push_back(json{{"id", "C"}, {"xyz", {L, 0, 0}}});
  doc["nodes"].push_back(json{{"id", "D"}, {"xyz", {L, a, 0}}});
  doc["joints"] = json::array({json{{"id", "S"}, {"type", "spherical"}, {"nodes", {"B", "C"}}}});
  doc["elements"].push_back(json{{"id", "r"}, {"type", "rigid"}, {"nodes", {"C", "D"}}});
  const beamfea::ojson ix = indices_of(doc);
  const auto& t = ix["translational"];
  const double k_y = 3 * E * Iz / (L * L * L);
  EXPECT_EQ(t["min"].get<double>(), 0.0);
  EXPECT_NEAR(t["max"].get<double>(), k_y, kRel * k_y);
  expect_direction(t["directions"][1], 0, 1, 0);
  EXPECT_EQ(t["free"].size(), 2u);
  EXPECT_NEAR(std::abs(t["directions"][0][1].get<double>()), 0.0, 1e-9);  // a free direction is across y
  EXPECT_TRUE(ix["condition_translational"].is_null());
  EXPECT_EQ(ix["rotational"]["min"].get<double>(), 0.0);
  EXPECT_EQ(ix["rotational"]["free"].size(), 3u);
  EXPECT_TRUE(ix["condition_rotational"].is_null());
  // A force along z drives a free direction: the deflection is unbounded.
  EXPECT_TRUE(ix["deflection"].is_null());
  EXPECT_TRUE(ix["deflection_norm"].is_null());
}

TEST(StiffnessIndicesOutput, APathStepCarriesTheIndicesOfItsStiffnessNode) {
  // At the unloaded start (load factor 0) the path's tangent is the linear stiffness: the indices
  // are the cantilever tip's closed forms above.
  json doc = cantilever_with({{"id", "k"},
                              {"type", "path"},
                              {"stiffness_node", "B"},
                              {"control", {{"load_factor", 1.0}, {"increments", 2}}}});
  doc["loads"] = json::array({json{{"node", "B"}, {"force", {0, -1000, 0}}}});
  const beamfea::Model model = beamfea::load_and_check(doc);
  const beamfea::RunReport report = beamfea::run_document(model, doc, {});
  ASSERT_FALSE(report.failed);
  const beamfea::ojson& steps = report.results["analyses"]["k"]["steps"];
  ASSERT_GE(steps.size(), 2u);
  ASSERT_EQ(steps[0]["load_factor"].get<double>(), 0.0);
  const beamfea::ojson& ix = steps[0]["indices"];
  const double k_axial = E * A / L, k_z = 3 * E * Iy / (L * L * L);
  EXPECT_NEAR(ix["translational"]["min"].get<double>(), k_z, 1e-7 * k_z);
  EXPECT_NEAR(ix["translational"]["max"].get<double>(), k_axial, 1e-7 * k_axial);
  EXPECT_NEAR(ix["condition_rotational"].get<double>(), E * Iz / (G * J), 1e-7 * E * Iz / (G * J));
  for (const auto& step : steps) EXPECT_TRUE(step["indices"]["translational"]["min"].is_number());
}

TEST(StiffnessIndicesOutput, BadDirectionsAndWrenchesAreInputErrorsAtTheirPointers) {
  const auto error = [](const json& extra) {
    json spec = {{"id", "k"}, {"type", "stiffness"}, {"node", "B"}};
    spec.update(extra);
    const json doc = cantilever_with(spec);
    const auto e = beamfea::test::thrown<beamfea::InputError>([&] { beamfea::load_and_check(doc); });
    return e ? std::string(e->what()) : std::string("no error");
  };
  EXPECT_NE(error({{"directions", {{1, 0, 0}, {0, 0, 0}}}}).find("/analyses/0/directions/1"), std::string::npos);
  EXPECT_NE(error({{"directions", {{1, 0}}}}).find("/analyses/0/directions/0"), std::string::npos);
  EXPECT_NE(error({{"reference_wrench", {1, 2, 3}}}).find("/analyses/0/reference_wrench"), std::string::npos);
  EXPECT_NE(error({{"ellipsoid", 1}}).find("/analyses/0/ellipsoid"), std::string::npos);
  EXPECT_NE(error({{"direction", {{1, 0, 0}}}}).find("did you mean 'directions'"), std::string::npos);
}

}  // namespace stiffness_indices_output_test
