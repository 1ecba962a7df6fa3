// Replays every file of the fuzz corpora through the program on every build
// (docs/testing.md). No crash, no hang, and:
// - tests/fuzz/corpus (models): `check` exits 0 or 2 and `run` agrees with it (one shared
//   validation): check 2 -> run 2 with --out left absent; check 0 -> run 0 or 1 with a parsable
//   results.json;
// - tests/fuzz/corpus_sweep (sweep files): `sweep` exits 2 with --out left absent, or 0/1 with a
//   whole table of one row per case, 0 exactly when every row is "ok".
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "io/sweep.hpp"
#include "support/files.hpp"
#include "support/models.hpp"
#include "support/sweep_util.hpp"

namespace corpus_replay_test {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::vector<fs::path> corpus(const std::string& folder = "corpus") {
  return beamfea::test::files_in(beamfea::test::source_path("tests/fuzz/" + folder));
}

// Seconds one case may take (the corpus holds small models; more is a hang).
constexpr int kCaseTimeout = 120;

}  // namespace

TEST(FuzzCorpus, EveryCaseEndsByTheRules) {
  const auto files = corpus();
  ASSERT_GE(files.size(), 20u) << "the corpus went missing";
  const auto dir = beamfea::test::temp_dir("corpus");
  int n_ok = 0, n_failed = 0, n_bad = 0;
  for (const auto& f : files) {
    SCOPED_TRACE(f.filename().string());
    const auto out = dir / f.stem();
    const std::string limit = "timeout " + std::to_string(kCaseTimeout) + " ";
    const auto check = beamfea::test::run_cli_with_prefix(limit, "check " + f.string());
    ASSERT_TRUE(check.exit_code == 0 || check.exit_code == 2) << "check: exit " << check.exit_code << "\n" << check.output;
    const auto run = beamfea::test::run_cli_with_prefix(limit, "run " + f.string() + " --out " + out.string() + " -q --no-vtk");
    if (check.exit_code == 2) {
      EXPECT_EQ(run.exit_code, 2) << "check rejected it, run did not:\n" << run.output;
      EXPECT_FALSE(fs::exists(out)) << "bad input must leave --out as it was";
      EXPECT_NE(run.output.find("error"), std::string::npos) << run.output;
      ++n_bad;
    } else {
      ASSERT_TRUE(run.exit_code == 0 || run.exit_code == 1) << "run: exit " << run.exit_code << "\n" << run.output;
      std::ifstream in(out / "results.json");
      ASSERT_TRUE(in.good()) << "no results.json";
      EXPECT_NO_THROW({
        const json results = json::parse(in);
        EXPECT_TRUE(results.contains("analyses"));
      });
      (run.exit_code == 0 ? n_ok : n_failed) += 1;
    }
  }
  std::cout << "[corpus] " << files.size() << " cases: " << n_ok << " exit 0, " << n_failed << " exit 1, " << n_bad
            << " exit 2\n";
}

TEST(FuzzCorpus, EverySweepEndsByTheRules) {
  const auto files = corpus("corpus_sweep");
  ASSERT_GE(files.size(), 8u) << "the sweep corpus went missing";
  const auto dir = beamfea::test::temp_dir("corpus_sweep");
  int n_ok = 0, n_failed = 0, n_bad = 0;
  for (const auto& f : files) {
    SCOPED_TRACE(f.filename().string());
    const auto out = dir / f.stem();
    const auto run = beamfea::test::run_cli_with_prefix("timeout " + std::to_string(kCaseTimeout) + " ",
                                                        "sweep " + f.string() + " --out " + out.string() + " -q --jobs 1");
    ASSERT_TRUE(run.exit_code == 0 || run.exit_code == 1 || run.exit_code == 2) << "exit " << run.exit_code << "\n"
                                                                                  << run.output;
    if (run.exit_code == 2) {
      EXPECT_FALSE(fs::exists(out)) << "a bad sweep file must leave --out as it was";
      EXPECT_NE(run.output.find("error"), std::string::npos) << run.output;
      ++n_bad;
      continue;
    }
    const beamfea::Sweep sweep = beamfea::read_sweep_file(f.string());  // the program accepted it
    bool well_formed = false;
    const auto table = sweep_test::read_csv(out / "cases.csv", &well_formed);
    EXPECT_TRUE(well_formed);
    ASSERT_EQ(table.rows.size(), sweep.size());
    const int status = table.col("status");
    ASSERT_GE(status, 0);
    bool all_ok = true;
    for (std::size_t i = 0; i < table.rows.size(); ++i) {
      EXPECT_EQ(table.rows[i][0], sweep.case_id(i));
      const std::string& st = table.rows[i][status];
      EXPECT_TRUE(st == "ok" || st == "analysis failed" || st == "bad input") << st;
      all_ok = all_ok && st == "ok";
    }
    EXPECT_EQ(run.exit_code, all_ok ? 0 : 1);
    (run.exit_code == 0 ? n_ok : n_failed) += 1;
  }
  std::cout << "[corpus_sweep] " << files.size() << " sweep files: " << n_ok << " exit 0, " << n_failed << " exit 1, "
            << n_bad << " exit 2\n";
}

}  // namespace corpus_replay_test
