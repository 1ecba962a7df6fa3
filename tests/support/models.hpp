#pragma once
// Small helpers shared by the tests: build models from JSON text and run the CLI (the files of
// the tests: support/files.hpp).
#include <sys/wait.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "core/model.hpp"
#include "io/model_reader.hpp"
#include "support/files.hpp"

namespace beamfea::test {

inline Model model_from(const nlohmann::json& doc) { return read_model(doc); }

struct CliResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Runs the beamfea executable with `args` and returns its exit code and output; `prefix` is a
// command put before it ("timeout 60 "). A death by a signal gives exit_code -1.
inline CliResult run_cli_with_prefix(const std::string& prefix, const std::string& args) {
  CliResult r;
  const std::string cmd = prefix + std::string(BEAMFEA_EXE) + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  while (std::fgets(buf, sizeof buf, p)) r.output += buf;
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// Runs the beamfea executable with `args` and returns its exit code and output.
inline CliResult run_cli(const std::string& args) { return run_cli_with_prefix("", args); }

// A cantilever along +x from node "A" (fixed) to node "B", with `divisions` elements.
inline nlohmann::json cantilever(double L, double E, double G, double A, double Iy, double Iz, double J, int divisions = 1) {
  using nlohmann::json;
  return json{{"nodes", json::array({{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {L, 0, 0}}}})},
              {"materials", json::array({{{"id", "m"}, {"E", E}, {"G", G}}})},
              {"sections", json::array({{{"id", "s"}, {"A", A}, {"Iy", Iy}, {"Iz", Iz}, {"J", J}}})},
              {"elements", json::array({{{"id", "e"}, {"type", "beam"}, {"nodes", {"A", "B"}}, {"material", "m"},
                                         {"section", "s"}, {"orientation", {0, 0, 1}}, {"divisions", divisions}}})},
              {"supports", json::array({{{"node", "A"}, {"fix", "all"}}})},
              {"loads", json::array()}};
}

// A steel cantilever A-B of length 2 (A fixed) in `divisions` elements, the tip force (0, Py, 0)
// at B and one linear analysis "lin": the small model of the tests of the program's input and
// output.
inline nlohmann::json linear_cantilever(double Py, int divisions = 1) {
  nlohmann::json d = cantilever(2.0, 2.1e11, 8.1e10, 1e-3, 2e-6, 3e-6, 1e-6, divisions);
  d["loads"] = {{{"node", "B"}, {"force", {0, Py, 0}}}};
  d["analyses"] = {{{"id", "lin"}, {"type", "linear_static"}}};
  return d;
}

// A two-link planar chain (2 DOF) ending at node P: revolute joints JA (ground G to link L1 at A)
// and JB (L1's end B1 to L2's start B2), both about z; unit-modulus circular links; no loads.
inline nlohmann::json two_link_chain() {
  using nlohmann::json;
  return {{"nodes", {{{"id", "G"}, {"xyz", {0, 0, 0}}}, {{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B1"}, {"xyz", {1, 0, 0}}},
                     {{"id", "B2"}, {"xyz", {1, 0, 0}}}, {{"id", "P"}, {"xyz", {2, 0, 0}}}}},
          {"materials", {{{"id", "m"}, {"E", 1.0}, {"nu", 0.3}}}},
          {"sections", {{{"id", "s"}, {"shape", "circle"}, {"r", 0.05}}}},
          {"elements", {{{"id", "L1"}, {"type", "beam"}, {"nodes", {"A", "B1"}}, {"material", "m"}, {"section", "s"}},
                        {{"id", "L2"}, {"type", "beam"}, {"nodes", {"B2", "P"}}, {"material", "m"}, {"section", "s"}}}},
          {"joints", {{{"id", "JA"}, {"type", "revolute"}, {"nodes", {"G", "A"}}, {"axes", {{0, 0, 1}}}},
                      {{"id", "JB"}, {"type", "revolute"}, {"nodes", {"B1", "B2"}}, {"axes", {{0, 0, 1}}}}}},
          {"supports", {{{"node", "G"}, {"fix", "all"}}}}};
}

}  // namespace beamfea::test
