#include "cli/lump_command.hpp"

#include <iostream>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/lump.hpp"
#include "io/model_reader.hpp"

namespace beamfea::cli {

std::unique_ptr<LumpCommand> add_lump_command(CLI::App& app) {
  auto cmd = std::make_unique<LumpCommand>();
  cmd->app = app.add_subcommand("lump", "Write the lumped (VJM) model of a beam model: one 6-D virtual spring per link, "
                                        "with the link's condensed stiffness");
  cmd->app->add_option("model", cmd->model, "Beam model file (JSON)")->required();
  cmd->app->add_option("--links,-l", cmd->links,
                       "Links file: {\"links\": [{\"id\", \"elements\": [...], \"base\": node, \"tip\": node}]}")
      ->required();
  cmd->app->add_option("--out,-o", cmd->out, "Lumped model file to write (JSON)")->required();
  return cmd;
}

int run_lump_command(const LumpCommand& cmd) {
  try {
    const nlohmann::json model = read_json_file(cmd.model);
    const nlohmann::json links = read_json_file(cmd.links);
    const nlohmann::json lumped = lump_model(model, links);
    write_text_atomic(cmd.out, lumped.dump(2) + "\n");
    std::cerr << "beamfea: wrote " << cmd.out << " (" << links["links"].size() << " links lumped)\n";
    return 0;
  } catch (const InputError& e) {
    std::cerr << "beamfea: error: " << e.what() << "\n";
    return 2;
  } catch (const ModelError& e) {
    std::cerr << "beamfea: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "beamfea: error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace beamfea::cli
