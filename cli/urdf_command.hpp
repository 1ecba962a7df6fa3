#pragma once
// `beamfea urdf robot.urdf [--sidecar flex.json] -o model.json`: a URDF robot description (and a
// side-car with joint stiffnesses and flexible links) converted to a model file (io/urdf_reader.hpp,
// docs/urdf.md). Without -o the model is printed on stdout.
#include <CLI/CLI.hpp>
#include <memory>
#include <string>

namespace beamfea::cli {

struct UrdfCommand {
  CLI::App* app = nullptr;
  std::string urdf;
  std::string sidecar;  // empty: none
  std::string out;      // empty: stdout
};

// Adds the subcommand to `app`; the returned options are filled by app.parse().
std::unique_ptr<UrdfCommand> add_urdf_command(CLI::App& app);

// Runs it; returns the exit code (0, or 2 for bad input: nothing is written).
int run_urdf_command(const UrdfCommand& cmd);

}  // namespace beamfea::cli
