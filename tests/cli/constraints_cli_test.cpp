// Skewed supports, ties, linear constraints and models carried by springs, through the program:
// exit codes (0 success, 2 bad input naming the pointer) and what results.json holds.
#include <gtest/gtest.h>

#include <cmath>

#include "support/cli_case.hpp"
#include "support/models.hpp"

namespace constraints_cli_test {

using namespace beamfea;
using nlohmann::json;

namespace {

// The cantilever A-B (A fixed, tip load -1000 along y at B), with a second cantilever A2-B2 beside
// it (same section, along x at z = 1).
json two_cantilevers() {
  json d = test::linear_cantilever(-1000.0);
  d["nodes"].push_back({{"id", "A2"}, {"xyz", {0, 0, 1}}});
  d["nodes"].push_back({{"id", "B2"}, {"xyz", {2, 0, 1}}});
  json e = d["elements"][0];
  e["id"] = "e2";
  e["nodes"] = {"A2", "B2"};
  d["elements"].push_back(e);
  d["supports"].push_back({{"node", "A2"}, {"fix", "all"}});
  return d;
}

}  // namespace

TEST(ConstraintsCli, TiedTipsShareTheLoadAndReportTheTieForce) {
  // Two equal cantilevers tied at the tips on uy: each takes half the load, the tie passes 500 on.
  json d = two_cantilevers();
  d["ties"] = {{{"nodes", {"B", "B2"}}, {"dofs", {"uy"}}}};
  const auto r = test::run_model("cli_tie", d);
  ASSERT_EQ(r.code, 0) << r.message;
  const json lin = r.results()["analyses"]["lin"];
  const double uy = lin["nodes"]["B"]["displacement"][1].get<double>();
  EXPECT_NEAR(lin["nodes"]["B2"]["displacement"][1].get<double>() / uy, 1.0, 1e-12);
  // Half the load on one cantilever: P L^3 / 3 E Iz with P = 500, L = 2, E = 2.1e11, Iz = 3e-6.
  EXPECT_NEAR(uy / (-500.0 * 8.0 / (3 * 2.1e11 * 3e-6)), 1.0, 1e-9);
  EXPECT_NEAR(lin["tie_forces"][0][1].get<double>(), -500.0, 1e-6);
}

TEST(ConstraintsCli, RedundantTieIsExitTwoNamingIt) {
  json d = two_cantilevers();
  d["ties"] = {{{"nodes", {"B", "B2"}}, {"dofs", {"uy"}}}, {{"nodes", {"B", "B2"}}, {"dofs", {"ux", "uy"}}}};
  test::expect_bad_input(test::run_model("cli_tie_redundant", d), {"/ties/1", "redundant", "node 'B2'", "uy"});
  test::expect_bad_input(test::run_model("cli_tie_redundant_check", d, "check"), {"/ties/1", "redundant"});
}

TEST(ConstraintsCli, ContradictoryConstraintIsExitTwoNamingIt) {
  json d = two_cantilevers();
  d["constraints"] = {{{"terms", {{{"node", "A"}, {"dof", "uz"}, {"coefficient", 1.0}}}}, {"value", 0.01}}};
  test::expect_bad_input(test::run_model("cli_constraint_contradicts", d), {"/constraints/0", "contradicts"});
}

TEST(ConstraintsCli, BadTiesConstraintsAndAxesAreExitTwo) {
  json d = two_cantilevers();
  d["ties"] = {{{"nodes", {"B", "B2"}}, {"dof", {"uy"}}}};
  test::expect_bad_input(test::run_model("cli_tie_key", d), {"/ties/0", "dofs"});
  d = two_cantilevers();
  d["ties"] = {{{"nodes", {"B", "B"}}, {"dofs", {"uy"}}}};
  test::expect_bad_input(test::run_model("cli_tie_self", d), {"/ties/0/nodes", "node 'B'"});
  d = two_cantilevers();
  d["constraints"] = {{{"terms", {{{"node", "B"}, {"dof", "uq"}, {"coefficient", 1.0}}}}}};
  test::expect_bad_input(test::run_model("cli_constraint_dof", d), {"/constraints/0/terms/0/dof"});
  d = two_cantilevers();
  d["supports"][0]["axes"] = {{1, 0, 0}, {0, 1, 0}, {0, 0.5, 1}};
  test::expect_bad_input(test::run_model("cli_axes", d), {"/supports/0/axes", "orthonormal"});
  d = two_cantilevers();
  d["supports"][0]["axes"] = {{1, 0, 0}, {0, 1, 0}, {0, 0, -1}};
  test::expect_bad_input(test::run_model("cli_axes_left", d), {"/supports/0/axes", "left-handed"});
}

TEST(ConstraintsCli, InclinedRollerWritesBothReactions) {
  // The tip B on a roller whose frame is turned by 90 degrees about z holding its uy (global -x):
  // the tip's axial reaction is in both frames, with opposite signs along global x and frame y.
  json d = test::linear_cantilever(-1000.0);
  d["loads"] = {{{"node", "B"}, {"force", {400.0, 0, 0}}}};
  d["supports"].push_back({{"node", "B"}, {"fix", {"uy"}}, {"axes", {{0, 1, 0}, {-1, 0, 0}, {0, 0, 1}}}});
  const auto r = test::run_model("cli_roller", d);
  ASSERT_EQ(r.code, 0) << r.message;
  const json B = r.results()["analyses"]["lin"]["nodes"]["B"];
  // The load acts where B is held along x: the roller takes all of it, -400 along x, which is
  // +400 along the frame's y = -x and nothing along its x.
  EXPECT_NEAR(B["reaction"][0].get<double>(), -400.0, 1e-6);
  EXPECT_NEAR(B["reaction_local"][1].get<double>(), 400.0, 1e-6);
  EXPECT_NEAR(B["reaction_local"][0].get<double>(), 0.0, 1e-6);
}

TEST(ConstraintsCli, ANodeOnSpringsIsAValidModel) {
  json d{{"nodes", {{{"id", "G"}, {"xyz", {0, 0, 0}}}, {{"id", "N"}, {"xyz", {0, 0, 0}}}}},
         {"joints", {{{"id", "s"}, {"type", "virtual_spring"}, {"nodes", {"G", "N"}}, {"stiffness", {1e6, 1e6, 1e6, 1e3, 1e3, 1e3}}}}},
         {"supports", {{{"node", "G"}, {"fix", "all"}}}},
         {"loads", {{{"node", "N"}, {"force", {0, 0, -50.0}}}}},
         {"analyses", {{{"id", "lin"}, {"type", "linear_static"}}}}};
  const auto r = test::run_model("cli_springs", d);
  ASSERT_EQ(r.code, 0) << r.message;
  EXPECT_NEAR(r.results()["analyses"]["lin"]["nodes"]["N"]["displacement"][2].get<double>(), -50.0 / 1e6, 1e-18);
  d["joints"] = json::array();
  test::expect_bad_input(test::run_model("cli_nothing", d), {"/elements", "nothing carries a load"});
}

}  // namespace constraints_cli_test
