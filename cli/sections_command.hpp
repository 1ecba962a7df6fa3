#pragma once
// `beamfea sections`: the section shapes a model's "shape" names, with their dimensions and
// formulas; `beamfea sections i h=0.3 b=0.15 tw=0.0071 tf=0.0107 r=0.015`: one shape's properties
// (A, Iy, Iz, J, ky, kz, Iyz and the principal moments), as text or, with --json, as a JSON object.
#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <vector>

namespace beamfea::cli {

struct SectionsCommand {
  CLI::App* app = nullptr;
  std::string shape;                   // empty: list the shapes
  std::vector<std::string> dimensions;  // "key=value"
  bool json = false;
};

// Adds the subcommand to `app`; the returned options are filled by app.parse().
std::unique_ptr<SectionsCommand> add_sections_command(CLI::App& app);

// Runs it; returns the exit code (0, or 2 for an unknown shape or bad dimensions).
int run_sections_command(const SectionsCommand& cmd);

}  // namespace beamfea::cli
