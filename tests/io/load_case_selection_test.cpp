// An analysis's "load_case" (docs/input-format.md, "Loads, load cases, masses"): "default" names
// the top-level loads and gravity in every analysis type that takes a load case, and gives the
// result of the same loads named otherwise; an unknown id is bad input naming the field and the
// ids it may take.
#include <gtest/gtest.h>

#include <string>

#include "core/errors.hpp"
#include "io/run.hpp"
#include "support/models.hpp"

namespace load_case_selection_test {

using namespace beamfea;
using nlohmann::json;

namespace {

// A steel cantilever along x (four elements) under its own weight and a tip load that compresses
// it, with the same loads also as the load case "same".
json cantilever_with_case() {
  json doc = test::cantilever(2.0, 2.1e11, 8.1e10, 1e-3, 2e-6, 3e-6, 1e-6, 4);
  doc["materials"][0]["density"] = 7850.0;
  const json loads = json::array({{{"node", "B"}, {"force", {-1e3, 0, -1e2}}}});
  doc["loads"] = loads;
  doc["gravity"] = {0, 0, -9.81};
  doc["load_cases"] = json::array({{{"id", "same"}, {"loads", loads}, {"gravity", {0, 0, -9.81}}}});
  return doc;
}

// The two-link chain (tests/support/models.hpp), its tip
// loaded, with the same load also as the load case "same".
json chain_with_case() {
  const json loads = json::array({{{"node", "P"}, {"force", {0, -2, 0}}}});
  json d = test::two_link_chain();
  d["loads"] = loads;
  d["load_cases"] = {{{"id", "same"}, {"loads", loads}}};
  return d;
}

// One analysis spec of each type that takes a load case, with the document it runs on.
struct Case {
  const char* type;
  json document;
  json spec;
  // Whether a load case changes what is computed (a loaded stiffness, modes about the loaded
  // state, the efforts): then "default" is compared with the named case only.
  bool load_case_switches_mode;
};

std::vector<Case> cases() {
  const json alloc = {{"type", "actuator_allocation"}, {"platform_node", "P"}, {"candidate_joints", {"JA", "JB"}},
                      {"actuators", 2}, {"actuator_stiffness", 1.0}, {"directions", {"rz", "uy"}}};
  return {
      {"linear_static", cantilever_with_case(), {{"type", "linear_static"}}, false},
      {"stiffness", cantilever_with_case(), {{"type", "stiffness"}, {"node", "B"}}, true},
      {"buckling", cantilever_with_case(), {{"type", "buckling"}, {"modes", 2}}, false},
      {"path", cantilever_with_case(),
       {{"type", "path"}, {"control", {{"load_factor", 1.0}, {"increments", 2}}}, {"track", {"B"}}}, false},
      {"modal", cantilever_with_case(), {{"type", "modal"}, {"modes", 2}}, true},
      {"actuator_allocation", chain_with_case(), alloc, true},
  };
}

// The result of `c`'s analysis with "load_case" set to `load_case` (none when empty), without
// what differs from run to run (wall_time_s) or echoes the spec (load_case).
ojson result_with(const Case& c, const std::string& load_case) {
  json doc = c.document;
  json spec = c.spec;
  spec["id"] = "a";
  if (!load_case.empty()) spec["load_case"] = load_case;
  doc["analyses"] = json::array({spec});
  const Model m = load_and_check(doc);
  RunReport report = run_document(m, doc, RunOptions{});
  ojson r = report.results["analyses"]["a"];
  r.erase("wall_time_s");
  r.erase("load_case");
  return r;
}

}  // namespace

TEST(LoadCaseSelection, DefaultGivesTheResultOfTheTopLevelLoadsInEveryAnalysisType) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.type);
    const ojson by_default = result_with(c, "default");
    EXPECT_EQ(by_default["status"], "ok") << by_default.dump();
    // The same loads named "same": the same numbers, bit for bit (one computation).
    EXPECT_EQ(by_default, result_with(c, "same"));
    if (!c.load_case_switches_mode) {
      EXPECT_EQ(by_default, result_with(c, ""));
    }
  }
}

TEST(LoadCaseSelection, DefaultIsEchoedInTheResult) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.type);
    if (std::string(c.type) == "path") continue;  // a path's result names no load case
    json doc = c.document;
    json spec = c.spec;
    spec["id"] = "a";
    spec["load_case"] = "default";
    doc["analyses"] = json::array({spec});
    const Model m = load_and_check(doc);
    const RunReport report = run_document(m, doc, RunOptions{});
    const ojson& r = report.results.at("analyses").at("a");
    ASSERT_TRUE(r.contains("load_case")) << r.dump();
    EXPECT_EQ(r.at("load_case"), "default");
  }
}

TEST(LoadCaseSelection, AnUnknownIdNamesTheFieldAndTheKnownIds) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.type);
    json doc = c.document;
    json spec = c.spec;
    spec["id"] = "a";
    spec["load_case"] = "nope";
    doc["analyses"] = json::array({spec});
    try {
      load_and_check(doc);
      ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
      EXPECT_EQ(e.pointer(), "/analyses/0/load_case");
      EXPECT_NE(std::string(e.what()).find("unknown load case or combination 'nope' (known: default, same)"), std::string::npos)
          << e.what();
    }
  }
}

TEST(LoadCaseSelection, TheDefaultCaseIsTheModelsOwnLoadSet) {
  json doc = cantilever_with_case();
  doc["combinations"] = json::array({{{"id", "twice"}, {"factors", {{"same", 2.0}}}}});
  const Model m = test::model_from(doc);
  // "" and "default" select the model's one default LoadSet, not a copy made per call.
  EXPECT_EQ(&m.loads_for(""), &m.default_loads());
  EXPECT_EQ(&m.loads_for("default"), &m.default_loads());
  EXPECT_EQ(&m.loads_for("same"), &m.load_cases[0].loads);
  // A combination's sum is made once, when it is read: its force is twice the case's.
  const LoadSet& twice = m.loads_for("twice");
  EXPECT_EQ(&twice, &m.loads_for("twice"));
  ASSERT_EQ(twice.nodal.size(), 1u);
  EXPECT_DOUBLE_EQ(twice.nodal[0].force.x(), -2e3);
  EXPECT_DOUBLE_EQ(twice.gravity.z(), -2 * 9.81);
  EXPECT_THROW(m.loads_for("nope"), ModelError);
}

}  // namespace load_case_selection_test
