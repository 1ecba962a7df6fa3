#pragma once
// `beamfea lump model.json --links links.json -o lumped.json`: the lumped (VJM) model of a beam
// model, one 6-D virtual spring per link with the link's condensed stiffness (io/lump.hpp).
#include <CLI/CLI.hpp>
#include <memory>
#include <string>

namespace beamfea::cli {

struct LumpCommand {
  CLI::App* app = nullptr;
  std::string model, links, out;
};

// Adds the subcommand to `app`; the returned options are filled by app.parse().
std::unique_ptr<LumpCommand> add_lump_command(CLI::App& app);

// Runs it; returns the exit code (0, or 2 for bad input: the output file is then not written).
int run_lump_command(const LumpCommand& cmd);

}  // namespace beamfea::cli
