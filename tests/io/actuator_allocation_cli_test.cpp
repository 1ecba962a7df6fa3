// Bad input to the "actuator_allocation" analysis, through the command-line program: exit code 2
// and a message that names the thing at fault.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <sys/wait.h>

#include "support/models.hpp"

namespace actuator_allocation_cli_test {

namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

// The two-link chain (tests/support/models.hpp) with an actuator allocation over both joints.
json chain() {
  json d = beamfea::test::two_link_chain();
  d["analyses"] = {{{"id", "alloc"}, {"type", "actuator_allocation"}, {"platform_node", "P"},
                    {"candidate_joints", {"JA", "JB"}}, {"actuators", 2}, {"actuator_stiffness", 1.0},
                    {"directions", {"rz", "uy"}}}};
  return d;
}

struct CliRun {
  int code = -1;
  std::string output;
};

CliRun run(const json& doc, const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("beamfea_alloc_cli_" + name);
  fs::create_directories(dir);
  const fs::path file = dir / "model.json";
  std::ofstream(file) << doc.dump(1);
  const std::string cmd = std::string("\"") + BEAMFEA_EXE + "\" run \"" + file.string() + "\" --out \"" +
                          (dir / "out").string() + "\" --quiet --no-vtk 2>&1";
  CliRun r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 512> buf{};
  while (fgets(buf.data(), buf.size(), p)) r.output += buf.data();
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

TEST(ActuatorAllocationCli, ValidChainRunsAndRanksOneScheme) {
  const CliRun r = run(chain(), "valid");
  EXPECT_EQ(r.code, 0) << r.output;
}

TEST(ActuatorAllocationCli, UnknownCandidateJointExitsTwoNamingIt) {
  json d = chain();
  d["analyses"][0]["candidate_joints"] = {"JA", "J9"};
  const CliRun r = run(d, "unknown_joint");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("J9"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("/analyses/0/candidate_joints/1"), std::string::npos) << r.output;
}

TEST(ActuatorAllocationCli, MoreActuatorsThanCandidatesExitsTwo) {
  json d = chain();
  d["analyses"][0]["actuators"] = 3;
  const CliRun r = run(d, "too_many");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("3 actuators but only 2 candidate"), std::string::npos) << r.output;
}

TEST(ActuatorAllocationCli, PlatformNodeNotOnTheModelExitsTwoNamingIt) {
  json d = chain();
  d["analyses"][0]["platform_node"] = "Q";
  const CliRun r = run(d, "no_node");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("'Q'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("/analyses/0/platform_node"), std::string::npos) << r.output;
}

TEST(ActuatorAllocationCli, PoseThatSeparatesAJointExitsTwoNamingTheJoint) {
  json d = chain();
  // B1 moves, its partner B2 follows automatically; moving both apart is an error.
  d["analyses"][0]["poses"] = {{{"id", "bad"}, {"nodes", {{{"node", "B1"}, {"xyz", {0, 1, 0}}},
                                                          {{"node", "B2"}, {"xyz", {0, 1.5, 0}}}}}}};
  const CliRun r = run(d, "bad_pose");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("joint 'JB'"), std::string::npos) << r.output;
}

// load_case (docs/analyses/actuator-allocation.md, "With a load case").
TEST(ActuatorAllocationCli, UnknownLoadCaseExitsTwoNamingIt) {
  json d = chain();
  d["analyses"][0]["load_case"] = "wind";
  const CliRun r = run(d, "unknown_case");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("/analyses/0/load_case"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("'wind'"), std::string::npos) << r.output;
}

TEST(ActuatorAllocationCli, RankingByALoadedStiffnessWithoutALoadCaseExitsTwo) {
  json d = chain();
  d["analyses"][0]["rank_by"] = {{"stiffness", "loaded_total"}, {"direction", "uy"}};
  const CliRun r = run(d, "loaded_rank");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("/analyses/0/rank_by/stiffness"), std::string::npos) << r.output;
}

TEST(ActuatorAllocationCli, LoadCaseReportsEffortsDisplacementAndLoadedStiffness) {
  json d = chain();
  d["load_cases"] = {{{"id", "tip"}, {"loads", {{{"node", "P"}, {"force", {0, -2, 0}}}}}}};
  d["analyses"][0]["load_case"] = "tip";
  d["analyses"][0]["rank_by"] = {{"stiffness", "loaded_total"}, {"direction", "uy"}};
  const CliRun r = run(d, "load_case");
  ASSERT_EQ(r.code, 0) << r.output;
  const fs::path out = fs::temp_directory_path() / "beamfea_alloc_cli_load_case" / "out";
  json res;
  std::ifstream(out / "results.json") >> res;
  const json& a = res["analyses"]["alloc"];
  EXPECT_EQ(a["load_case"], "tip");
  const json& pose = a["schemes"][0]["poses"][0];
  // Statics of the straight chain A (x = 0) - B (x = 1) - P (x = 2), force -2 along y at P: the
  // motors hold the moments about their axes, tau_A = 2 x 2 = 4, tau_B = 1 x 2 = 2.
  ASSERT_EQ(pose["actuator_efforts"].size(), 2u);
  EXPECT_NEAR(pose["actuator_efforts"][0]["effort"].get<double>(), 4.0, 1e-9);
  EXPECT_NEAR(pose["actuator_efforts"][1]["effort"].get<double>(), 2.0, 1e-9);
  // Rigid links, unit springs: q = -tau, uy(P) = 2 q_A + 1 q_B = -10.
  EXPECT_NEAR(pose["platform_displacement"]["actuated"]["uy"].get<double>(), -10.0, 1e-9);
  EXPECT_TRUE(pose["loaded_stiffness"]["total"].is_array());
  EXPECT_TRUE(pose["loaded_stiffness"]["components"]["total"]["uy"].is_number());
  EXPECT_EQ(a["rank_by"]["stiffness"], "loaded_total");
  EXPECT_TRUE(fs::exists(out / "alloc_efforts.csv"));
  EXPECT_TRUE(fs::exists(out / "alloc_load_case.csv"));
}

}  // namespace

}  // namespace actuator_allocation_cli_test
