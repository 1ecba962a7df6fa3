// Inputs and outputs you can trust: one small model per failure class that a fuzzer
// found. Each asserts the exit code by the rules (0 success, 1 an analysis failed, 2 bad input),
// what the message names, and what the output folder holds.
// GCC 12 reports -Wrestrict false positives inside std::string concatenation with literals
// (GCC bug 105329); the code here is plain string building.
#pragma GCC diagnostic ignored "-Wrestrict"
#include <gtest/gtest.h>

#include <chrono>

#include "support/cli_case.hpp"
#include "support/models.hpp"

namespace trust_test {

using namespace beamfea;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// A cantilever A-B of length 2 (A fixed), a tip load, one linear analysis.
json base() { return test::linear_cantilever(-1000.0); }

using Run = test::CliCase;

Run run(const std::string& name, const std::string& text, const std::string& verb = "run", bool keep_out = false) {
  return test::run_model_text("trust_" + name, text, verb, keep_out);
}
Run run(const std::string& name, const json& d, const std::string& verb = "run", bool keep_out = false) {
  return run(name, d.dump(), verb, keep_out);
}

void expect_bad(const Run& r, const std::vector<std::string>& fragments) { test::expect_bad_input(r, fragments); }

// `check` and `run` share one validation: both reject, naming the same pointer.
void expect_bad_in_check_and_run(const std::string& name, const json& d, const std::vector<std::string>& fragments) {
  expect_bad(run(name + "_check", d, "check"), fragments);
  expect_bad(run(name + "_run", d), fragments);
}

// A model whose every DOF is supported.
json all_held() {
  json d = base();
  d["supports"].push_back({{"node", "B"}, {"fix", "all"}});
  return d;
}

}  // namespace

// --- Crashes: zero free DOFs is an answer --------------------------------------------------------

TEST(ZeroFreeDofs, LinearStaticGivesTheReactions) {
  const auto r = run("zero_linear", all_held());
  ASSERT_EQ(r.code, 0) << r.message;
  const json res = r.results();
  EXPECT_EQ(res["analyses"]["lin"]["free_dofs"], 0);
  // The whole load goes into the support at B: reaction = -load (statics).
  EXPECT_DOUBLE_EQ(res["analyses"]["lin"]["nodes"]["B"]["reaction"][1].get<double>(), 1000.0);
}

TEST(ZeroFreeDofs, BucklingReportsThatNothingCanBuckle) {
  json d = all_held();
  d["analyses"] = {{{"id", "b"}, {"type", "buckling"}}};
  const auto r = run("zero_buckling", d);
  ASSERT_EQ(r.code, 0) << r.message;
  const json b = r.results()["analyses"]["b"];
  EXPECT_EQ(b["status"], "no buckling");
  EXPECT_EQ(b["free_dofs"], 0);
  EXPECT_TRUE(b["load_factors"].empty());
}

TEST(ZeroFreeDofs, PathEndsCleanly) {
  json d = all_held();
  d["analyses"] = {{{"id", "p"}, {"type", "path"}, {"control", {{"load_factor", 1.0}, {"increments", 2}}}}};
  const auto r = run("zero_path", d);
  ASSERT_EQ(r.code, 1) << r.message;  // a clean failure, not a crash
  const json p = r.results()["analyses"]["p"];
  EXPECT_EQ(p["status"], "failed");
  EXPECT_NE(p["termination"].get<std::string>().find("no free DOF"), std::string::npos) << p.dump();
}

// --- Ids become file names ----------------------------------------------------------------------

TEST(SafeIds, AnalysisIdThatLeavesTheOutputFolderIsRejected) {
  json d = base();
  d["analyses"][0]["id"] = "../x";
  const auto r = run("id_dotdot", d);
  expect_bad(r, {"/analyses/0/id", "letters, digits"});
  EXPECT_FALSE(fs::exists(r.dir / "x.vtu"));
  json e = base();
  e["analyses"][0]["id"] = "a/b";
  expect_bad(run("id_slash", e), {"/analyses/0/id"});
}

TEST(SafeIds, LongAnalysisIdIsAnErrorNotACrash) {
  json d = base();
  d["analyses"][0]["id"] = std::string(300, 'a');
  expect_bad(run("id_long", d), {"/analyses/0/id", "300 characters", "at most 64"});
}

// Two analyses whose files would have one name: the buckling analysis "a" writes a_mode1.vtu,
// a_mode2.vtu ..., so an analysis "a_mode1" (a_mode1.vtu) would overwrite one of them; the path
// analysis "p" writes p.csv, p.pvd and p_step<k>.vtu. check and run both reject, naming both
// analyses' pointers and the file.
TEST(SafeIds, AnalysesWhoseFilesWouldShareANameAreRejected) {
  json d = base();
  d["analyses"] = {{{"id", "a"}, {"type", "buckling"}, {"modes", 2}}, {{"id", "lin"}, {"type", "linear_static"}},
                   {{"id", "a_mode1"}, {"type", "linear_static"}}};
  expect_bad_in_check_and_run("clash_mode", d, {"/analyses/2/id", "/analyses/0/id", "a_mode1.vtu", "rename"});

  json e = base();
  e["analyses"] = {{{"id", "p_step12"}, {"type", "linear_static"}},
                   {{"id", "p"}, {"type", "path"}, {"control", {{"load_factor", 1.0}, {"increments", 2}}}}};
  expect_bad_in_check_and_run("clash_step", e, {"/analyses/1/id", "/analyses/0/id", "p_step12.vtu"});

  json m = base();
  m["materials"][0]["density"] = 7850.0;
  m["analyses"] = {{{"id", "m"}, {"type", "modal"}, {"modes", 3}}, {{"id", "m_mode3"}, {"type", "linear_static"}}};
  expect_bad_in_check_and_run("clash_modal", m, {"/analyses/1/id", "/analyses/0/id", "m_mode3.vtu"});

  json f = base();
  f["analyses"] = {{{"id", "p"}, {"type", "path"}, {"control", {{"load_factor", 1.0}, {"increments", 2}}}},
                   {{"id", "p"}, {"type", "linear_static"}}};
  expect_bad_in_check_and_run("clash_dup", f, {"/analyses/1/id", "duplicate"});
}

// Names that only look alike are accepted: "a_mode" and "a_mode01" are no file of the buckling
// analysis "a" (its numbers have no leading zero), nor is "a_mode1x".
TEST(SafeIds, AnalysesWhoseFilesOnlyLookAlikeAreAccepted) {
  json d = base();
  d["analyses"] = {{{"id", "a"}, {"type", "buckling"}, {"modes", 2}},
                   {{"id", "a_mode"}, {"type", "linear_static"}},
                   {{"id", "a_mode01"}, {"type", "linear_static"}},
                   {{"id", "a_mode1x"}, {"type", "linear_static"}}};
  const auto r = run("clash_none", d, "check");
  EXPECT_EQ(r.code, 0) << r.message;
}

// --- Checks made before any analysis runs -----------------------------------------------------

// The stiffness of a node whose motion supports or rigid links restrict is a well-posed question
// (not bad input): the answer is a zero compliance, six rigid directions and rank 0.
TEST(ValidateFirst, StiffnessAtASupportedNodeIsAZeroCompliance) {
  json d = base();
  d["analyses"].push_back({{"id", "K"}, {"type", "stiffness"}, {"node", "A"}});
  const auto r = run("stiff_supported", d);
  ASSERT_EQ(r.code, 0) << r.message;
  const json k = r.results()["analyses"]["K"];
  EXPECT_EQ(k["rank"], 0);
  EXPECT_EQ(k["rigid_directions"].size(), 6u);
  for (const auto& row : k["compliance"])
    for (const auto& v : row) EXPECT_EQ(v.get<double>(), 0.0);
}

TEST(ValidateFirst, StiffnessAtANodeHeldByARigidLinkIsAZeroCompliance) {
  json d = base();
  d["nodes"].push_back({{"id", "C"}, {"xyz", {0, 1, 0}}});
  d["elements"].push_back({{"id", "r"}, {"type", "rigid"}, {"nodes", {"A", "C"}}});
  d["analyses"].push_back({{"id", "K"}, {"type", "stiffness"}, {"node", "C"}});
  const auto r = run("stiff_rigid", d);
  ASSERT_EQ(r.code, 0) << r.message;
  const json k = r.results()["analyses"]["K"];
  EXPECT_EQ(k["rank"], 0);
  EXPECT_EQ(k["rigid_directions"].size(), 6u);
}

TEST(ValidateFirst, DisplacementControlOnASupportedDof) {
  json d = base();
  d["analyses"].push_back({{"id", "p"}, {"type", "path"}, {"control", {{"node", "A"}, {"dof", "uy"}, {"to", 0.1}}}});
  expect_bad_in_check_and_run("ctrl_supported", d, {"/analyses/1/control/dof", "node 'A' dof uy", "is supported"});
}

TEST(ValidateFirst, PathWithoutLoads) {
  json d = base();
  d["loads"] = json::array();
  d["analyses"].push_back({{"id", "p"}, {"type", "path"}, {"control", {{"load_factor", 1.0}}}});
  expect_bad_in_check_and_run("path_noloads", d, {"/analyses/1/control", "no loads"});
}

TEST(ValidateFirst, ImperfectionModeThatDoesNotExist) {
  json d = base();
  d["loads"] = {{{"node", "B"}, {"force", {-1000, 0, 0}}}};
  d["analyses"].push_back({{"id", "p"}, {"type", "path"},
                           {"control", {{"arc_length", 0.01}}},
                           {"imperfection", {{"mode", 7}, {"amplitude", 0.001}}}});
  // One beam, six free DOFs at B.
  expect_bad_in_check_and_run("imperfection", d, {"/analyses/1/imperfection/mode", "mode 7 does not exist", "6 free DOF"});
}

TEST(ValidateFirst, EarlierAnalysesWriteNothingWhenALaterOneIsBad) {
  json d = base();
  // (A stiffness at a supported node is not bad input: a control on a supported DOF is.)
  d["analyses"].push_back({{"id", "p"}, {"type", "path"}, {"control", {{"node", "A"}, {"dof", "uy"}, {"to", 0.1}}}});
  const auto r = run("staged_bad", d, "run", /*keep_out=*/true);
  EXPECT_EQ(r.code, 2) << r.message;
  // --out exactly as it was: the old file, nothing else.
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(r.dir / "out")) names.push_back(e.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"old.txt"});
}

// --- Outputs are staged --------------------------------------------------------------------------

TEST(StagedOutputs, AFailedAnalysisKeepsResultsAndTheOthersFiles) {
  json d = base();
  // A path stopped by max_steps before its target is incomplete: exit 1.
  d["analyses"].push_back({{"id", "p"}, {"type", "path"}, {"max_steps", 1},
                           {"control", {{"load_factor", 1.0}, {"increments", 10}}}});
  const auto r = run("staged_fail", d, "run", /*keep_out=*/true);
  ASSERT_EQ(r.code, 1) << r.message;
  EXPECT_TRUE(fs::exists(r.dir / "out" / "results.json"));
  EXPECT_TRUE(fs::exists(r.dir / "out" / "lin.vtu"));
  EXPECT_TRUE(fs::exists(r.dir / "out" / "old.txt"));
  for (const auto& e : fs::directory_iterator(r.dir / "out"))
    EXPECT_EQ(e.path().filename().string().find(".beamfea-staging"), std::string::npos) << e.path();
  const json res = r.results();
  EXPECT_EQ(res["analyses"]["lin"]["status"], "ok");
  EXPECT_EQ(res["analyses"]["p"]["status"], "failed");
}

// --- Silent acceptance --------------------------------------------------------------------------

TEST(SilentAcceptance, IntegerBeyondItsTypeIsAnErrorNotAWrap) {
  json d = base();
  d["elements"][0]["divisions"] = 4294967297LL;  // wrapped to 1 before
  expect_bad(run("int_wrap", d), {"/elements/0/divisions", "out of range"});
}

TEST(SilentAcceptance, ModelWithoutAnalysesIsAnError) {
  json d = base();
  d.erase("analyses");
  expect_bad_in_check_and_run("no_analyses", d, {"/analyses", "no analyses"});
}

TEST(SilentAcceptance, HugeForceOrStiffnessIsAnErrorNotNull) {
  json d = base();
  d["loads"][0]["force"] = {0, -1e308, 0};
  expect_bad(run("huge_force", d), {"/loads/0/force/1", "1e100"});
  json e = base();
  e["nodes"].push_back({{"id", "C"}, {"xyz", {2, 0, 0}}});
  e["joints"] = {{{"id", "j"}, {"type", "revolute"}, {"nodes", {"B", "C"}}, {"axes", {{0, 0, 1}}}, {"stiffness", {1e308}}}};
  expect_bad(run("huge_joint", e), {"/joints/0/stiffness/0", "1e100"});
}

TEST(SilentAcceptance, NonFiniteResultIsAnAnalysisFailure) {
  // Stiffnesses 12 E I / L^3 of ~1e350 overflow double precision inside the analysis.
  json d = test::cantilever(1e-50, 1e100, 1e100, 1e100, 1e100, 1e100, 1e100);
  d["loads"] = {{{"node", "B"}, {"force", {0, -1, 0}}}};
  d["analyses"] = {{{"id", "lin"}, {"type", "linear_static"}}};
  const auto r = run("nonfinite", d);
  ASSERT_EQ(r.code, 1) << r.message;
  const json lin = r.results()["analyses"]["lin"];
  EXPECT_NE(lin["status"], "ok") << lin.dump();
}

// --- Hangs: sizes are bounded and meshing is linear ---------------------------------------------

TEST(Sizes, DivisionsHaveADocumentedBound) {
  json d = base();
  d["elements"][0]["divisions"] = 1000000;
  expect_bad(run("divisions_big", d), {"/elements/0/divisions", "between 1 and 10000"});
}

TEST(Sizes, MeshingIsLinearInTheNumberOfNodes) {
  // 20 members of 10000 divisions: 199,980 internal nodes. Quadratic id lookups took hours.
  json d = base();
  d["elements"] = json::array();
  for (int k = 0; k < 20; ++k)
    d["elements"].push_back({{"id", "e" + std::to_string(k)}, {"type", "beam"}, {"nodes", {"A", "B"}}, {"material", "m"},
                             {"section", "s"}, {"divisions", 10000}});
  const auto t0 = std::chrono::steady_clock::now();
  const auto r = run("mesh_linear", d, "check");
  const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(r.code, 0) << r.message;
  EXPECT_NE(r.message.find("199982 nodes"), std::string::npos) << r.message;
  EXPECT_LT(dt, 60.0);  // about 2 s here; quadratic lookups need ~2e10 string comparisons
}

// --- Misreported ---------------------------------------------------------------------------------

TEST(Misreported, NumberBeyondDoubleRangeIsMalformedJson) {
  json d = base();
  std::string text = d.dump();
  text.replace(text.find("2.0,0"), 3, "1e999");  // node B's x
  expect_bad(run("1e999", text), {"malformed JSON"});
}

TEST(Misreported, CoordinatesWhoseProductsOverflowAreNamed) {
  json d = base();
  d["nodes"][1]["xyz"] = {1e308, 0, 0};
  expect_bad(run("coord_huge", d), {"/nodes/1/xyz/0", "1e100"});
}

TEST(Misreported, DeeplyNestedJsonIsRejectedWithoutOverflowingTheStack) {
  std::string deep = std::string(100000, '[') + std::string(100000, ']');
  expect_bad(run("deep", "{\"_x\": " + deep + "}"), {"malformed JSON", "nested deeper"});
}

// --- Contradictions ------------------------------------------------------------------------------

TEST(Contradictions, SupportAndPrescribedValueThatDisagree) {
  json d = base();
  d["prescribed"] = {{{"node", "A"}, {"dof", "uy"}, {"value", 0.01}}};
  expect_bad_in_check_and_run("support_vs_prescribed", d, {"/prescribed/0", "node 'A' dof uy", "/supports/0"});
}

TEST(Contradictions, AgreeingSupportAndPrescribedValueAreAccepted) {
  json d = base();
  d["prescribed"] = {{{"node", "A"}, {"dof", "uy"}, {"value", 0.0}}};
  EXPECT_EQ(run("support_and_zero", d).code, 0);
}

TEST(Contradictions, TwoPrescribedValuesOnOneDofNameBoth) {
  json d = base();
  d["prescribed"] = {{{"node", "B"}, {"dof", "uy"}, {"value", 0.01}}, {{"node", "B"}, {"dof", "uy"}, {"value", 0.02}}};
  expect_bad(run("prescribed_twice", d), {"/prescribed/1", "node 'B' dof uy", "prescribed twice", "/prescribed/0"});
}

TEST(Contradictions, SupportsOnOneRigidBodyThatDisagree) {
  json d = base();
  d["nodes"].push_back({{"id", "C"}, {"xyz", {0, 1, 0}}});
  d["elements"].push_back({{"id", "r"}, {"type", "rigid"}, {"nodes", {"A", "C"}}});
  d["prescribed"] = {{{"node", "C"}, {"dof", "uz"}, {"value", 0.01}}};  // A is fixed: C cannot move
  expect_bad_in_check_and_run("rigid_disagree", d, {"disagree", "node 'C' dof uz"});
}

TEST(Contradictions, ModelWithoutElements) {
  json d = base();
  d["elements"] = json::array();
  expect_bad_in_check_and_run("no_elements", d, {"/elements", "no elements"});
}

}  // namespace trust_test
