// Second-order analysis and tension-only members through `beamfea run`: exit codes, results.json
// keys, the diverged run's message and kept linear step, bad input naming the field.
#include <gtest/gtest.h>

#include <cmath>

#include "support/cli_case.hpp"
#include "support/models.hpp"

namespace second_order_cli_test {

using namespace beamfea;
using nlohmann::json;

namespace {
constexpr double pi = 3.14159265358979323846;
const double E = 210e9, I = 1e-6, L = 3.0;
const double P_cr = pi * pi * E * I / (4 * L * L);  // Euler's cantilever (Timoshenko & Gere 1961, eq. 2.3)

// A cantilever column along x, clamped at A, compressed by P and pushed sideways by H at B, with
// one second_order analysis.
json column(double P, double H) {
  json d;
  d["nodes"] = json::array({{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {L, 0, 0}}}});
  d["materials"] = json::array({{{"id", "m"}, {"E", E}, {"G", 81e9}}});
  d["sections"] = json::array({{{"id", "s"}, {"A", 1e-3}, {"Iy", I}, {"Iz", I}, {"J", 2e-6}}});
  d["elements"] = json::array({{{"id", "col"}, {"type", "beam"}, {"nodes", {"A", "B"}}, {"material", "m"},
                                {"section", "s"}, {"orientation", {0, 0, 1}}, {"divisions", 16}}});
  d["supports"] = json::array({{{"node", "A"}, {"fix", {"ux", "uy", "uz", "rx", "ry", "rz"}}}});
  d["loads"] = json::array({{{"node", "B"}, {"force", {-P, H, 0}}}});
  d["analyses"] = json::array({{{"id", "pd"}, {"type", "second_order"}, {"tolerance", 1e-10}, {"max_iterations", 100}}});
  return d;
}
}  // namespace

// Below the critical load: exit 0, the tip deflection of the beam-column closed form
// H (tan kL - kL) / (k^3 EI), iterations and amplification (tip over H L^3 / (3 EI)).
TEST(SecondOrderCli, BelowTheCriticalLoadRunsWithIterationsAndAmplification) {
  const double P = 0.5 * P_cr, H = 1000.0;
  const auto c = test::run_model("so_below", column(P, H));
  ASSERT_EQ(c.code, 0) << c.message;
  const json r = c.results()["analyses"]["pd"];
  EXPECT_EQ(r["status"], "ok");
  const double k = std::sqrt(P / (E * I));
  const double exact = H * (std::tan(k * L) - k * L) / (k * k * k * E * I);
  const double tip = r["nodes"]["B"]["displacement"][1];
  EXPECT_NEAR(tip, exact, 1e-5 * exact);
  EXPECT_GE(r["iterations"].get<int>(), 1);
  EXPECT_NEAR(r["amplification"].get<double>(), tip / (H * L * L * L / (3 * E * I)), 1e-9);
  EXPECT_EQ(r["inactive_members"], json::array());
  EXPECT_TRUE(r["elements"]["col"].contains("stations"));
}

// Above it: exit 1, "second-order analysis diverged: load above the critical load factor X",
// X = P_cr / P, status failed, the linear step's displacements kept.
TEST(SecondOrderCli, AboveTheCriticalLoadExitsOneWithTheFactor) {
  const double P = 2.0 * P_cr, H = 1000.0;
  const auto c = test::run_model("so_above", column(P, H));
  EXPECT_EQ(c.code, 1) << c.message;
  const json r = c.results()["analyses"]["pd"];
  const std::string message = r["message"];
  EXPECT_NE(message.find("second-order analysis diverged: load above the critical load factor 0.49"), std::string::npos)
      << message;
  EXPECT_EQ(r["status"], "failed");
  EXPECT_NEAR(r["critical_load_factor"].get<double>(), 0.5, 1e-4);  // the 16-element buckling load's error
  const double linear = H * L * L * L / (3 * E * I);
  EXPECT_NEAR(r["nodes"]["B"]["displacement"][1].get<double>(), linear, 1e-9 * linear);
}

TEST(SecondOrderCli, BadSpecsAreExitTwoNamingTheField) {
  json d = column(1000.0, 1.0);
  d["analyses"][0]["geometric_stiffness"] = "moment";
  test::expect_bad_input(test::run_model("so_bad_kind", d), {"/analyses/0/geometric_stiffness", "expected full or axial"});
  d = column(1000.0, 1.0);
  d["analyses"][0]["max_iteration"] = 3;
  test::expect_bad_input(test::run_model("so_bad_key", d), {"/analyses/0", "max_iteration", "max_iterations"});
  d = column(1000.0, 1.0);
  d["elements"][0]["behaviour"] = "slack";
  test::expect_bad_input(test::run_model("so_bad_behaviour", d), {"/elements/0/behaviour", "tension_only"});
  d = column(1000.0, 1.0);
  d["analyses"][0] = {{"id", "k"}, {"type", "stiffness"}, {"node", "B"}, {"about", "second_order"}};
  test::expect_bad_input(test::run_model("so_about_without_case", d), {"/analyses/0/about", "load_case"});
}

// linear_static of a model with a tension-only member: inactive_members names the slack one, and a
// slack member that leaves a mechanism exits 1 naming it.
TEST(SecondOrderCli, LinearStaticNamesInactiveMembers) {
  json d = column(1000.0, 0.0);
  d["elements"][0]["behaviour"] = "compression_only";
  d["analyses"] = json::array({{{"id", "ls"}, {"type", "linear_static"}}});
  auto c = test::run_model("ls_compression_only", d);
  ASSERT_EQ(c.code, 0) << c.message;
  EXPECT_EQ(c.results()["analyses"]["ls"]["inactive_members"], json::array());
  d["elements"][0]["behaviour"] = "tension_only";
  c = test::run_model("ls_tension_only_slack", d);
  EXPECT_EQ(c.code, 1) << c.message;
  const std::string message = c.results()["analyses"]["ls"]["message"];
  EXPECT_NE(message.find("slack members 'col'"), std::string::npos) << message;
  EXPECT_EQ(c.results()["analyses"]["ls"]["status"], "mechanism");
  EXPECT_EQ(c.results()["analyses"]["ls"]["inactive_members"], json::array({"col"}));
}

}  // namespace second_order_cli_test
