#pragma once
// One model file through the program, for the tests of exit codes, messages and outputs
// (tests/cli/bad_input_test.cpp, trust_test.cpp, tests/io/modal_input_test.cpp,
// path_frequencies_cli_test.cpp): the text is written to <tmp>/model.json and
// `beamfea run <it> --out <tmp>/out -q` (or `check`) is run; the exit code, stdout and stderr
// together, and the folder come back.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/files.hpp"
#include "support/models.hpp"

namespace beamfea::test {

struct CliCase {
  int code = -1;
  std::string message;         // stdout and stderr
  std::filesystem::path dir;   // the test's folder; --out is dir / "out"
  std::filesystem::path out() const { return dir / "out"; }
  bool results_written() const { return std::filesystem::exists(out() / "results.json"); }
  // The run's results.json (throws where there is none).
  nlohmann::json results() const { return read_json(out() / "results.json"); }
};

// `verb` "run" or "check"; keep_out: --out exists beforehand and holds old.txt (a run's outputs
// must leave it there).
inline CliCase run_model_text(const std::string& name, const std::string& text, const std::string& verb = "run",
                              bool keep_out = false) {
  CliCase c;
  c.dir = temp_dir(name);
  if (keep_out) {
    std::filesystem::create_directories(c.out());
    write_file(c.out() / "old.txt", "from an earlier run");
  }
  write_file(c.dir / "model.json", text);
  std::string args = verb + " " + (c.dir / "model.json").string();
  if (verb == "run") args += " --out " + c.out().string() + " -q";
  const auto r = run_cli(args);
  c.code = r.exit_code;
  c.message = r.output;
  return c;
}

inline CliCase run_model(const std::string& name, const nlohmann::json& d, const std::string& verb = "run",
                         bool keep_out = false) {
  return run_model_text(name, d.dump(), verb, keep_out);
}

// Bad input: exit 2, --out left absent, and the message names each fragment (a JSON pointer, an
// entity, the reason).
inline void expect_bad_input(const CliCase& c, const std::vector<std::string>& fragments) {
  EXPECT_EQ(c.code, 2) << c.message;
  EXPECT_FALSE(std::filesystem::exists(c.out())) << "bad input must leave --out as it was (absent)";
  for (const auto& f : fragments)
    EXPECT_NE(c.message.find(f), std::string::npos) << "missing '" << f << "' in: " << c.message;
}

}  // namespace beamfea::test
