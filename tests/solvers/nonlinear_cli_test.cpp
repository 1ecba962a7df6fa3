// "buckling" and "path" from the command line: result keys and files (a contract).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "nl_models.hpp"

namespace nonlinear_cli_test {

using namespace beamfea::test;
namespace fs = std::filesystem;

namespace {
constexpr double pi = 3.14159265358979323846;

json run_cli(const json& doc, const std::string& name, fs::path& dir) {
  dir = fs::temp_directory_path() / ("beamfea_nl_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path in = dir / "model.json";
  std::ofstream(in) << doc.dump(1);
  const std::string cmd = std::string(BEAMFEA_EXE) + " run " + in.string() + " --out " + (dir / "out").string() + " -q 2>&1";
  const int rc = std::system(cmd.c_str());
  EXPECT_EQ(rc, 0) << cmd;
  std::ifstream f(dir / "out" / "results.json");
  json r;
  f >> r;
  return r;
}
}  // namespace

TEST(NonlinearCli, BucklingWritesLoadFactorsModesAndOneVtuPerMode) {
  const double L = 2.0, EI = 210e9 * 1e-6;
  json d = straight_member(L, 8, 210e9, 81e9, 1e-3, 1e-6, 1e-6, 2e-6);
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  d["loads"].push_back(load("B", -1000.0, 0, 0));
  d["analyses"] = json::array({{{"id", "b"}, {"type", "buckling"}, {"modes", 3}}});
  fs::path dir;
  const json r = run_cli(d, "buckling", dir);
  const auto& b = r["analyses"]["b"];
  ASSERT_EQ(b["load_factors"].size(), 3u);
  EXPECT_NEAR(b["load_factors"][0].get<double>() * 1000.0 / (pi * pi * EI / (4 * L * L)), 1.0, 1e-4);
  EXPECT_LE(b["load_factors"][0].get<double>(), b["load_factors"][1].get<double>());
  EXPECT_EQ(b["modes"][0]["nodes"]["B"]["displacement"].size(), 6u);
  for (int k = 1; k <= 3; ++k) EXPECT_TRUE(fs::exists(dir / "out" / ("b_mode" + std::to_string(k) + ".vtu")));
  EXPECT_TRUE(fs::exists(dir / "out" / "b.pvd"));
  fs::remove_all(dir);
}

TEST(NonlinearCli, PathWritesStepsCriticalPointsCsvAndVtuPerStep) {
  const double L = 1.0, EI = 1.0;
  json d = straight_member(L, 8, 1.0, 1.0, 1e6, 10.0, 1.0, 10.0);
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  d["loads"].push_back(load("B", -pi * pi * EI / (4 * L * L), 0, 0));
  d["analyses"] = json::array({{{"id", "p"}, {"type", "path"}, {"track", {"B"}}, {"stiffness_node", "B"},
                                {"control", {{"arc_length", 0.1}, {"max", 0.15}}}, {"branch_switch", true},
                                {"stop", {{"steps", 8}}}}});
  fs::path dir;
  const json r = run_cli(d, "path", dir);
  const auto& p = r["analyses"]["p"];
  ASSERT_TRUE(p.contains("steps")) << r.dump(1);
  // Eight steps, plus the located bifurcation point that branch switching inserts.
  const std::size_t n = p["steps"].size();
  ASSERT_GE(n, 9u) << p["termination"];
  EXPECT_EQ(p["steps"][n - 1]["step"].get<std::size_t>(), n - 1);
  for (const char* k : {"load_factor", "control", "nodes", "negative_eigenvalues", "stable", "min_eigenvalue", "stiffness"})
    EXPECT_TRUE(p["steps"][3].contains(k)) << k;
  EXPECT_EQ(p["steps"][3]["nodes"]["B"]["displacement"].size(), 6u);
  ASSERT_GE(p["critical_points"].size(), 1u);
  for (const char* k : {"type", "load_factor", "step", "mode"}) EXPECT_TRUE(p["critical_points"][0].contains(k)) << k;
  EXPECT_EQ(p["critical_points"][0]["type"], "bifurcation");
  EXPECT_TRUE(p.contains("termination"));
  std::ifstream csv(dir / "out" / "p.csv");
  int rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, 1 + static_cast<int>(n));
  EXPECT_TRUE(fs::exists(dir / "out" / "p.pvd"));
  EXPECT_TRUE(fs::exists(dir / "out" / "p_step0.vtu"));
  EXPECT_TRUE(fs::exists(dir / "out" / ("p_step" + std::to_string(n - 1) + ".vtu")));
  fs::remove_all(dir);
}

}  // namespace nonlinear_cli_test
