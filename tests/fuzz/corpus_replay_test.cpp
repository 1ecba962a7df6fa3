// Replays every file of the fuzz corpus (tests/fuzz/corpus: seeds from the examples and tests,
// and the mutations that found bugs) through the program on every build (issue 9). Each case:
// no crash, no hang; `check` exits 0 or 2 and `run` agrees with it (one shared validation):
// check 2 -> run 2 with --out left absent; check 0 -> run 0 or 1 with a parsable results.json.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "support/models.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::vector<fs::path> corpus() {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(fs::path(BEAMFEA_SOURCE_DIR) / "tests" / "fuzz" / "corpus"))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
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
