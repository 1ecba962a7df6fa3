// The io half of sweeps: reading sweep files (errors name the entry), running one case, and the
// table (columns, rows, CSV quoting, resume, the final sorted rewrite). The loop over the cases
// is tested in tests/app/sweep_runner_test.cpp.
#include "io/sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/errors.hpp"
#include "io/sweep_table.hpp"
#include "support/errors.hpp"
#include "support/sweep_util.hpp"

namespace sweep_test {

using namespace sweep_test;
using beamfea::InputError;
using beamfea::Sweep;
using beamfea::SweepCaseResult;

namespace {

std::string pointer_of(const std::function<void()>& f) {
  const auto e = beamfea::test::thrown<InputError>(f);
  return e ? e->pointer() : "(no error)";
}

// Three list cases on the cantilever: two tip loads and one with an unknown section.
json three_cases() {
  return {{"cases",
           {json{{"id", "p1"}, {"set", {{"/loads/0/force/1", -1000.0}}}},
            json{{"id", "bad"}, {"set", {{"/elements/0/section", "nope"}}}},
            json{{"id", "p2"}, {"set", {{"/loads/0/force/1", -3000.0}}}}}},
          {"outputs", {json{{"name", "v"}, {"path", "analyses.lin.nodes.B.displacement[1]"}}, "analyses.K.matrix[1]"}}};
}

}  // namespace

TEST(SweepFile, BadSweepFilesNameTheEntry) {
  const auto dir = temp_dir("bad");
  auto read = [&](const json& sweep) { return [&, sweep] { beamfea::read_sweep_file(write_sweep(dir, sweep).string()); }; };
  const json out = {"analyses.lin.nodes.B.displacement[1]"};
  EXPECT_EQ(pointer_of(read({{"grid", json::array()}, {"outputs", out}})), "/grid");
  EXPECT_EQ(pointer_of(read({{"grid", {json{{"pointer", "/loads/0/force/1"}, {"values", json::array()}}}}})),
            "/grid/0/values");
  EXPECT_EQ(pointer_of(read({{"grid", {json{{"pointer", "/loads/3/force/1"}, {"values", {1}}}}}})), "/grid/0/pointer");
  EXPECT_EQ(pointer_of(read({{"grid", {json{{"pointer", "/loads/0/force/1"}, {"values", {1, "two"}}}}}})),
            "/grid/0/values/1");
  EXPECT_EQ(pointer_of(read({{"grid", {json{{"pointer", "/nodes/1/xyz"}, {"values", {{1, 0}}}}}}})), "/grid/0/values/0");
  EXPECT_EQ(pointer_of(read({{"cases", {json{{"set", {{"/materials/0/E", 1.0}}}}, json{{"set", {{"/materials/0/X", 1.0}}}}}}})),
            "/cases/1/set/~1materials~10~1X");
  EXPECT_EQ(pointer_of(read({{"cases", {json{{"patch", {json{{"op", "remove"}, {"path", "/supports/4"}}}}}}}})),
            "/cases/0/patch");
  // A patch is checked on the base with the case's "set" applied (the test fails: force/1 is 5), and
  // each patch on the base as it was (the second applies after the first removed the load; the
  // third's test fails).
  EXPECT_EQ(pointer_of(read({{"cases", {json{{"set", {{"/loads/0/force/1", 5.0}}},
                                             {"patch", {json{{"op", "test"}, {"path", "/loads/0/force/1"}, {"value", -1000}}}}}}}})),
            "/cases/0/patch");
  EXPECT_EQ(pointer_of(read({{"grid", {json{{"name", "p"},
                                            {"patches", {{json{{"op", "remove"}, {"path", "/loads/0"}}},
                                                         {json{{"op", "test"}, {"path", "/loads/0/node"}, {"value", "B"}}},
                                                         {json{{"op", "test"}, {"path", "/loads/0/node"}, {"value", "X"}}}}}}}}})),
            "/grid/0/patches/2");
  EXPECT_EQ(pointer_of(read({{"cases", json::array()}})), "/cases");
  EXPECT_EQ(pointer_of(read({{"cases", {json::object()}}, {"outputs", {"analyses.nope.x"}}})), "/outputs/0");
  EXPECT_EQ(pointer_of(read({{"cases", {json::object()}}, {"output", out}})), "/output");
  EXPECT_EQ(pointer_of(read({{"cases", {json{{"id", "a/b"}}}}})), "/cases/0/id");
  // Column names are one line each in the table's header (found by the rule of fuzz_sweep).
  EXPECT_EQ(pointer_of(read({{"cases", {json::object()}}, {"outputs", {json{{"name", "v\nw"}, {"path", out[0]}}}}})),
            "/outputs/0");
  EXPECT_EQ(pointer_of(read({{"grid", {json{{"name", "P\r"}, {"pointer", "/loads/0/force/1"}, {"values", {1}}}}}})),
            "/grid/0/name");
}

// One case in process, and its row: the tip deflection of the cantilever, v = P L^3 / (3 E Iz)
// (Gere & Goodno, Table G-1 case 4), and the stiffness row K[uy] = (0, 12 E Iz / L^3, 0, 0, 0,
// -6 E Iz / L^2) of the tip node (Przemieniecki eq. 5.116), with L = 2.
TEST(SweepCase, OneCaseGivesTheClosedFormsAndItsRow) {
  const auto dir = temp_dir("one_case");
  const Sweep s = beamfea::read_sweep_file(write_sweep(dir, three_cases()).string());
  const double L = 2.0;
  const SweepCaseResult r = beamfea::run_sweep_case(s, 2);
  ASSERT_EQ(r.status, SweepCaseResult::Status::Succeeded) << r.message;
  ASSERT_EQ(r.outputs.size(), 2u);
  ASSERT_EQ(r.outputs[0].size(), 1u);
  EXPECT_EQ(r.outputs[0][0].first, "v");
  const double v = -3000.0 * L * L * L / (3 * kE * kIz);
  EXPECT_NEAR(std::stod(r.outputs[0][0].second), v, 1e-9 * std::abs(v));
  ASSERT_EQ(r.outputs[1].size(), 6u);
  EXPECT_EQ(r.outputs[1][1].first, "analyses.K.matrix[1][1]");
  const double k11 = 12 * kE * kIz / (L * L * L), k15 = 6 * kE * kIz / (L * L);
  EXPECT_NEAR(std::stod(r.outputs[1][1].second), k11, 1e-9 * k11);
  EXPECT_NEAR(std::abs(std::stod(r.outputs[1][5].second)), k15, 1e-9 * k15);

  const auto columns = beamfea::sweep_columns(s, &r);
  const auto header = columns.header(s);
  // case, the two set pointers (the parameters of a list without "parameters"), v, the K row,
  // status, message, wall time.
  ASSERT_EQ(header.size(), 1u + 2u + 1u + 6u + 3u);
  EXPECT_EQ(header[1], "/loads/0/force/1");
  EXPECT_EQ(header[3], "v");
  std::string row = beamfea::sweep_row(s, 2, columns, r);
  ASSERT_EQ(row.back(), '\n');
  row.pop_back();
  const auto cells = beamfea::csv_split(row);
  ASSERT_EQ(cells.size(), header.size());
  EXPECT_EQ(cells[0], "p2");
  EXPECT_EQ(cells[1], "-3000");
  EXPECT_EQ(cells[2], "");  // p2 does not set the section
  EXPECT_EQ(std::stod(cells[3]), std::stod(r.outputs[0][0].second));  // shortest round trip: exact
  EXPECT_EQ(cells[header.size() - 3], "ok");

  // A case whose model the reader rejects is "bad input" naming the entry; its outputs are empty
  // cells of the same row shape.
  const SweepCaseResult b = beamfea::run_sweep_case(s, 1);
  EXPECT_EQ(b.status, SweepCaseResult::Status::BadInput);
  EXPECT_NE(b.message.find("/elements/0/section"), std::string::npos) << b.message;
  std::string brow = beamfea::sweep_row(s, 1, columns, b);
  brow.pop_back();
  const auto bcells = beamfea::csv_split(brow);
  ASSERT_EQ(bcells.size(), header.size());
  EXPECT_EQ(bcells[2], "nope");
  EXPECT_EQ(bcells[3], "");
  EXPECT_EQ(bcells[header.size() - 3], "bad input");
}

TEST(SweepTable, CsvFieldsAreQuotedOnlyWhenNeededAndSplitBack) {
  const std::vector<std::string> cells{"plain", "a,b", "say \"hi\"", "", "x\ny"};
  std::string line = beamfea::csv_line(cells);
  EXPECT_EQ(line, "plain,\"a,b\",\"say \"\"hi\"\"\",,\"x\ny\"\n");
  line.pop_back();
  // A quoted line break cannot be split by csv_split line by line; the others come back as written.
  const auto back = beamfea::csv_split("plain,\"a,b\",\"say \"\"hi\"\"\",");
  EXPECT_EQ(back, (std::vector<std::string>{"plain", "a,b", "say \"hi\"", ""}));
  EXPECT_EQ(beamfea::csv_cell(json(0.1)), "0.1");
  EXPECT_EQ(beamfea::csv_cell(json("two\nlines")), "two lines");
  EXPECT_EQ(beamfea::csv_cell(json(nullptr)), "");
}

// The sweep's cells are formatted into a reused string with a compiled format (csv_cell_into): the
// same text as csv_cell's runtime "{}" (shortest round trip), at the limits of fixed and exponent
// notation, for the longest texts and the special values, and written over a longer old cell.
TEST(SweepTable, ACellFormattedInPlaceIsTheCsvCell) {
  const double values[] = {0.1, -0.0, 0.0, 1.0, 100.0, 1e15, 1e16, 1.5e16, 9.999999999999999e15, 1e-4, 1e-5,
                           123456.789, -2.2250738585072014e-308, 4.9406564584124654e-324, 1.7976931348623157e308,
                           -1.2345678901234567e-100, 2.0 / 3.0, std::nan(""), INFINITY, -INFINITY};
  std::string cell = "an old cell longer than any number written over it";
  for (double v : values) {
    beamfea::csv_cell_into(cell, beamfea::ojson(v));
    EXPECT_EQ(cell, beamfea::csv_cell(beamfea::ojson(v))) << v;
  }
  EXPECT_EQ((beamfea::csv_cell_into(cell, beamfea::ojson(1e16)), cell), "1e+16");
  EXPECT_EQ((beamfea::csv_cell_into(cell, beamfea::ojson(-0.0)), cell), "-0");
  beamfea::csv_cell_into(cell, beamfea::ojson("text, quoted later"));
  EXPECT_EQ(cell, "text, quoted later");
}

TEST(SweepTable, ResumeFindsTheCasesOfThisSweepAndRejectsAnotherTable) {
  const auto dir = temp_dir("resume_io");
  const Sweep s = beamfea::read_sweep_file(write_sweep(dir, three_cases()).string());
  const auto table = dir / "cases.csv";
  EXPECT_FALSE(beamfea::resume_sweep_table(s, table).found);

  const auto r = beamfea::run_sweep_case(s, 2);
  const auto columns = beamfea::sweep_columns(s, &r);
  // A header, the row of case "p2" and half a row (as if the writer had died mid-line).
  write(table, beamfea::csv_line(columns.header(s)) + beamfea::sweep_row(s, 2, columns, r) + "p1,-1000,,0.0");
  const auto resumed = beamfea::resume_sweep_table(s, table);
  ASSERT_TRUE(resumed.found);
  EXPECT_EQ(resumed.columns.outputs, columns.outputs);
  EXPECT_EQ(resumed.done, (std::vector<char>{0, 0, 1}));
  const std::string repaired = read(table);
  EXPECT_EQ(repaired.back(), '\n');
  EXPECT_EQ(repaired.find("p1,"), std::string::npos) << "the partial line is cut off";

  // Another sweep's table: other columns, or a case id that is not this sweep's.
  write(table, "case,x,status,message,wall_time_s\n");
  try {
    beamfea::resume_sweep_table(s, table);
    ADD_FAILURE() << "another sweep's table was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not a table of this sweep"), std::string::npos) << e.what();
  }
  write(table, beamfea::csv_line(columns.header(s)) + "zz" + beamfea::sweep_row(s, 2, columns, r));
  EXPECT_THROW(beamfea::resume_sweep_table(s, table), InputError);
}

TEST(SweepTable, FinishSortsByCaseKeepsTheLastRowOfACaseAndCounts) {
  const auto dir = temp_dir("finish_io");
  const Sweep s = beamfea::read_sweep_file(write_sweep(dir, three_cases()).string());
  std::vector<SweepCaseResult> r;
  for (std::size_t i = 0; i < 3; ++i) r.push_back(beamfea::run_sweep_case(s, i));
  const auto columns = beamfea::sweep_columns(s, &r[0]);
  const auto table = dir / "cases.csv";
  write(table, beamfea::csv_line(columns.header(s)));
  {
    beamfea::SweepTableAppender out(table);
    SweepCaseResult failed = r[0];
    failed.status = SweepCaseResult::Status::AnalysisFailed;
    out.append(beamfea::sweep_row(s, 2, columns, r[2]) + beamfea::sweep_row(s, 0, columns, failed));
    out.append(beamfea::sweep_row(s, 1, columns, r[1]) + beamfea::sweep_row(s, 0, columns, r[0]));  // case 0 again: ok
  }
  const auto counts = beamfea::finish_sweep_table(s, table);
  EXPECT_EQ(counts.ok, 2u);
  EXPECT_EQ(counts.bad_input, 1u);
  EXPECT_EQ(counts.analysis_failed, 0u);
  bool well_formed = false;
  const Csv t = read_csv(table, &well_formed);
  EXPECT_TRUE(well_formed);
  ASSERT_EQ(t.rows.size(), 3u);
  EXPECT_EQ(t.rows[0][0], "p1");
  EXPECT_EQ(t.rows[0][t.col("status")], "ok");
  EXPECT_EQ(t.rows[1][0], "bad");
  EXPECT_EQ(t.rows[2][0], "p2");
  // Finishing a finished table (rows in order, one per case: left as it is) counts the same and
  // leaves the same text; the status of the unquoted rows and of the quoted bad-input row is read.
  const std::string finished = read(table);
  const auto again = beamfea::finish_sweep_table(s, table);
  EXPECT_EQ(again.ok, 2u);
  EXPECT_EQ(again.bad_input, 1u);
  EXPECT_EQ(again.analysis_failed, 0u);
  EXPECT_EQ(read(table), finished);
}

// A worker's reused document (SweepCaseDocument) gives every case the same document as a fresh
// copy (Sweep::document), in any order: grid values set in place and put back, a list case with a
// patch adding a key the base lacks (a fresh copy), and the cases after it.
TEST(SweepCase, AReusedDocumentGivesEachCaseTheFreshCopysDocument) {
  const json grid = {{"model", cantilever()},
                     {"grid", {json{{"pointer", "/loads/0/force/1"}, {"values", {-1.0, -2.0, -3.0}}},
                               json{{"pointer", {"/nodes/1/xyz/0", "/nodes/1/xyz/1"}}, {"values", {1.0, 2.0}}}}},
                     {"outputs", {"analyses.K.matrix"}}};
  const json list = {
      {"model", cantilever()},
      {"cases", {json{{"id", "a"}, {"set", {{"/loads/0/force/1", -5.0}, {"/nodes/1/xyz/0", 3.0}}}},
                 json{{"id", "b"}, {"patch", {json{{"op", "add"}, {"path", "/loads/0/moment"}, {"value", {0, 0, 1.0}}}}}},
                 json{{"id", "c"}, {"set", {{"/loads/0/force/0", 7.0}}}},
                 json{{"id", "d"}, {"set", {{"/nodes/1/xyz/0", 4.0}}}}}},
      {"outputs", {"analyses.K.matrix"}}};
  for (const json& file : {grid, list}) {
    const Sweep s = beamfea::read_sweep(file, fs::temp_directory_path());
    beamfea::SweepCaseDocument documents(s);
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < s.size(); ++i) order.push_back(i);
    for (std::size_t i = s.size(); i-- > 0;) order.push_back(i);
    order.push_back(1);
    order.push_back(1);
    for (const std::size_t i : order) EXPECT_EQ(documents.apply(i), s.document(i)) << "case " << i;
    // The same results either way.
    const SweepCaseResult reused = beamfea::run_sweep_case(s, 1, {}, &documents);
    const SweepCaseResult fresh = beamfea::run_sweep_case(s, 1);
    EXPECT_EQ(reused.outputs, fresh.outputs);
  }
}

// JSON Patches are applied to the worker's document in place and undone after the case: every
// RFC 6902 operation, on objects and arrays, gives the fresh copy's document (Sweep::document) in
// any order of the cases; a patch of the whole document gets a fresh copy; a combination of patches
// that does not apply fails with the fresh copy's error and leaves the next case intact.
TEST(SweepCase, PatchesAppliedInPlaceGiveEachCaseTheFreshCopysDocument) {
  const json list = json::parse(R"({"cases": [
    {"id": "add_member", "patch": [{"op": "add", "path": "/loads/0/moment", "value": [0, 0, 1.5]}]},
    {"id": "add_elements", "patch": [{"op": "add", "path": "/nodes/1", "value": {"id": "C", "xyz": [1, 0, 0]}},
                                     {"op": "add", "path": "/loads/-", "value": {"node": "C", "force": [0, 0, -2]}}]},
    {"id": "remove", "patch": [{"op": "remove", "path": "/analyses/0"}, {"op": "remove", "path": "/loads/0/force"}]},
    {"id": "move_copy", "patch": [{"op": "move", "from": "/loads/0/force", "path": "/loads/0/moment"},
                                  {"op": "copy", "from": "/nodes/1/xyz", "path": "/nodes/0/xyz"},
                                  {"op": "copy", "from": "/nodes/0", "path": "/nodes/-"}]},
    {"id": "test_replace", "set": {"/loads/0/force/0": 7.0},
     "patch": [{"op": "test", "path": "/loads/0/force/0", "value": 7.0},
               {"op": "replace", "path": "/loads/0/force/1", "value": -3.0},
               {"op": "add", "path": "/supports/0/fix", "value": ["ux", "uy", "uz", "rx", "ry"]},
               {"op": "remove", "path": "/supports/0/fix"},
               {"op": "add", "path": "/supports/0/fix", "value": "all"}]},
    {"id": "whole", "patch": [{"op": "replace", "path": "", "value": {"nodes": []}}]},
    {"id": "plain", "set": {"/nodes/1/xyz/0": 4.0}}],
    "outputs": ["analyses.K.matrix"]})");
  json list_file = list;
  list_file["model"] = cantilever();
  const json grid = json::parse(R"({"grid": [
    {"name": "first", "patches": [[{"op": "remove", "path": "/loads/0"}],
                                  [{"op": "test", "path": "/loads/0/node", "value": "B"}]]},
    {"name": "second", "patches": [[{"op": "replace", "path": "/loads/0/force/1", "value": -5.0}],
                                   [{"op": "add", "path": "/loads/0/moment", "value": [0, 0, 2.0]}]]}],
    "outputs": ["analyses.K.matrix"]})");
  json grid_file = grid;
  grid_file["model"] = cantilever();
  for (const json& file : {list_file, grid_file}) {
    const Sweep s = beamfea::read_sweep(file, fs::temp_directory_path());
    beamfea::SweepCaseDocument documents(s);
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < s.size(); ++i) order.push_back(i);
    for (std::size_t i = s.size(); i-- > 0;) order.push_back(i);
    for (std::size_t i = 0; i < s.size(); ++i) order.push_back(i);
    std::size_t failed = 0;
    for (const std::size_t i : order) {
      std::string fresh_error;
      json fresh;
      try {
        fresh = s.document(i);
      } catch (const InputError& e) {
        fresh_error = e.what();
      }
      if (!fresh_error.empty()) {
        ++failed;
        try {
          documents.apply(i);
          ADD_FAILURE() << "case " << i << " applied; the fresh copy says " << fresh_error;
        } catch (const InputError& e) {
          EXPECT_EQ(std::string(e.what()), fresh_error) << "case " << i;
        }
        continue;
      }
      EXPECT_EQ(documents.apply(i), fresh) << "case " << i;
      EXPECT_NE(documents.apply(i), s.base) << "case " << i << " changed nothing";
      // In place, but for the patch of the whole document.
      EXPECT_EQ(documents.in_place(), s.case_id(i) != "whole") << "case " << i;
    }
    // The grid's two combinations that remove the load and then change it fail, three times each.
    EXPECT_EQ(failed, file.contains("grid") ? 6u : 0u);
  }
}

TEST(SweepCase, AReusedResultHoldsOnlyItsOwnCase) {
  // One SweepCaseResult written over case after case (as a sweep's worker does) against a fresh
  // result per case: the same status, message and cells, whatever the previous case left there
  // (36 cells, none because the analysis found a mechanism, none because the input is bad).
  json model = cantilever();
  model["supports"][0]["fix"] = {"ux", "uy", "uz", "rx", "ry", "rz"};
  const json list = {
      {"model", model},
      {"cases", {json{{"id", "ok"}, {"set", {{"/loads/0/force/1", -5.0}}}},
                 json{{"id", "mechanism"}, {"set", {{"/supports/0/fix/3", "ux"}}}},  // rx free
                 json{{"id", "bad"}, {"set", {{"/supports/0/fix/3", "qx"}}}},        // no such DOF
                 json{{"id", "longer"}, {"set", {{"/nodes/1/xyz/0", 3.0}}}}}},
      {"outputs", {"analyses.K.matrix", "analyses.K.rank"}}};
  const Sweep s = beamfea::read_sweep(list, fs::temp_directory_path());
  beamfea::SweepCaseDocument documents(s);
  SweepCaseResult reused;
  std::size_t seen_ok = 0, seen_failed = 0, seen_bad = 0;
  for (const std::size_t i : {0, 1, 2, 3, 0, 2, 1, 3, 3, 0}) {
    beamfea::run_sweep_case(s, i, {}, &documents, reused);
    const SweepCaseResult fresh = beamfea::run_sweep_case(s, i);
    EXPECT_EQ(reused.status, fresh.status) << "case " << i;
    EXPECT_EQ(reused.message, fresh.message) << "case " << i;
    EXPECT_EQ(reused.outputs, fresh.outputs) << "case " << i;
    switch (fresh.status) {
      case SweepCaseResult::Status::Succeeded:
        ++seen_ok;
        ASSERT_EQ(fresh.outputs.size(), 2u);
        EXPECT_EQ(fresh.outputs[0].size(), 36u);
        EXPECT_EQ(fresh.outputs[0][7].first, "analyses.K.matrix[1][1]");
        break;
      case SweepCaseResult::Status::AnalysisFailed: ++seen_failed; break;
      case SweepCaseResult::Status::BadInput: ++seen_bad; break;
    }
    // The row from the reused result is the fresh result's row.
    const beamfea::SweepColumns columns = beamfea::sweep_columns(s, nullptr);
    std::string row = "x";
    beamfea::append_sweep_row(row, s, i, columns, reused);
    std::string expected = beamfea::sweep_row(s, i, columns, fresh);
    // wall_time_s (the last field) differs between the two runs: compare up to it.
    expected = expected.substr(0, expected.rfind(','));
    EXPECT_EQ(row.substr(0, row.rfind(',')), "x" + expected);
  }
  EXPECT_EQ(seen_ok, 6u);
  EXPECT_EQ(seen_failed, 2u);
  EXPECT_EQ(seen_bad, 2u);
}

TEST(SweepCase, AReusedWorkspaceGivesEachCaseTheFreshResult) {
  // A worker's workspace (its document, its model buffer and its results, SweepWorkspace) case
  // after case against fresh ones: the same status, message and cells (compared as text: the
  // cells print each double exactly) for a model that grows (a patch adds a node, a member of
  // three divisions and a joint) and shrinks back, a mechanism, bad input in between, and a
  // case whose stiffness node changes.
  json model = cantilever();
  model["supports"][0]["fix"] = {"ux", "uy", "uz", "rx", "ry", "rz"};
  const json grow = {json{{"op", "add"}, {"path", "/nodes/-"}, {"value", {{"id", "C"}, {"xyz", {2, 1.5, 0}}}}},
                     json{{"op", "add"}, {"path", "/nodes/-"}, {"value", {{"id", "D"}, {"xyz", {2, 1.5, 0}}}}},
                     json{{"op", "add"},
                          {"path", "/elements/-"},
                          {"value", {{"id", "a much longer member id"}, {"type", "beam"}, {"nodes", {"B", "C"}},
                                     {"material", "steel"}, {"section", "s"}, {"divisions", 3}}}},
                     json{{"op", "add"},
                          {"path", "/joints"},
                          {"value", {{{"id", "hinge"}, {"type", "revolute"}, {"nodes", {"C", "D"}}, {"axes", {{0, 0, 1}}},
                                      {"stiffness", {1e5}}}}}},
                     json{{"op", "replace"}, {"path", "/analyses/1/node"}, {"value", "D"}}};
  const json list = {
      {"model", model},
      {"cases", {json{{"id", "ok"}, {"set", {{"/loads/0/force/1", -5.0}}}},
                 json{{"id", "grown"}, {"patch", grow}},
                 json{{"id", "mechanism"}, {"set", {{"/supports/0/fix/3", "ux"}}}},  // rx free
                 json{{"id", "bad"}, {"set", {{"/supports/0/fix/3", "qx"}}}},        // no such DOF
                 json{{"id", "longer"}, {"set", {{"/nodes/1/xyz/0", 3.0}}}}}},
      {"outputs", {"analyses.K.matrix", "analyses.K.rank", "analyses.lin.nodes.B.displacement"}}};
  const Sweep s = beamfea::read_sweep(list, fs::temp_directory_path());
  beamfea::SweepWorkspace workspace(s);
  SweepCaseResult reused;
  std::size_t seen_ok = 0, seen_failed = 0, seen_bad = 0;
  for (const std::size_t i : {0, 1, 2, 3, 4, 1, 0, 3, 1, 1, 2, 4, 0}) {
    beamfea::run_sweep_case(s, i, {}, workspace, reused);
    const SweepCaseResult fresh = beamfea::run_sweep_case(s, i);
    EXPECT_EQ(reused.status, fresh.status) << "case " << i;
    EXPECT_EQ(reused.message, fresh.message) << "case " << i;
    EXPECT_EQ(reused.outputs, fresh.outputs) << "case " << i;
    switch (fresh.status) {
      case SweepCaseResult::Status::Succeeded: ++seen_ok; break;
      case SweepCaseResult::Status::AnalysisFailed: ++seen_failed; break;
      case SweepCaseResult::Status::BadInput: ++seen_bad; break;
    }
  }
  EXPECT_EQ(seen_ok, 9u);
  EXPECT_EQ(seen_failed, 2u);
  EXPECT_EQ(seen_bad, 2u);
  // The grown model's stiffness at D differs from the cantilever's at B (the case really changed
  // the model), and is of full rank.
  beamfea::run_sweep_case(s, 1, {}, workspace, reused);
  const SweepCaseResult plain = beamfea::run_sweep_case(s, 0);
  ASSERT_EQ(reused.status, SweepCaseResult::Status::Succeeded) << reused.message;
  EXPECT_NE(reused.outputs[0], plain.outputs[0]);
  ASSERT_EQ(reused.outputs[1].size(), 1u);
  EXPECT_EQ(reused.outputs[1][0].second, "6");
}

}  // namespace sweep_test
