#include "cli/urdf_command.hpp"

#include <iostream>
#include <optional>

#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/json_writer.hpp"
#include "io/model_reader.hpp"
#include "io/urdf_reader.hpp"

namespace beamfea::cli {

std::unique_ptr<UrdfCommand> add_urdf_command(CLI::App& app) {
  auto cmd = std::make_unique<UrdfCommand>();
  cmd->app = app.add_subcommand("urdf", "Convert a URDF robot description to a model file");
  cmd->app->add_option("robot", cmd->urdf, "URDF file")->required();
  cmd->app->add_option("--sidecar,-s", cmd->sidecar, "Side-car JSON: joint stiffnesses, flexible links, materials, sections");
  cmd->app->add_option("--out,-o", cmd->out, "Model file to write (default: stdout)");
  return cmd;
}

int run_urdf_command(const UrdfCommand& cmd) {
  try {
    std::optional<nlohmann::json> sidecar;
    if (!cmd.sidecar.empty()) sidecar = read_json_file(cmd.sidecar);
    const auto model = urdf_file_to_model(cmd.urdf, sidecar, "'" + cmd.sidecar + "'");
    // As results.json is written: one member per line, arrays of numbers on one line.
    std::string text;
    write_results_json(model, text);
    text += "\n";
    if (cmd.out.empty()) std::cout << text;
    else write_text_atomic(cmd.out, text);
    return 0;
  } catch (const InputError& e) {
    std::cerr << "beamfea: error: " << e.what() << "\n";
    return 2;
  } catch (const Error& e) {
    std::cerr << "beamfea: error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace beamfea::cli
