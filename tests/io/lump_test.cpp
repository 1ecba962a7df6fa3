// Link springs from models ("stiffness_from_model") and generated lumped models (io/lump.hpp):
// the condensed spring equals the closed-form cantilever spring on a one-member link, and a serial
// arm's lumped model has the beam model's tip compliance (condensation is exact for a tree).
#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "io/lump.hpp"
#include "io/model_reader.hpp"
#include "io/run.hpp"
#include "solvers/condensed_stiffness.hpp"
#include "support/cli_case.hpp"
#include "support/files.hpp"

namespace lump_test {

namespace {

using nlohmann::json;

constexpr double E = 7.0e10, G = 2.6e10;

json materials() { return {{{"id", "al"}, {"E", E}, {"G", G}}}; }
json sections() {
  return {{{"id", "tube"}, {"shape", "tube"}, {"d", 0.04}, {"t", 0.003}},
          {{"id", "rect"}, {"A", 6e-4}, {"Iy", 2e-8}, {"Iz", 4.5e-8}, {"J", 4.2e-8}, {"ky", 1.2}, {"kz", 1.2}}};
}

// A model whose joint "s" is a virtual spring with `spring` (the stiffness key and its value).
json spring_model(const json& spring) {
  json j = {{"id", "s"}, {"type", "virtual_spring"}, {"nodes", {"P", "Q"}}};
  j.update(spring);
  return {{"nodes", {{{"id", "O"}, {"xyz", {0, 0, 0}}}, {{"id", "P"}, {"xyz", {1, 0, 0}}}, {{"id", "Q"}, {"xyz", {1, 0, 0}}}}},
          {"materials", materials()},
          {"sections", sections()},
          {"elements", {{{"id", "r"}, {"type", "rigid"}, {"nodes", {"O", "P"}}}}},
          {"joints", {j}},
          {"supports", {{{"node", "O"}, {"fix", "all"}}}}};
}

// A one-member link model A-B along x of length L (no supports: the reader clamps the base).
json link_model(double L, const std::string& theory) {
  return {{"nodes", {{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {L, 0, 0}}}}},
          {"materials", materials()},
          {"sections", sections()},
          {"elements",
           {{{"id", "e"}, {"type", "beam"}, {"nodes", {"A", "B"}}, {"material", "al"}, {"section", "rect"},
             {"orientation", {0, 0, 1}}, {"divisions", 3}, {"theory", theory}}}}};
}

Eigen::MatrixXd spring_of(const json& doc) { return beamfea::read_model(doc).joints[0].stiffness_matrix; }

double relative(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return (a - b).norm() / b.norm(); }

// A serial arm: link 1 (one member O-J1a along x), a revolute actuator j1 (J1a-J1b, about z, a
// spring of 5e3), link 2 (two members J1b-M along x and M-T, out of plane), clamped at O.
json arm() {
  return {{"nodes",
           {{{"id", "O"}, {"xyz", {0, 0, 0}}}, {{"id", "J1a"}, {"xyz", {0.5, 0, 0}}}, {{"id", "J1b"}, {"xyz", {0.5, 0, 0}}},
            {{"id", "M"}, {"xyz", {0.9, 0, 0}}}, {{"id", "T"}, {"xyz", {0.9, 0.25, 0.1}}}}},
          {"materials", materials()},
          {"sections", sections()},
          {"elements",
           {{{"id", "l1"}, {"type", "beam"}, {"nodes", {"O", "J1a"}}, {"material", "al"}, {"section", "tube"}, {"divisions", 3}},
            {{"id", "l2a"}, {"type", "beam"}, {"nodes", {"J1b", "M"}}, {"material", "al"}, {"section", "rect"},
             {"orientation", {0, 0, 1}}, {"divisions", 2}},
            {{"id", "l2b"}, {"type", "beam"}, {"nodes", {"M", "T"}}, {"material", "al"}, {"section", "tube"}, {"divisions", 2}}}},
          {"joints", {{{"id", "j1"}, {"type", "revolute"}, {"nodes", {"J1a", "J1b"}}, {"axes", {{0, 0, 1}}}, {"stiffness", {5e3}}}}},
          {"supports", {{{"node", "O"}, {"fix", "all"}}}},
          {"loads", {{{"node", "T"}, {"force", {0, 0, -10}}}}}};
}

json arm_links() {
  return {{"links",
           {{{"id", "L1"}, {"elements", {"l1"}}, {"base", "O"}, {"tip", "J1a"}},
            {{"id", "L2"}, {"elements", {"l2a", "l2b"}}, {"base", "J1b"}, {"tip", "T"}}}}};
}

beamfea::Mat6 tip_compliance(const json& doc) {
  const beamfea::Model m = beamfea::read_model(doc);
  const auto c = beamfea::linear_node_stiffness(m, m.find_node("T"));
  EXPECT_TRUE(c.ok) << c.message;
  return c.compliance;
}

}  // namespace

// A one-member link condensed from its model gives the closed-form cantilever spring of
// stiffness_from_beam (Pashkevich, Klimchik & Chablat 2010, eq. 39), Euler-Bernoulli and Timoshenko.
TEST(StiffnessFromModel, OneMemberLinkEqualsStiffnessFromBeam) {
  for (const std::string theory : {"euler_bernoulli", "timoshenko"}) {
    const Eigen::MatrixXd from_beam = spring_of(spring_model(
        {{"stiffness_from_beam", {{"material", "al"}, {"section", "rect"}, {"length", 0.7}, {"theory", theory}}}}));
    const Eigen::MatrixXd from_model = spring_of(spring_model(
        {{"stiffness_from_model", {{"model", link_model(0.7, theory)}, {"base", "A"}, {"tip", "B"}}}}));
    ASSERT_EQ(from_model.rows(), 6) << theory;
    EXPECT_LT(relative(from_model, from_beam), 1e-9) << theory;
  }
}

// A file name is relative to the folder of the model file that names it, not the working folder.
TEST(StiffnessFromModel, FilePathIsRelativeToTheModelsFolder) {
  const auto dir = beamfea::test::temp_dir("stiffness_from_model_file");
  std::filesystem::create_directories(dir / "links");
  beamfea::test::write_file(dir / "links" / "link.json", link_model(0.7, "euler_bernoulli").dump());
  beamfea::test::write_file(dir / "model.json",
                            spring_model({{"stiffness_from_model", {{"model", "links/link.json"}, {"base", "A"}, {"tip", "B"}}}}).dump());
  const Eigen::MatrixXd from_file = spring_of(beamfea::read_json_file((dir / "model.json").string()));
  const Eigen::MatrixXd from_beam =
      spring_of(spring_model({{"stiffness_from_beam", {{"material", "al"}, {"section", "rect"}, {"length", 0.7}}}}));
  EXPECT_LT(relative(from_file, from_beam), 1e-9);
}

TEST(StiffnessFromModel, UnknownTipIsBadInput) {
  json d = spring_model({{"stiffness_from_model", {{"model", link_model(0.7, "euler_bernoulli")}, {"base", "A"}, {"tip", "Z"}}}});
  d["analyses"] = {{{"id", "lin"}, {"type", "linear_static"}}};
  beamfea::test::expect_bad_input(beamfea::test::run_model("stiffness_from_model_tip", d),
                                  {"/joints/0/stiffness_from_model/tip", "joint 's'", "no node 'Z'"});
}

// A serial arm's lumped model (one virtual spring per link) has the beam model's linear compliance
// at the tip: condensation onto the link's tip is exact for a chain.
TEST(Lump, SerialArmHasTheBeamModelsTipCompliance) {
  const json lumped = beamfea::lump_model(arm(), arm_links());
  // Joint, base and tip nodes kept with their ids; the links' members replaced.
  for (const char* id : {"O", "J1a", "J1b", "T", "L1_spring", "L2_spring"}) {
    bool found = false;
    for (const auto& n : lumped["nodes"]) found = found || n["id"] == id;
    EXPECT_TRUE(found) << id;
  }
  for (const auto& n : lumped["nodes"]) EXPECT_NE(n["id"], "M");
  EXPECT_EQ(lumped["joints"].size(), 3u);  // j1 and two springs
  const beamfea::Mat6 beam = tip_compliance(arm()), vjm = tip_compliance(lumped);
  EXPECT_LT(relative(vjm, beam), 1e-9);
}

TEST(Lump, ProgramWritesTheLumpedModel) {
  const auto dir = beamfea::test::temp_dir("lump_cli");
  beamfea::test::write_file(dir / "arm.json", arm().dump());
  beamfea::test::write_file(dir / "links.json", arm_links().dump());
  const auto r = beamfea::test::run_cli("lump " + (dir / "arm.json").string() + " --links " + (dir / "links.json").string() +
                                        " -o " + (dir / "lumped.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_LT(relative(tip_compliance(beamfea::test::read_json(dir / "lumped.json")), tip_compliance(arm())), 1e-9);
}

TEST(Lump, UnknownElementIsBadInput) {
  const auto dir = beamfea::test::temp_dir("lump_bad");
  json links = arm_links();
  links["links"][1]["elements"][1] = "l9";
  beamfea::test::write_file(dir / "arm.json", arm().dump());
  beamfea::test::write_file(dir / "links.json", links.dump());
  const auto r = beamfea::test::run_cli("lump " + (dir / "arm.json").string() + " --links " + (dir / "links.json").string() +
                                        " -o " + (dir / "lumped.json").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("/links/1/elements/1"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("unknown element 'l9'"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "lumped.json"));
}

// A load on a node inside a link cannot be kept: bad input naming the node and the link.
TEST(Lump, LoadInsideALinkIsBadInput) {
  json model = arm();
  model["loads"].push_back({{"node", "M"}, {"force", {0, 0, -1}}});
  try {
    beamfea::lump_model(model, arm_links());
    FAIL() << "expected an InputError";
  } catch (const beamfea::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("node 'M' is inside the link"), std::string::npos) << e.what();
  }
}

}  // namespace lump_test
