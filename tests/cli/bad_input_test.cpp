// Bad input: exit code 2, a message naming the field (JSON pointer) and the entity, no results.
#include <gtest/gtest.h>

#include "support/cli_case.hpp"
#include "support/models.hpp"

namespace bad_input_test {

using namespace beamfea;
using nlohmann::json;

namespace {

json base() { return test::linear_cantilever(-1.0); }

using Outcome = test::CliCase;

Outcome run_text(const std::string& name, const std::string& text) { return test::run_model_text(name, text); }

Outcome run_doc(const std::string& name, const json& d) { return run_text(name, d.dump()); }

void expect_bad(const Outcome& o, const std::vector<std::string>& fragments) { test::expect_bad_input(o, fragments); }

}  // namespace

TEST(BadInput, GoodModelRunsAndWritesResults) {
  const auto o = run_doc("good", base());
  EXPECT_EQ(o.code, 0) << o.message;
  EXPECT_TRUE(o.results_written());
}

TEST(BadInput, MalformedJsonIsRejected) { expect_bad(run_text("malformed", "{\"nodes\": [}"), {"malformed JSON", "byte"}); }

TEST(BadInput, UnknownNodeIsNamedWithItsPointer) {
  json d = base();
  d["elements"][0]["nodes"][1] = "Z";
  expect_bad(run_doc("unknown", d), {"/elements/0/nodes/1", "unknown node 'Z'"});
}

TEST(BadInput, DuplicateIdIsNamedWithBothPlaces) {
  json d = base();
  d["nodes"].push_back({{"id", "A"}, {"xyz", {5, 0, 0}}});
  expect_bad(run_doc("duplicate", d), {"/nodes/2/id", "duplicate node id 'A'", "/nodes/0"});
}

TEST(BadInput, ZeroLengthElementIsRejected) {
  json d = base();
  d["nodes"][1]["xyz"] = {0, 0, 0};
  expect_bad(run_doc("zerolength", d), {"/elements/0/nodes", "element 'e'", "zero length"});
}

TEST(BadInput, OrientationParallelToTheMemberIsRejected) {
  json d = base();
  d["elements"][0]["orientation"] = {3, 0, 0};
  expect_bad(run_doc("parallel", d), {"/elements/0/orientation", "element 'e'", "parallel"});
}

TEST(BadInput, MissingOrNonPositivePropertyIsRejected) {
  json d = base();
  d["sections"][0].erase("Iz");
  expect_bad(run_doc("missing", d), {"/sections/0/Iz", "section 's'", "missing"});
  json e = base();
  e["materials"][0]["E"] = -1;
  expect_bad(run_doc("negative", e), {"/materials/0/E", "material 'm'", "positive"});
}

TEST(BadInput, SupportOnAnUnknownDofIsRejected) {
  json d = base();
  d["supports"][0]["fix"] = {"ux", "uw"};
  expect_bad(run_doc("dof", d), {"/supports/0/fix/1", "node 'A'", "unknown DOF 'uw'"});
}

TEST(BadInput, UnknownAnalysisTypeIsRejected) {
  json d = base();
  d["analyses"].push_back({{"id", "x"}, {"type", "dynamics"}});
  expect_bad(run_doc("analysis", d), {"/analyses/1/type", "unknown type 'dynamics'"});
}

TEST(BadInput, JointBetweenDistantNodesIsRejected) {
  json d = base();
  d["joints"] = {{{"id", "j"}, {"type", "revolute"}, {"nodes", {"A", "B"}}, {"axes", {{0, 0, 1}}}}};
  expect_bad(run_doc("joint", d), {"/joints/0/nodes", "joint 'j'", "do not coincide"});
}

TEST(BadInput, CheckCommandValidatesWithoutRunning) {
  const auto dir = test::temp_dir("check");
  test::write_file(dir / "model.json", base().dump());
  auto r = test::run_cli("check " + (dir / "model.json").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  json d = base();
  d["elements"][0]["section"] = "nope";
  test::write_file(dir / "bad.json", d.dump());
  r = test::run_cli("check " + (dir / "bad.json").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("/elements/0/section"), std::string::npos) << r.output;
}

// One key policy: every object rejects unknown keys, suggesting the nearest known one;
// '_'-prefixed keys and "comment" are free.
TEST(StrictKeys, MisspelledTopLevelKeySuggestsTheKnownOne) {
  json d = base();
  d["suports"] = d["supports"];
  d.erase("supports");
  expect_bad(run_doc("key_top", d), {"/suports", "unknown key 'suports'", "did you mean 'supports'?"});
}

TEST(StrictKeys, UnknownKeyInAnEntryIsNamedWithItsPointer) {
  json d = base();
  d["materials"][0]["Ee"] = 1.0;
  expect_bad(run_doc("key_material", d), {"/materials/0/Ee", "did you mean 'E'?"});
  json e = base();
  e["elements"][0]["divisons"] = 4;
  expect_bad(run_doc("key_element", e), {"/elements/0/divisons", "did you mean 'divisions'?"});
  json f = base();
  f["loads"][0]["forse"] = {0, 1, 0};
  expect_bad(run_doc("key_load", f), {"/loads/0/forse", "did you mean 'force'?"});
}

TEST(StrictKeys, UnknownKeyInAnAnalysisSpecAndItsBlocksIsRejected) {
  json d = base();
  d["analyses"].push_back({{"id", "b"}, {"type", "buckling"}, {"mode", 2}});
  expect_bad(run_doc("key_buckling", d), {"/analyses/1/mode", "did you mean 'modes'?"});
  json e = base();
  e["analyses"] = {{{"id", "p"}, {"type", "path"}, {"control", {{"load_factor", 1.0}, {"incremnts", 4}}}}};
  expect_bad(run_doc("key_control", e), {"/analyses/0/control/incremnts", "did you mean 'increments'?"});
  json f = base();
  f["analyses"] = {{{"id", "p"}, {"type", "path"}, {"control", {{"load_factor", 1.0}}}, {"stop", {{"step", 3}}}}};
  expect_bad(run_doc("key_stop", f), {"/analyses/0/stop/step", "did you mean 'steps'?"});
}

TEST(StrictKeys, UnderscoreKeysAndCommentsAreFree) {
  json d = base();
  d["_note"] = "mine";
  d["comment"] = "a cantilever";
  d["nodes"][0]["_label"] = 3;
  d["analyses"][0]["comment"] = "first";
  const auto o = run_doc("key_free", d);
  EXPECT_EQ(o.code, 0) << o.message;
}

TEST(StrictKeys, AFarFetchedKeyListsTheKnownKeys) {
  json d = base();
  d["nodes"][0]["zzzzzzzz"] = 1;
  expect_bad(run_doc("key_far", d), {"/nodes/0/zzzzzzzz", "known keys: id xyz"});
}

TEST(AnalysisFailure, MechanismExitsWithOneAndNamesTheJoint) {
  json d = base();
  d["nodes"].push_back({{"id", "C"}, {"xyz", {2, 0, 0}}});
  d["nodes"].push_back({{"id", "D"}, {"xyz", {3, 0, 0}}});
  d["elements"].push_back({{"id", "cd"}, {"type", "beam"}, {"nodes", {"C", "D"}}, {"material", "m"}, {"section", "s"}});
  d["joints"] = {{{"id", "hinge"}, {"type", "revolute"}, {"nodes", {"B", "C"}}, {"axes", {{0, 0, 1}}}}};
  const auto o = run_doc("mechanism", d);
  EXPECT_EQ(o.code, 1) << o.message;
  EXPECT_TRUE(o.results_written());
}

// Found by outside fuzzing: arc-length limits that passed `check` and then ran 100,000 steps of
// 1e-6. min above max, and an arc length below 1e-12 of the model's size, are exit 2 at the field.
TEST(BadInput, ArcLengthLimitsThatCannotWorkAreNamed) {
  json d = base();
  d["analyses"] = {{{"id", "p"}, {"type", "path"}, {"control", {{"arc_length", 1e-3}, {"min", 1e-5}, {"max", 1e-6}}}}};
  expect_bad(run_doc("arc_minmax", d), {"/analyses/0/control/min", "above max"});
  d["analyses"] = {{{"id", "p"}, {"type", "path"}, {"control", {{"arc_length", 1e-300}}}}};
  expect_bad(run_doc("arc_tiny", d), {"/analyses/0/control/arc_length", "below 1e-12 of the model's size"});
  d["analyses"] = {{{"id", "p"}, {"type", "path"}, {"control", {{"arc_length", "auto"}, {"min", 1e-200}}}}};
  expect_bad(run_doc("arc_tiny_min", d), {"/analyses/0/control/min", "below 1e-12"});
}

}  // namespace bad_input_test
