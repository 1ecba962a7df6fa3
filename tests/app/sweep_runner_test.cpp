// The sweep loop in process (app/sweep_runner.hpp): grids and lists, set and patch forms,
// collected outputs against closed forms, parallel == serial, failing cases, resume, the stop
// flag and the progress callback.
#include "app/sweep_runner.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

#include "core/errors.hpp"
#include "support/sweep_util.hpp"

namespace sweep_runner_test {

using namespace sweep_test;
using beamfea::InputError;
using beamfea::Sweep;
using beamfea::SweepOptions;
using beamfea::SweepProgress;
using beamfea::SweepSummary;

namespace {

SweepOptions quiet_options(const fs::path& out, int jobs = 1) {
  SweepOptions o;
  o.out_dir = out;
  o.jobs = jobs;
  return o;
}

json load_grid() {
  return json{{"grid", json::array({json{{"name", "P"}, {"pointer", "/loads/0/force/1"}, {"values", {-1000, -2000, 500.5}}},
                                    json{{"name", "tip"}, {"pointer", "/nodes/1/xyz"}, {"values", {{1, 0, 0}, {2.5, 0, 0}}}}})},
              {"outputs", {"analyses.lin.nodes.B.displacement[1]", "analyses.K.matrix"}}};
}

}  // namespace

TEST(SweepRunner, GridOfLoadsAndLengthsMatchesCantileverClosedForms) {
  const auto dir = temp_dir("grid");
  const Sweep s = beamfea::read_sweep_file(write_sweep(dir, load_grid()).string());
  ASSERT_EQ(s.size(), 6u);
  const auto summary = beamfea::run_sweep(s, quiet_options(dir / "out"));
  EXPECT_EQ(summary.ok, 6u);
  EXPECT_EQ(summary.exit_code(), 0);

  bool well_formed = false;
  const Csv t = read_csv(dir / "out" / "cases.csv", &well_formed);
  ASSERT_TRUE(well_formed);
  ASSERT_EQ(t.rows.size(), 6u);
  // Columns: case, parameters, flattened outputs (6x6 matrix = 36 columns), status, message, time.
  EXPECT_EQ(t.header.size(), 1u + 2u + 1u + 36u + 3u);
  const int P = t.col("P"), uy = t.col("analyses.lin.nodes.B.displacement[1]");
  const int k11 = t.col("analyses.K.matrix[1][1]"), k15 = t.col("analyses.K.matrix[1][5]"), st = t.col("status");
  ASSERT_GE(P, 0);
  ASSERT_GE(uy, 0);
  ASSERT_GE(k11, 0);
  ASSERT_GE(k15, 0);
  const double Ls[2] = {1.0, 2.5};
  for (std::size_t i = 0; i < 6; ++i) {
    const auto& r = t.rows[i];
    EXPECT_EQ(r[0], std::to_string(i));  // sorted by case order, last axis fastest
    EXPECT_EQ(r[st], "ok");
    const double L = Ls[i % 2], p = std::stod(r[P]);
    const double v = p * L * L * L / (3 * kE * kIz);
    EXPECT_NEAR(std::stod(r[uy]), v, 1e-9 * std::abs(v));
    EXPECT_NEAR(std::stod(r[k11]), 12 * kE * kIz / (L * L * L), 1e-9 * 12 * kE * kIz / (L * L * L));
    EXPECT_NEAR(std::stod(r[k15]), 6 * kE * kIz / (L * L) * (std::stod(r[k15]) < 0 ? -1 : 1), 1e-6 * kE * kIz / (L * L));
  }
}

TEST(SweepRunner, ListCasesApplySetsAndJsonPatches) {
  const auto dir = temp_dir("list");
  json sweep = {
      {"cases",
       {json{{"id", "soft"}, {"parameters", {{"E", 70e9}}}, {"set", {{"/materials/0/E", 70e9}}}},
        json{{"id", "stiff"},
             {"parameters", {{"E", 210e9}, {"Iz", 4e-6}}},
             {"patch", {json{{"op", "replace"}, {"path", "/sections/0/Iz"}, {"value", 4e-6}}}}},
        // Both forms in one case: "set" first, then the patch (which adds a second tip load).
        json{{"id", "both"},
             {"set", {{"/loads/0/force/1", -500.0}}},
             {"patch", {json{{"op", "add"}, {"path", "/loads/-"}, {"value", {{"node", "B"}, {"force", {0, -500, 0}}}}}}}}}},
      {"outputs", {json{{"name", "v"}, {"path", "/analyses/lin/nodes/B/displacement/1"}}}}};
  const Sweep s = beamfea::read_sweep_file(write_sweep(dir, sweep).string());
  EXPECT_EQ(s.parameter_names, (std::vector<std::string>{"E", "Iz", "/loads/0/force/1"}));
  const auto summary = beamfea::run_sweep(s, quiet_options(dir / "out", 2));
  EXPECT_EQ(summary.ok, 3u);
  const Csv t = read_csv(dir / "out" / "cases.csv");
  ASSERT_EQ(t.rows.size(), 3u);
  const int v = t.col("v");
  const double L = 2.0;
  EXPECT_EQ(t.rows[0][0], "soft");
  EXPECT_NEAR(std::stod(t.rows[0][v]), -1000 * L * L * L / (3 * 70e9 * kIz), 1e-12);
  EXPECT_EQ(t.rows[1][0], "stiff");
  EXPECT_EQ(t.rows[1][t.col("Iz")], "4e-06");
  EXPECT_NEAR(std::stod(t.rows[1][v]), -1000 * L * L * L / (3 * kE * 4e-6), 1e-12);
  EXPECT_EQ(t.rows[2][0], "both");
  EXPECT_EQ(t.rows[2][t.col("/loads/0/force/1")], "-500");
  EXPECT_NEAR(std::stod(t.rows[2][v]), -1000 * L * L * L / (3 * kE * kIz), 1e-12);
}

TEST(SweepRunner, ParallelRunGivesTheSerialTable) {
  const auto dir = temp_dir("parallel");
  std::vector<double> loads, lengths;
  for (int i = 0; i < 40; ++i) loads.push_back(-100.0 * (i + 1));
  for (int i = 0; i < 10; ++i) lengths.push_back(0.5 + 0.25 * i);
  json sweep = {{"grid", {json{{"name", "P"}, {"pointer", "/loads/0/force/1"}, {"values", loads}},
                          json{{"name", "L"}, {"pointer", "/nodes/1/xyz/0"}, {"values", lengths}}}},
                {"outputs", {"analyses.lin.nodes.B.displacement", "analyses.K.matrix", "analyses.K.rank"}}};
  const Sweep s = beamfea::read_sweep_file(write_sweep(dir, sweep).string());
  const auto serial = beamfea::run_sweep(s, quiet_options(dir / "serial", 1));
  const auto parallel = beamfea::run_sweep(s, quiet_options(dir / "parallel", 4));
  EXPECT_EQ(serial.ok, 400u);
  EXPECT_EQ(parallel.ok, 400u);
  const Csv a = read_csv(dir / "serial" / "cases.csv"), b = read_csv(dir / "parallel" / "cases.csv");
  EXPECT_EQ(a.header, b.header);
  EXPECT_EQ(a.without_time(), b.without_time());
}

TEST(SweepRunner, FailingCasesAreRowsAndTheSweepGoesOn) {
  const auto dir = temp_dir("failing");
  json sweep = {{"cases",
                 {json{{"id", "a"}, {"set", {{"/loads/0/force/1", -1.0}}}},
                  // No support: a mechanism, so the analyses fail.
                  json{{"id", "free"}, {"patch", {json{{"op", "remove"}, {"path", "/supports/0"}}}}},
                  // An unknown section: the case's model is bad input.
                  json{{"id", "bad"}, {"set", {{"/elements/0/section", "nope"}}}},
                  json{{"id", "z"}, {"set", {{"/loads/0/force/1", -2.0}}}}}},
                {"outputs", {"analyses.lin.nodes.B.displacement[1]"}}};
  const Sweep s = beamfea::read_sweep_file(write_sweep(dir, sweep).string());
  // Two workers: the table sorted and counted after the run (finish_sweep_table). One: the cases
  // inline, the table written in order and its statuses counted by the runner as it goes.
  for (const int jobs : {2, 1}) {
    const auto out = dir / ("out" + std::to_string(jobs));
    const auto summary = beamfea::run_sweep(s, quiet_options(out, jobs));
    EXPECT_EQ(summary.ok, 2u) << jobs;
    EXPECT_EQ(summary.analysis_failed, 1u) << jobs;
    EXPECT_EQ(summary.bad_input, 1u) << jobs;
    EXPECT_EQ(summary.exit_code(), 1);
    const Csv t = read_csv(out / "cases.csv");
    ASSERT_EQ(t.rows.size(), 4u);
    const int st = t.col("status"), msg = t.col("message");
    EXPECT_EQ(t.rows[0][st], "ok");
    EXPECT_EQ(t.rows[1][st], "analysis failed");
    EXPECT_FALSE(t.rows[1][msg].empty());
    EXPECT_EQ(t.rows[2][st], "bad input");
    EXPECT_NE(t.rows[2][msg].find("/elements/0/section"), std::string::npos) << t.rows[2][msg];
    EXPECT_EQ(t.rows[3][st], "ok");
  }
  EXPECT_EQ(read_csv(dir / "out1" / "cases.csv").without_time(), read_csv(dir / "out2" / "cases.csv").without_time());
}

// A one-worker sweep whose first cases fail (the probe runs them before one ends ok) counts the
// probe's rows with the others: the summary is that of the table.
TEST(SweepRunner, InlineSweepCountsTheProbesFailedCases) {
  const auto dir = temp_dir("inline_counts");
  json sweep = {{"grid", {json{{"name", "sec"}, {"pointer", "/elements/0/section"}, {"values", {"nope", "s"}}},
                          json{{"name", "P"}, {"pointer", "/loads/0/force/1"}, {"values", {-1, -2, -3}}}}},
                {"outputs", {"analyses.lin.nodes.B.displacement[1]"}}};
  const Sweep s = beamfea::read_sweep_file(write_sweep(dir, sweep).string());
  const auto summary = beamfea::run_sweep(s, quiet_options(dir / "out", 1));
  EXPECT_EQ(summary.ok, 3u);
  EXPECT_EQ(summary.bad_input, 3u);
  EXPECT_EQ(summary.analysis_failed, 0u);
  const Csv t = read_csv(dir / "out" / "cases.csv");
  ASSERT_EQ(t.rows.size(), 6u);
  std::size_t bad = 0;
  for (const auto& row : t.rows) bad += row[t.col("status")] == "bad input";
  EXPECT_EQ(bad, 3u);
}

TEST(SweepRunner, ResumeRunsOnlyTheCasesMissingFromTheTable) {
  const auto dir = temp_dir("resume");
  std::vector<double> loads;
  for (int i = 0; i < 30; ++i) loads.push_back(-10.0 * (i + 1));
  json sweep = {{"grid", {json{{"name", "P"}, {"pointer", "/loads/0/force/1"}, {"values", loads}}}},
                {"outputs", {"analyses.lin.nodes.B.displacement[1]"}}};
  const Sweep s = beamfea::read_sweep_file(write_sweep(dir, sweep).string());
  beamfea::run_sweep(s, quiet_options(dir / "out", 2));
  const Csv full = read_csv(dir / "out" / "cases.csv");

  // Keep the header and 7 rows, as if the sweep had been killed.
  const std::string text = read(dir / "out" / "cases.csv");
  std::size_t pos = 0;
  for (int line = 0; line < 8; ++line) pos = text.find('\n', pos) + 1;
  write(dir / "out" / "cases.csv", text.substr(0, pos));

  auto opt = quiet_options(dir / "out", 3);
  opt.resume = true;
  const auto summary = beamfea::run_sweep(s, opt);
  EXPECT_EQ(summary.skipped, 7u);
  EXPECT_EQ(summary.ran, 23u);
  EXPECT_EQ(summary.ok, 30u);
  const Csv resumed = read_csv(dir / "out" / "cases.csv");
  EXPECT_EQ(resumed.without_time(), full.without_time());

  // Resuming a complete table runs nothing.
  EXPECT_EQ(beamfea::run_sweep(s, opt).ran, 0u);
}

TEST(SweepRunner, KeepWritesEachCasesResults) {
  const auto dir = temp_dir("keep");
  json sweep = {{"grid", {json{{"pointer", "/loads/0/force/1"}, {"values", {-1, -2}}}}}, {"outputs", json::array()}};
  const Sweep s = beamfea::read_sweep_file(write_sweep(dir, sweep).string());
  auto opt = quiet_options(dir / "out");
  beamfea::run_sweep(s, opt);
  EXPECT_FALSE(fs::exists(dir / "out" / "cases"));
  opt.keep = true;
  beamfea::run_sweep(s, opt);
  EXPECT_TRUE(fs::exists(dir / "out" / "cases" / "0" / "results.json"));
  EXPECT_TRUE(fs::exists(dir / "out" / "cases" / "1" / "lin.vtu"));
}

// The progress callback sees every case run now (the probe's first case excluded, as in the
// table's count) with the failures counted, and ends with exactly one final call.
TEST(SweepRunner, ProgressCountsTheCasesAndEndsWithOneFinalCall) {
  const auto dir = temp_dir("progress");
  json sweep = {{"grid", {json{{"name", "P"}, {"pointer", "/loads/0/force/1"}, {"values", {-1, -2, -3, -4, -5, -6, -7, -8}}},
                          json{{"name", "sec"}, {"pointer", "/elements/0/section"}, {"values", {"s", "nope"}}}}},
                {"outputs", {"analyses.lin.nodes.B.displacement[1]"}}};
  const Sweep s = beamfea::read_sweep_file(write_sweep(dir, sweep).string());
  auto opt = quiet_options(dir / "out", 2);
  std::vector<SweepProgress> calls;
  opt.progress = [&](const SweepProgress& p) { calls.push_back(p); };
  const SweepSummary summary = beamfea::run_sweep(s, opt);
  EXPECT_EQ(summary.ok, 8u);
  EXPECT_EQ(summary.bad_input, 8u);
  ASSERT_FALSE(calls.empty());
  std::size_t finals = 0;
  for (std::size_t k = 0; k < calls.size(); ++k) {
    finals += calls[k].final;
    if (k > 0) {
      EXPECT_GE(calls[k].done, calls[k - 1].done);
    }
  }
  EXPECT_EQ(finals, 1u);
  const SweepProgress& last = calls.back();
  EXPECT_TRUE(last.final);
  EXPECT_EQ(last.total, 15u);  // case 0 ("s", ok) settled the columns
  EXPECT_EQ(last.done, 15u);
  EXPECT_EQ(last.failed, 8u);  // every "nope" case
  EXPECT_GT(last.elapsed_s, 0.0);
}

// The stop flag (set here from the progress callback, as a signal handler sets it in the
// program) stops handing out cases: the table holds the finished cases, sorted and whole, and
// the summary says interrupted (exit code 130).
TEST(SweepRunner, StopFlagEndsTheSweepWithASortedTableOfTheFinishedCases) {
  const auto dir = temp_dir("stop");
  std::vector<double> loads;
  for (int i = 0; i < 2000; ++i) loads.push_back(-1.0 * (i + 1));
  json sweep = {{"grid", {json{{"name", "P"}, {"pointer", "/loads/0/force/1"}, {"values", loads}}}},
                {"outputs", {"analyses.lin.nodes.B.displacement[1]"}}};
  const Sweep s = beamfea::read_sweep_file(write_sweep(dir, sweep).string());
  std::atomic<bool> stop{false};
  auto opt = quiet_options(dir / "out", 2);
  opt.stop = &stop;
  opt.progress = [&](const SweepProgress& p) {
    if (p.done >= 10) stop = true;
  };
  const SweepSummary summary = beamfea::run_sweep(s, opt);
  EXPECT_TRUE(summary.interrupted);
  EXPECT_EQ(summary.exit_code(), 130);
  EXPECT_NE(summary.report().find("interrupted"), std::string::npos) << summary.report();
  bool well_formed = false;
  const Csv t = read_csv(dir / "out" / "cases.csv", &well_formed);
  EXPECT_TRUE(well_formed);
  EXPECT_EQ(t.rows.size(), summary.ok);
  EXPECT_GE(t.rows.size(), 11u);
  EXPECT_LT(t.rows.size(), 2000u);
  for (std::size_t i = 1; i < t.rows.size(); ++i) EXPECT_LT(std::stoul(t.rows[i - 1][0]), std::stoul(t.rows[i][0]));

  // --resume completes the table.
  auto again = quiet_options(dir / "out", 2);
  again.resume = true;
  const SweepSummary rest = beamfea::run_sweep(s, again);
  EXPECT_FALSE(rest.interrupted);
  EXPECT_EQ(rest.skipped, t.rows.size());
  EXPECT_EQ(rest.ok, 2000u);
}

}  // namespace sweep_runner_test

namespace sweep_runner_test {

// Two ranks whose rank 1 never answers (it died as the sweep started): rank 0's side of the
// transport, nothing ever received.
class SilentPeer : public beamfea::SweepComm {
 public:
  int rank() const override { return 0; }
  int size() const override { return 2; }
  void broadcast(std::string&) override {}
  void send(const std::string&, bool) override {}
  bool receive(std::string&, bool&, int&) override { return false; }
};

// A rank that stops answering is lost after the rank timeout: rank 0 finishes the table with its
// own rows, names the rank and the cases it held (every other case of the grid: rank r runs the
// cases r modulo 2 after the probe's case 0), exits 1, and --resume completes the table as an
// uninterrupted run writes it.
TEST(SweepRunner, ALostRankIsNamedWithItsCasesAndTheTableResumes) {
  const auto dir = temp_dir("lost_rank");
  std::vector<double> loads;
  for (int i = 0; i < 10; ++i) loads.push_back(-10.0 * (i + 1));
  const json sweep = {{"grid", {json{{"name", "P"}, {"pointer", "/loads/0/force/1"}, {"values", loads}}}},
                      {"outputs", {"analyses.lin.nodes.B.displacement[1]"}}};
  const Sweep s = beamfea::read_sweep_file(write_sweep(dir, sweep).string());
  auto opt = quiet_options(dir / "out");
  opt.rank_timeout_s = 0.2;
  SilentPeer peer;
  const SweepSummary summary = beamfea::run_sweep(s, opt, &peer);
  ASSERT_EQ(summary.lost.size(), 1u);
  EXPECT_EQ(summary.lost[0].rank, 1);
  EXPECT_EQ(summary.lost[0].cases, (std::vector<std::string>{"1", "3", "5", "7", "9"}));
  EXPECT_EQ(summary.exit_code(), 1);
  EXPECT_NE(summary.lost_report().find("rank 1 "), std::string::npos) << summary.lost_report();
  EXPECT_NE(summary.lost_report().find("1, 3, 5, 7, 9"), std::string::npos) << summary.lost_report();
  bool well_formed = false;
  EXPECT_EQ(read_csv(dir / "out" / "cases.csv", &well_formed).rows.size(), 5u);
  EXPECT_TRUE(well_formed);

  opt.resume = true;
  const SweepSummary resumed = beamfea::run_sweep(s, opt);
  EXPECT_EQ(resumed.skipped, 5u);
  EXPECT_EQ(resumed.ok, 10u);
  EXPECT_TRUE(resumed.lost.empty());
  beamfea::run_sweep(s, quiet_options(dir / "whole"));
  EXPECT_EQ(read_csv(dir / "out" / "cases.csv").without_time(), read_csv(dir / "whole" / "cases.csv").without_time());
}

}  // namespace sweep_runner_test
