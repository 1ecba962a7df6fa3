#pragma once
// `beamfea sweep sweep.json --out DIR`: many cases of one base model, one results table
// (docs/sweep.md). Under `mpirun -n K` the cases are split across the ranks and rank 0 writes
// the one table; MPI is used when the program was built with it (BEAMFEA_HAVE_MPI).
#include <CLI/CLI.hpp>
#include <memory>
#include <string>

namespace beamfea::cli {

struct SweepCommand {
  CLI::App* app = nullptr;
  std::string sweep_path;
  std::string out_dir = "out";
  int jobs = 0;
  bool keep = false;
  bool resume = false;
  bool quiet = false;
  std::string progress = "auto";
};

// Adds the subcommand to `app`; the returned options are filled by app.parse().
std::unique_ptr<SweepCommand> add_sweep_command(CLI::App& app);

// Runs it; returns the exit code (0 all cases ok, 1 some case failed, 2 bad input, 130 interrupted).
int run_sweep_command(const SweepCommand& cmd);

}  // namespace beamfea::cli
