#pragma once
// `beamfea run model.json --out DIR`: every analysis of one model, DIR/results.json and each
// analysis's files (io/run.hpp). Under `mpirun -n K` (K > 1) the K processes run the one model
// together: each reads and checks it, the iterative solves (PETSc) are distributed over them, and
// rank 0 alone writes the outputs (docs/analyses/solver.md, "One model on several processes").
#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

#include "app/program_settings.hpp"

namespace beamfea::cli {

struct RunCommand {
  CLI::App* app = nullptr;
  std::string model_path;
  std::string out_dir = "out";
  bool no_vtk = false;
  bool quiet = false;
  std::vector<std::string> only;
};

// Adds the subcommand to `app`; the returned options are filled by app.parse().
std::unique_ptr<RunCommand> add_run_command(CLI::App& app);

// Runs it; returns the exit code (0 success, 1 an analysis failed, 2 bad input). Under mpirun a
// process that fails after the model was checked ends the whole job (MPI_Abort) with its message.
int run_run_command(const RunCommand& cmd, const app::ProgramSettings& settings);

}  // namespace beamfea::cli
