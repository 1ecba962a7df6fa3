// A stiffness result tells the three kinds of direction apart: `compliance` where the node moves
// against finite stiffness, `unbounded_directions` (with `compliance_bounded` false) where it moves
// freely and the compliance holds 0 only by convention, `rigid_directions` where it cannot move.
//
// Model: a cantilever A-B (A clamped, length L along x) and a node C at B's place behind a
// spherical joint. C translates with the tip (its translational compliance is the cantilever's) and
// spins freely. Closed forms (Euler-Bernoulli cantilever, end load): ux = P L / (E A),
// uy = P L^3 / (3 E Iz), uz = P L^3 / (3 E Iy).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "io/run.hpp"
#include "support/models.hpp"

namespace stiffness_directions_test {

using nlohmann::json;

constexpr double L = 2.0, E = 2.1e11, G = 8.0e10, A = 1.0e-3, Iy = 2.0e-6, Iz = 3.0e-6, J = 4.0e-6;

// With `spherical_tip`, the node C behind a spherical joint at B (then holding B alone leaves C's
// spin a mechanism: ask C or A).
beamfea::ojson stiffness_of(const std::string& node, bool spherical_tip = true) {
  json doc = beamfea::test::cantilever(L, E, G, A, Iy, Iz, J);
  if (spherical_tip) {
    doc["nodes"].push_back(json{{"id", "C"}, {"xyz", {L, 0, 0}}});
    doc["joints"] = json::array({json{{"id", "S"}, {"type", "spherical"}, {"nodes", {"B", "C"}}}});
  }
  doc["analyses"] = json::array({json{{"id", "k"}, {"type", "stiffness"}, {"node", node}}});
  const beamfea::Model model = beamfea::load_and_check(doc);
  const beamfea::RunReport report = beamfea::run_document(model, doc, {});
  EXPECT_FALSE(report.failed);
  return report.results["analyses"]["k"];
}

// The squared norm of the projection of DOF d's unit vector on the span of orthonormal vectors.
double projection(const beamfea::ojson& vectors, int d) {
  double p = 0.0;
  for (const auto& v : vectors) p += std::pow(v[d].get<double>(), 2);
  return p;
}

TEST(StiffnessDirections, ANodeThatSpinsFreelyHasItsRotationsMarkedUnbounded) {
  const beamfea::ojson k = stiffness_of("C");
  ASSERT_EQ(k["status"], "ok") << k.dump();
  // Translations: the cantilever's tip compliance (closed forms above), 1e-9 relative.
  EXPECT_NEAR(k["compliance"][0][0].get<double>(), L / (E * A), 1e-9 * L / (E * A));
  EXPECT_NEAR(k["compliance"][1][1].get<double>(), L * L * L / (3 * E * Iz), 1e-9 * L * L * L / (3 * E * Iz));
  EXPECT_NEAR(k["compliance"][2][2].get<double>(), L * L * L / (3 * E * Iy), 1e-9 * L * L * L / (3 * E * Iy));
  // Rotations: free. The compliance holds 0 there, and the result says why.
  for (int d = 3; d < 6; ++d) EXPECT_EQ(k["compliance"][d][d].get<double>(), 0.0);
  EXPECT_EQ(k["compliance_bounded"], false);
  ASSERT_EQ(k["unbounded_directions"].size(), 3u);
  EXPECT_EQ(k["unbounded_directions"], k["null_space"]);
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(projection(k["unbounded_directions"], d), 0.0, 1e-12) << "translation " << d;
  for (int d = 3; d < 6; ++d) EXPECT_NEAR(projection(k["unbounded_directions"], d), 1.0, 1e-12) << "rotation " << d;
  EXPECT_TRUE(k["rigid_directions"].empty());
}

TEST(StiffnessDirections, AClampedNodeIsRigidNotUnbounded) {
  const beamfea::ojson k = stiffness_of("A");
  ASSERT_EQ(k["status"], "ok") << k.dump();
  EXPECT_EQ(k["compliance_bounded"], true);
  EXPECT_TRUE(k["unbounded_directions"].empty());
  EXPECT_EQ(k["rigid_directions"].size(), 6u);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) EXPECT_EQ(k["compliance"][i][j].get<double>(), 0.0);
}

TEST(StiffnessDirections, AResistedNodeHasABoundedComplianceInEveryDirection) {
  const beamfea::ojson k = stiffness_of("B", false);
  ASSERT_EQ(k["status"], "ok") << k.dump();
  EXPECT_EQ(k["compliance_bounded"], true);
  EXPECT_TRUE(k["unbounded_directions"].empty());
  EXPECT_TRUE(k["rigid_directions"].empty());
  // Tip rotation about z under an end moment: L / (E Iz).
  EXPECT_NEAR(k["compliance"][5][5].get<double>(), L / (E * Iz), 1e-9 * L / (E * Iz));
}

}  // namespace stiffness_directions_test
