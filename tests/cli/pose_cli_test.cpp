// Poses through the program (docs/poses.md): a bad pose is exit 2 naming its joint or node, with
// --out left as it was; a good one writes results.json with the top-level "pose".
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "support/cli_case.hpp"

namespace pose_cli_test {

using nlohmann::json;

// A pendulum: ground G, revolute q (a spring) at the origin, a rigid link to the tip T at (1, 0, 0),
// and a cantilever beam hanging from the tip so that the stiffness analysis has something to bend.
json pendulum() {
  return json{{"nodes", {{{"id", "G"}, {"xyz", {0, 0, 0}}}, {{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "T"}, {"xyz", {1, 0, 0}}}}},
              {"materials", {{{"id", "m"}, {"E", 2.1e11}, {"G", 8.1e10}}}},
              {"sections", {{{"id", "s"}, {"A", 1e-3}, {"Iy", 2e-6}, {"Iz", 2e-6}, {"J", 4e-6}}}},
              {"elements", {{{"id", "link"}, {"type", "beam"}, {"nodes", {"A", "T"}}, {"material", "m"}, {"section", "s"}}}},
              {"joints",
               {{{"id", "q"}, {"type", "revolute"}, {"nodes", {"G", "A"}}, {"axes", {{0, 0, 1}}}, {"stiffness", {100.0}},
                 {"limits", {{-1.0, 1.0}}}}}},
              {"supports", {{{"node", "G"}, {"fix", "all"}}}},
              {"analyses", {{{"id", "K"}, {"type", "stiffness"}, {"node", "T"}}}}};
}

TEST(PoseCli, APoseIsWrittenToResults) {
  json d = pendulum();
  d["pose"] = {{"joints", {{"q", 0.5}}}};
  const auto c = beamfea::test::run_model("pose_ok", d);
  ASSERT_EQ(c.code, 0) << c.message;
  const json r = c.results();
  EXPECT_DOUBLE_EQ(r["pose"]["joints"]["q"].get<double>(), 0.5);
  EXPECT_NEAR(r["pose"]["nodes"]["T"][0].get<double>(), std::cos(0.5), 1e-15);
  EXPECT_NEAR(r["pose"]["nodes"]["T"][1].get<double>(), std::sin(0.5), 1e-15);
}

TEST(PoseCli, BadPosesAreExitTwoNamingTheCulprit) {
  json d = pendulum();
  d["pose"] = {{"joints", {{"nope", 0.1}}}};
  beamfea::test::expect_bad_input(beamfea::test::run_model("pose_unknown_joint", d), {"/pose/joints/nope", "unknown joint 'nope'"});
  d["pose"] = {{"joints", {{"q", 1.5}}}};
  beamfea::test::expect_bad_input(beamfea::test::run_model("pose_limit", d), {"/pose/joints/q", "outside its limits [-1.0, 1.0]"});
  d["pose"] = {{"nodes", {{{"node", "T"}, {"xyz", {0, 2, 0}}}}}};  // the tip stays on the unit circle
  beamfea::test::expect_bad_input(beamfea::test::run_model("pose_reach", d), {"node 'T'", "beyond reach"});
  d["pose"] = {{"nodes", {{{"node", "X"}, {"xyz", {0, 1, 0}}}}}};
  beamfea::test::expect_bad_input(beamfea::test::run_model("pose_unknown_node", d), {"/pose/nodes/0/node", "unknown node 'X'"});
  d["pose"] = {{"joints", {{"q", 0.1}}}, {"joint", {}}};
  beamfea::test::expect_bad_input(beamfea::test::run_model("pose_key", d), {"/pose/joint", "did you mean 'joints'"});
}

}  // namespace pose_cli_test
