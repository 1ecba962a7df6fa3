#pragma once
// Small helpers shared by the tests: build models from JSON text and run the CLI.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/model.hpp"
#include "io/model_reader.hpp"

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

// A fresh temporary folder for one test.
inline std::filesystem::path temp_dir(const std::string& name) {
  auto d = std::filesystem::temp_directory_path() / ("beamfea_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

inline void write_file(const std::filesystem::path& p, const std::string& text) {
  std::ofstream out(p);
  out << text;
}

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

}  // namespace beamfea::test
