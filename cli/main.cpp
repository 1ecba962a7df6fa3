// beamfea: the command-line program.
//   beamfea run model.json --out DIR     run every analysis, write DIR/results.json and VTK files
//                                        (cli/run_command.cpp; under mpirun, one model on K processes)
//   beamfea check model.json             validate only (the same validation as run)
//   beamfea sweep sweep.json --out DIR   many cases, one table DIR/cases.csv (cli/sweep_command.cpp)
//   beamfea sections [shape key=value ...]  the section shapes, or one shape's properties
//   beamfea urdf robot.urdf [--sidecar flex.json] -o model.json   a robot description as a model
//   beamfea lump model.json --links links.json -o lumped.json   the lumped (VJM) model (cli/lump_command.cpp)
// Exit codes: 0 success, 1 an analysis failed, 2 bad input (DIR left as it was).
#include <CLI/CLI.hpp>

#include <iostream>

#include "app/program_settings.hpp"
#include "cli/lump_command.hpp"
#include "cli/run_command.hpp"
#include "cli/sections_command.hpp"
#include "cli/sweep_command.hpp"
#include "cli/urdf_command.hpp"
#include "core/errors.hpp"
#include "core/version.hpp"
#include "io/model_reader.hpp"
#include "io/model_warnings.hpp"
#include "io/run.hpp"
#include "solvers/petsc_solver.hpp"

int main(int argc, char** argv) {
  // PETSc (the iterative solver, started on first use) finalised as main returns, whichever way.
  const struct PetscAtExit {
    ~PetscAtExit() { beamfea::finalize_petsc(); }
  } petsc_at_exit;
  // The BLAS kernels, the libraries' OpenMP, the prefault thread and the huge-page advice, before
  // any analysis (app/program_settings.hpp).
  const auto settings = beamfea::app::configure_program();
  CLI::App app{"beamfea: matrix structural analysis of 3-D frames of Euler-Bernoulli beams"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("beamfea ") + beamfea::kVersion + "\nBLAS: " + beamfea::app::describe(settings.blas) +
                                          "\nOpenMP: " + (settings.openmp_serial ? "the libraries' parallel regions on one thread"
                                                                         : "as the environment says") +
                                          "\nHuge pages: " + settings.huge_pages.reason);

  const auto run = beamfea::cli::add_run_command(app);

  std::string check_path;
  auto* check = app.add_subcommand("check", "Validate a model file without analysing it");
  check->add_option("model", check_path, "Model file (JSON)")->required();

  const auto sweep = beamfea::cli::add_sweep_command(app);
  const auto sections = beamfea::cli::add_sections_command(app);
  const auto urdf = beamfea::cli::add_urdf_command(app);
  const auto lump = beamfea::cli::add_lump_command(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  beamfea::app::install_openblas_threads_hook();
  if (*sweep->app) return beamfea::cli::run_sweep_command(*sweep);
  if (*sections->app) return beamfea::cli::run_sections_command(*sections);
  if (*urdf->app) return beamfea::cli::run_urdf_command(*urdf);
  if (*lump->app) return beamfea::cli::run_lump_command(*lump);
  if (*run->app) return beamfea::cli::run_run_command(*run, settings);
  // `check`: bad input (InputError, ModelError from validation) is exit 2.
  try {
    const auto doc = beamfea::read_json_file(check_path);
    const auto model = beamfea::load_and_check(doc);
    for (const std::string& w : beamfea::model_warnings(model)) std::cerr << "beamfea: warning: " << w << "\n";
    std::cout << check_path << ": ok (" << model.nodes.size() << " nodes, " << model.elements.size()
              << " elements, " << model.joints.size() << " joints)\n";
    return 0;
  } catch (const beamfea::InputError& e) {
    std::cerr << "beamfea: error: " << e.what() << "\n";
    return 2;
  } catch (const beamfea::ModelError& e) {
    std::cerr << "beamfea: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "beamfea: error: " << e.what() << "\n";
    return 1;
  }
}
