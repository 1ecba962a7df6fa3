// Deferred parts of results.json (io/deferred_results.hpp): objects made member by member while
// the file is written must give the text the results tree gives, byte for byte, on one thread and
// in slices on several; a non-finite number inside them is found with its path, as in the tree.
// (A linear analysis cannot be made to give one through its input: the input's bounds make it fail
// at the factorisation first. The test on the parts themselves covers the check.)
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "io/analysis.hpp"
#include "io/deferred_results.hpp"
#include "io/json_util.hpp"
#include "io/json_writer.hpp"
#include "io/run.hpp"
#include "support/files.hpp"
#include "support/models.hpp"
#include "support/parallel_hooks.hpp"

namespace deferred_results_test {

using json = nlohmann::json;
using ojson = nlohmann::ordered_json;
using beamfea::DeferredMembers;
using beamfea::DeferredParts;
using beamfea::MemberSink;
using beamfea::ParallelTasks;

// Every task on a thread of its own, and the tasks last first (tests/support/parallel_hooks.hpp).
const ParallelTasks thread_per_task = beamfea::test::ThreadPerTask{};
using beamfea::test::last_first;
using beamfea::test::read_json;
using beamfea::test::read_text;

// Run `doc` with results.json written; the analyses' measured wall_time_s (the one value that
// differs from run to run) set to 0 in the text.
struct Written {
  std::string text;
  beamfea::RunReport report;
};
// The text with every "wall_time_s": <number> written as "wall_time_s": 0 (the one value that
// differs between two runs).
std::string without_wall_times(const std::string& text) {
  static constexpr std::string_view key = "\"wall_time_s\": ";
  std::string out;
  std::size_t from = 0;
  for (std::size_t at; (at = text.find(key, from)) != std::string::npos;) {
    out.append(text, from, at - from).append(key).append("0");
    from = text.find_first_not_of("-+.0123456789e", at + key.size());
    if (from == std::string::npos) from = text.size();
  }
  return out.append(text, from, std::string::npos);
}

Written run(const json& doc, bool in_memory, const ParallelTasks& parallel, const std::string& name) {
  const auto dir = beamfea::test::temp_dir(std::string("deferred_").append(name).append(in_memory ? "_tree" : "_deferred"));
  const beamfea::Model model = beamfea::load_and_check(doc);
  beamfea::RunOptions options;
  options.out_dir = dir;
  options.write_vtk = false;
  options.results_in_memory = in_memory;
  options.parallel = parallel;
  Written r;
  r.report = beamfea::run_document(model, doc, options);
  r.text = without_wall_times(read_text(dir / "results.json"));
  std::filesystem::remove_all(dir);
  return r;
}

// A frame of (nx+1)(ny+1)(nz+1) nodes with what a member's output can hold: columns in two
// segments (their "segments"), distributed loads over part of some beams (stations at the load's
// ends), a rigid link (no stations) and a revolute joint with a spring (the "joints" object),
// supports with reactions, nodal loads.
json frame(int nx, int ny, int nz) {
  json nodes = json::array(), elements = json::array(), supports = json::array(), loads = json::array();
  const auto id = [&](int i, int j, int k) {
    std::string s = "n";
    s += std::to_string(i).append("_").append(std::to_string(j)).append("_").append(std::to_string(k));
    return s;
  };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        nodes.push_back({{"id", id(i, j, k)}, {"xyz", {4.0 * i, 5.0 * j, 3.0 * k}}});
        if (k == 0) supports.push_back({{"node", id(i, j, k)}, {"fix", "all"}});
        if (k > 0 && (i + j) % 3 == 0) loads.push_back({{"node", id(i, j, k)}, {"force", {1e3 * i, -2e2 * j, -5e3}}});
      }
  int e = 0;
  const auto beam = [&](const std::string& a, const std::string& b, int divisions) {
    elements.push_back({{"id", std::string("e").append(std::to_string(e++))}, {"type", "beam"}, {"nodes", {a, b}}, {"material", "steel"},
                        {"section", "ipe"}, {"divisions", divisions}});
  };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) beam(id(i, j, k), id(i, j, k + 1), 2);
  for (int k = 1; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        if (i < nx) {
          beam(id(i, j, k), id(i + 1, j, k), 1);
          if ((i + j + k) % 4 == 0)
            loads.push_back({{"element", elements.back()["id"]}, {"distributed", {0, 0, -2e3}}, {"from", 0.25}, {"to", 0.8}});
        }
        if (j < ny) beam(id(i, j, k), id(i, j + 1, k), 1);
      }
  // A tip on a rigid link and a revolute joint off the roof's corner.
  nodes.push_back({{"id", "arm"}, {"xyz", {0.0, 0.0, 3.0 * nz}}});
  nodes.push_back({{"id", "tip"}, {"xyz", {-1.0, 0.0, 3.0 * nz}}});
  elements.push_back({{"id", "link"}, {"type", "rigid"}, {"nodes", {"arm", "tip"}}});
  loads.push_back({{"node", "tip"}, {"force", {0, 0, -1e3}}});
  json joints = json::array({{{"id", "hinge"}, {"type", "revolute"}, {"nodes", {id(0, 0, nz), "arm"}}, {"axes", {{0, 1, 0}}},
                              {"stiffness", {5e6}}}});
  return {{"nodes", nodes},
          {"materials", {{{"id", "steel"}, {"E", 2.1e11}, {"G", 8.1e10}}}},
          {"sections", {{{"id", "ipe"}, {"A", 5.4e-3}, {"Iy", 8.4e-5}, {"Iz", 6.0e-6}, {"J", 2.0e-7}}}},
          {"elements", elements},
          {"joints", joints},
          {"supports", supports},
          {"loads", loads},
          {"analyses", {{{"id", "lin"}, {"type", "linear_static"}, {"stations", 4}}}}};
}

TEST(DeferredResults, ALargeFrameIsWrittenByteForByteAsFromTheTree) {
  // 1,183 nodes and 2,887 members: both objects go through the slices when a hook is given.
  const json doc = frame(12, 12, 6);
  const Written tree = run(doc, true, {}, "frame");
  ASSERT_FALSE(tree.report.failed);
  ASSERT_GT(tree.text.size(), std::size_t{2} << 20);
  for (const auto& [name, hook] : {std::pair<const char*, ParallelTasks>{"serial", {}},
                                   {"threads", thread_per_task}, {"last_first", last_first}}) {
    const Written deferred = run(doc, false, hook, std::string("frame_").append(name));
    EXPECT_FALSE(deferred.report.failed) << name;
    EXPECT_TRUE(deferred.text == tree.text) << name;  // (not EXPECT_EQ: a failure would print megabytes)
    // The tree the caller gets back lacks the deferred objects, and only them.
    const ojson& lin = deferred.report.results["analyses"]["lin"];
    EXPECT_FALSE(lin.contains("nodes")) << name;
    EXPECT_FALSE(lin.contains("elements")) << name;
    EXPECT_EQ(lin["status"], "ok") << name;
    EXPECT_TRUE(lin.contains("joints")) << name;
  }
  // What the text holds is what the tree held (the comparison above is not between two empties).
  const ojson& lin = tree.report.results["analyses"]["lin"];
  EXPECT_EQ(lin["nodes"].size(), 13u * 13u * 7u + 2u + 13u * 13u * 6u);  // and the columns' middle nodes
  EXPECT_EQ(lin["elements"].size(), 13u * 13u * 6u + 2u * 12u * 13u * 6u + 1u);
  EXPECT_EQ(lin["elements"]["e0"]["segments"].size(), 2u);
  EXPECT_TRUE(lin["nodes"]["n0_0_0"].contains("reaction"));
}

// A run that writes nothing and whose caller reads no results tree (a process of a distributed
// `beamfea run` other than rank 0) makes the deferred objects never: its tree holds the
// analysis's status and figures, without nodes or members, and no placeholder.
TEST(DeferredResults, ARunThatWritesNothingNeverMakesTheDeferredObjects) {
  const json doc = frame(6, 6, 3);
  const beamfea::Model model = beamfea::load_and_check(doc);
  beamfea::RunOptions options;
  options.write_vtk = false;
  options.results_in_memory = false;
  const beamfea::RunReport report = beamfea::run_document(model, doc, options);
  ASSERT_FALSE(report.failed);
  const ojson& lin = report.results["analyses"]["lin"];
  EXPECT_EQ(lin["status"], "ok");
  EXPECT_FALSE(lin.contains("nodes"));
  EXPECT_FALSE(lin.contains("elements"));
  EXPECT_TRUE(lin.contains("joints"));
  EXPECT_GT(lin["solver"]["iterations"].get<int>(), 0);
  // The same run with the tree kept has them (what the absence above is measured against).
  options.results_in_memory = true;
  const beamfea::RunReport kept = beamfea::run_document(model, doc, options);
  EXPECT_EQ(kept.results["analyses"]["lin"]["nodes"].size(), 7u * 7u * 4u + 2u + 7u * 7u * 3u);  // with the arm, the tip and the columns' middle nodes
}

TEST(DeferredResults, TheExamplesAreWrittenByteForByteAsFromTheTree) {
  for (const char* example : {"01_space_frame", "04_load_sweep", "09_robot_arm_self_weight"}) {
    const json doc = read_json(beamfea::test::source_path("examples") / example / "model.json");
    const Written tree = run(doc, true, {}, example);
    const Written deferred = run(doc, false, thread_per_task, example);
    EXPECT_EQ(deferred.text, tree.text) << example;
    EXPECT_NE(tree.text.find("\"stations\""), std::string::npos) << example;
  }
}

TEST(DeferredResults, AFailedAnalysisIsWrittenAsFromTheTree) {
  // Stiffnesses 12 E I / L^3 of ~1e350 overflow double precision inside the analysis (as in
  // tests/cli/trust_test.cpp): the factorisation fails, and the result has no nodes or members.
  json d = beamfea::test::cantilever(1e-50, 1e100, 1e100, 1e100, 1e100, 1e100, 1e100);
  d["loads"] = {{{"node", "B"}, {"force", {0, -1, 0}}}};
  d["analyses"] = {{{"id", "lin"}, {"type", "linear_static"}}};
  const Written tree = run(d, true, {}, "failed");
  const Written deferred = run(d, false, {}, "failed");
  ASSERT_TRUE(tree.report.failed);
  EXPECT_TRUE(deferred.report.failed);
  EXPECT_EQ(deferred.report.outcomes.at(0).second.message, tree.report.outcomes.at(0).second.message);
  EXPECT_EQ(deferred.text, tree.text);
}

// The writer alone: a deferred object of `n` members {"i": i, "u": [..]} beside the same object
// held in the tree, and an empty one.
ojson member(std::size_t i) { return {{"i", i}, {"u", {0.1 * static_cast<double>(i), -1.0 / static_cast<double>(i + 1)}}}; }
DeferredMembers numbered(std::size_t n) {
  return {n, [](std::size_t first, std::size_t end, const MemberSink& emit) {
            for (std::size_t i = first; i < end; ++i) emit(std::string("m").append(std::to_string(i)), member(i));
          },
          {}};
}

TEST(DeferredResults, ThePlaceholdersAreWrittenAsTheObjectsTheyStandFor) {
  ojson tree = {{"a", 1}, {"big", ojson::object()}, {"empty", ojson::object()}, {"after", {1.5, 2.5}}};
  for (std::size_t i = 0; i < 5000; ++i) tree["big"][std::string("m").append(std::to_string(i))] = member(i);
  ojson with_parts = {{"a", 1}, {"big", nullptr}, {"empty", nullptr}, {"after", {1.5, 2.5}}};
  DeferredParts parts;
  parts.defer(with_parts["big"], numbered(5000));
  parts.defer(with_parts["empty"], numbered(0));
  EXPECT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts.find(with_parts["a"]), nullptr);
  ASSERT_NE(parts.find(with_parts["big"]), nullptr);
  std::string expected;
  beamfea::write_results_json(tree, expected);
  for (const auto& hook : {ParallelTasks{}, ParallelTasks{thread_per_task}, ParallelTasks{last_first}}) {
    std::string text;
    beamfea::write_results_json(with_parts, text, hook, &parts);
    EXPECT_TRUE(text == expected);
  }
  // Non-finite numbers inside a part are found with their path: by making the members, or, where
  // the part answers whether they are finite, only when it says they are not.
  const auto with_nan = [](std::size_t first, std::size_t end, const MemberSink& emit) {
    for (std::size_t i = first; i < end; ++i)
      emit(std::string("m").append(std::to_string(i)), ojson{{"v", i == 2 ? std::nan("") : 1.0}});
  };
  DeferredParts bad;
  ojson holder = {{"x", nullptr}, {"y", nullptr}, {"z", nullptr}};
  bad.defer(holder["x"], {3, with_nan, [] { return true; }});  // (says all are finite: not made)
  EXPECT_EQ(beamfea::first_non_finite(holder, "", &bad), "");
  bad.defer(holder["y"], {3, with_nan, [] { return false; }});
  EXPECT_EQ(beamfea::first_non_finite(holder, "", &bad), "y.m2.v");
  bad.defer(holder["z"], {3, with_nan, {}});
  holder.erase("y");
  EXPECT_EQ(beamfea::first_non_finite(holder, "", &bad), "z.m2.v");
  EXPECT_EQ(beamfea::first_non_finite(with_parts, "", &parts), "");
  // Once written, the placeholders leave the tree.
  parts.erase_placeholders(with_parts);
  EXPECT_EQ(with_parts, (ojson{{"a", 1}, {"after", {1.5, 2.5}}}));
}

}  // namespace deferred_results_test
