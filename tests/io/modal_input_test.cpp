// Input of the modal and Timoshenko features through the model file and the CLI: the element
// "theory", the virtual spring's stiffness_from_beam "theory", the modal analysis spec; bad input
// exits 2 naming the field.
#include <gtest/gtest.h>

#include "solvers/condensed_stiffness.hpp"
#include "support/cli_case.hpp"
#include "support/models.hpp"

namespace modal_input_test {

using namespace beamfea;
using nlohmann::json;

namespace {

const double E = 2.1e11, G = 8.1e10;

// A cantilever on a rectangle section (shear factors 6/5 by shape).
json rect_cantilever(int divisions = 1) {
  json d = test::cantilever(0.4, E, G, 1, 1, 1, 1, divisions);
  d["sections"] = {{{"id", "s"}, {"shape", "rectangle"}, {"b", 0.04}, {"h", 0.08}}};
  return d;
}

using Outcome = test::CliCase;

Outcome run_doc(const std::string& name, const json& d) { return test::run_model(name, d); }

void expect_bad(const Outcome& o, const std::vector<std::string>& fragments) { test::expect_bad_input(o, fragments); }

}  // namespace

// "theory": "timoshenko" reaches every element of a divided member; the default is
// Euler-Bernoulli.
TEST(ModalInput, TheoryIsReadAndCarriedToTheMeshedElements) {
  json d = rect_cantilever(3);
  Model eb = test::model_from(d);
  for (const auto& e : eb.elements) EXPECT_EQ(e.theory, BeamTheory::EulerBernoulli);
  d["elements"][0]["theory"] = "timoshenko";
  Model t = test::model_from(d);
  ASSERT_EQ(t.elements.size(), 3u);
  for (const auto& e : t.elements) EXPECT_EQ(e.theory, BeamTheory::Timoshenko);
  EXPECT_DOUBLE_EQ(t.sections[0].ky, 1.2);
}

// A virtual spring "from a Timoshenko beam" has exactly the tip stiffness of the Timoshenko
// cantilever it stands for: compare with the stiffness analysis of the beam model.
TEST(ModalInput, StiffnessFromATimoshenkoBeamIsTheTimoshenkoCantilever) {
  json beam = rect_cantilever(1);
  beam["elements"][0]["theory"] = "timoshenko";
  const Model mb = test::model_from(beam);
  const Mat6 Kb = linear_node_stiffness(mb, mb.find_node("B")).K;
  json vs;
  vs["nodes"] = {{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {0, 0, 0}}}};
  vs["materials"] = beam["materials"];
  vs["sections"] = beam["sections"];
  vs["joints"] = {{{"id", "v"}, {"type", "virtual_spring"}, {"nodes", {"A", "B"}},
                   {"stiffness_from_beam", {{"material", "m"}, {"section", "s"}, {"length", 0.4}, {"theory", "timoshenko"}}}}};
  vs["supports"] = {{{"node", "A"}, {"fix", "all"}}};
  const Model mv = test::model_from(vs);
  // The joint frame is x along the link, as the beam's local axes here (member along x,
  // orientation z): the joint stiffness is the beam's tip block.
  const Mat6 Kv = mv.joints[0].stiffness_matrix;
  EXPECT_LT((Kv - Kb).norm(), 1e-9 * Kb.norm());
  // and differs from the Euler-Bernoulli one by the shear compliance
  vs["joints"][0]["stiffness_from_beam"].erase("theory");
  const Mat6 Ke = test::model_from(vs).joints[0].stiffness_matrix;
  const double c_t = Kv.inverse()(2, 2), c_e = Ke.inverse()(2, 2);
  const double As = 0.04 * 0.08 / 1.2;
  EXPECT_NEAR(c_t - c_e, 0.4 / (G * As), 1e-9 * c_t);
}

TEST(ModalInput, UnknownTheoryIsRejected) {
  json d = rect_cantilever();
  d["elements"][0]["theory"] = "reissner";
  expect_bad(run_doc("theory", d), {"/elements/0/theory", "element 'e'", "reissner", "timoshenko"});
}

TEST(ModalInput, TimoshenkoBeamWithoutShearFactorsIsRejected) {
  json d = test::cantilever(1.0, E, G, 1e-3, 2e-6, 3e-6, 1e-6);
  d["elements"][0]["theory"] = "timoshenko";
  expect_bad(run_doc("no_k", d), {"/elements/0/theory", "section 's'", "shear factors"});
}

TEST(ModalInput, TheoryOnARigidLinkIsRejected) {
  json d = rect_cantilever();
  d["nodes"].push_back({{"id", "C"}, {"xyz", {1, 0, 0}}});
  d["elements"].push_back({{"id", "r"}, {"type", "rigid"}, {"nodes", {"B", "C"}}, {"theory", "timoshenko"}});
  expect_bad(run_doc("rigid_theory", d), {"/elements/1/theory", "rigid"});
}

TEST(ModalInput, MoreModesThanDofsAreRejected) {
  json d = rect_cantilever(1);
  d["analyses"] = {{{"id", "m"}, {"type", "modal"}, {"modes", 7}}};
  expect_bad(run_doc("modes", d), {"/analyses/0/modes", "7 modes", "6 free DOFs"});
}

TEST(ModalInput, UnknownModalKeyAndMassKindAreRejected) {
  json d = rect_cantilever(1);
  d["analyses"] = {{{"id", "m"}, {"type", "modal"}, {"mode", 3}}};
  expect_bad(run_doc("modal_key", d), {"/analyses/0/mode", "modes"});
  d["analyses"] = {{{"id", "m"}, {"type", "modal"}, {"mass", "diagonal"}}};
  expect_bad(run_doc("modal_mass", d), {"/analyses/0/mass", "lumped"});
}

// A model without any mass: the analysis runs and fails (exit 1), results.json says why.
TEST(ModalInput, ModelWithoutMassFailsWithAReason) {
  json d = rect_cantilever(2);
  d["analyses"] = {{{"id", "m"}, {"type", "modal"}, {"modes", 2}}};
  const Outcome r = run_doc("no_mass", d);
  EXPECT_EQ(r.code, 1) << r.message;
  ASSERT_TRUE(r.results_written());
  const json res = r.results();
  EXPECT_EQ(res["analyses"]["m"]["status"], "no mass");
  EXPECT_TRUE(res["analyses"]["m"]["frequencies"].empty());
}

}  // namespace modal_input_test
