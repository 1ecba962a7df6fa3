// beamfea: the command-line program.
//   beamfea run model.json --out DIR     run every analysis, write DIR/results.json and VTK files
//   beamfea check model.json             validate only (the same validation as run)
//   beamfea sweep sweep.json --out DIR   many cases, one table DIR/cases.csv (cli/sweep_command.cpp)
//   beamfea sections [shape key=value ...]  the section shapes, or one shape's properties
//   beamfea urdf robot.urdf [--sidecar flex.json] -o model.json   a robot description as a model
//   beamfea lump model.json --links links.json -o lumped.json   the lumped (VJM) model (cli/lump_command.cpp)
// Exit codes: 0 success, 1 an analysis failed, 2 bad input (DIR left as it was).
#include <CLI/CLI.hpp>

#include <iostream>

#include "app/thread_tasks.hpp"
#include "app/program_settings.hpp"
#include "cli/lump_command.hpp"
#include "cli/sections_command.hpp"
#include "cli/sweep_command.hpp"
#include "cli/urdf_command.hpp"
#include "core/errors.hpp"
#include "core/version.hpp"
#include "io/model_reader.hpp"
#include "io/model_warnings.hpp"
#include "io/run.hpp"
#include "solvers/petsc_solver.hpp"

namespace {

int report_error(const std::exception& e, int code) {
  std::cerr << "beamfea: error: " << e.what() << "\n";
  return code;
}

// What a run holds until the program ends: the input document, the model and the results object
// (millions of small allocations at 1e5 DOFs) are left to the operating system, which takes the
// whole address space back at once, instead of being freed node by node (about 5 % of the process
// at 21,504 DOFs, docs/performance.md). The global pointer keeps them reachable, so leak checkers
// report nothing; it is volatile so that the compiler cannot drop the store to a variable nothing
// else reads (at -O1 it did, and LeakSanitizer saw the whole run as leaked).
struct RunState {
  nlohmann::json document;
  beamfea::Model model;
  beamfea::RunReport report;
};
RunState* volatile g_run_state = nullptr;

}  // namespace

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

  std::string model_path, out_dir = "out";
  bool no_vtk = false, quiet = false;
  std::vector<std::string> only;
  auto* run = app.add_subcommand("run", "Run the analyses of a model file");
  run->add_option("model", model_path, "Model file (JSON)")->required();
  run->add_option("--out,-o", out_dir, "Output folder (created if needed)")->capture_default_str();
  run->add_flag("--no-vtk", no_vtk, "Write results.json only");
  run->add_flag("--quiet,-q", quiet, "No progress lines on stderr");
  run->add_option("--analysis,-a", only, "Run only these analysis ids");

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
  // Bad input (InputError, ModelError from validation) is exit 2 and writes nothing; anything
  // that escapes a run after validation is exit 1.
  try {
    if (*check) {
      const auto doc = beamfea::read_json_file(check_path);
      const auto model = beamfea::load_and_check(doc);
      for (const std::string& w : beamfea::model_warnings(model)) std::cerr << "beamfea: warning: " << w << "\n";
      std::cout << check_path << ": ok (" << model.nodes.size() << " nodes, " << model.elements.size()
                << " elements, " << model.joints.size() << " joints)\n";
      return 0;
    }
    RunState& state = *new RunState;
    g_run_state = &state;
    state.document = beamfea::read_json_file(model_path);
    state.model = beamfea::load_and_check(state.document);
    beamfea::RunOptions opt;
    opt.out_dir = out_dir;
    opt.write_vtk = !no_vtk;
    opt.only = only;
    if (!quiet) opt.progress = [](const std::string& s) { std::cerr << s << "\n"; };
    if (!quiet && !settings.blas.replaced.empty()) std::cerr << "beamfea: BLAS: " << beamfea::app::describe(settings.blas) << "\n";
    opt.warning = [](const std::string& s) { std::cerr << "beamfea: warning: " << s << "\n"; };
    opt.parallel = beamfea::app::thread_tasks();  // a large results.json formatted on all cores
    opt.results_in_memory = false;  // the program only writes the results: the largest objects are made as
                                    // results.json is written, never held whole (io/deferred_results.hpp)
    state.report = beamfea::run_document(state.model, state.document, opt);
    if (!quiet) std::cerr << "beamfea: wrote " << (opt.out_dir / "results.json").string() << "\n";
    return state.report.failed ? 1 : 0;
  } catch (const beamfea::InputError& e) {
    return report_error(e, 2);
  } catch (const beamfea::ModelError& e) {
    return report_error(e, 2);
  } catch (const std::exception& e) {
    return report_error(e, 1);
  }
}
