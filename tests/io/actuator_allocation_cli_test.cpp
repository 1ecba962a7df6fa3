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

namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

// A two-link planar chain (2 DOF) ending at P: joints A (ground) and B.
json chain() {
  return {{"nodes", {{{"id", "G"}, {"xyz", {0, 0, 0}}}, {{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B1"}, {"xyz", {1, 0, 0}}},
                     {{"id", "B2"}, {"xyz", {1, 0, 0}}}, {{"id", "P"}, {"xyz", {2, 0, 0}}}}},
          {"materials", {{{"id", "m"}, {"E", 1.0}, {"nu", 0.3}}}},
          {"sections", {{{"id", "s"}, {"shape", "circle"}, {"r", 0.05}}}},
          {"elements", {{{"id", "L1"}, {"type", "beam"}, {"nodes", {"A", "B1"}}, {"material", "m"}, {"section", "s"}},
                        {{"id", "L2"}, {"type", "beam"}, {"nodes", {"B2", "P"}}, {"material", "m"}, {"section", "s"}}}},
          {"joints", {{{"id", "JA"}, {"type", "revolute"}, {"nodes", {"G", "A"}}, {"axes", {{0, 0, 1}}}},
                      {{"id", "JB"}, {"type", "revolute"}, {"nodes", {"B1", "B2"}}, {"axes", {{0, 0, 1}}}}}},
          {"supports", {{{"node", "G"}, {"fix", "all"}}}},
          {"analyses", {{{"id", "alloc"}, {"type", "actuator_allocation"}, {"platform_node", "P"},
                         {"candidate_joints", {"JA", "JB"}}, {"actuators", 2}, {"actuator_stiffness", 1.0},
                         {"directions", {"rz", "uy"}}}}}};
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

}  // namespace
