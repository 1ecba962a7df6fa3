#include "cli/run_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <thread>

#include "app/openblas.hpp"
#include "app/thread_tasks.hpp"
#include "cli/mpi_world.hpp"
#include "core/errors.hpp"
#include "io/model_reader.hpp"
#include "io/run.hpp"
#include "solvers/petsc_solver.hpp"

namespace beamfea::cli {

namespace {

// What a run holds until the program ends: the input document, the model and the results object
// (millions of small allocations at 1e5 DOFs) are left to the operating system, which takes the
// whole address space back at once, instead of being freed node by node (about 5 % of the process
// at 21,504 DOFs, docs/performance.md). The global pointer keeps them reachable, so leak checkers
// report nothing; it is volatile so that the compiler cannot drop the store to a variable nothing
// else reads (at -O1 it did, and LeakSanitizer saw the whole run as leaked).
struct RunState {
  nlohmann::json document;
  Model model;
  RunReport report;
};
RunState* volatile g_run_state = nullptr;

RunState& new_run_state() {
  RunState* state = new RunState;
  g_run_state = state;
  return *state;
}

// The options of one process's run: `root` writes the outputs and says what happens.
RunOptions run_options(const RunCommand& cmd, const app::ProgramSettings& settings, bool root, unsigned threads) {
  RunOptions opt;
  if (root) opt.out_dir = cmd.out_dir;
  opt.write_vtk = !cmd.no_vtk;
  opt.only = cmd.only;
  if (root && !cmd.quiet) opt.progress = [](const std::string& s) { std::cerr << s << "\n"; };
  if (root && !cmd.quiet && !settings.blas.replaced.empty())
    std::cerr << "beamfea: BLAS: " << app::describe(settings.blas) << "\n";
  if (root) opt.warning = [](const std::string& s) { std::cerr << "beamfea: warning: " << s << "\n"; };
  opt.parallel = app::thread_tasks(threads);  // a large results.json formatted on all cores
  opt.results_in_memory = false;  // the program only writes the results: the largest objects are made as
                                  // results.json is written, never held whole (io/deferred_results.hpp)
  return opt;
}

// Exit code of an exception: 2 bad input, 1 anything else.
int exit_code_of(const std::exception& e) {
  return dynamic_cast<const InputError*>(&e) || dynamic_cast<const ModelError*>(&e) ? 2 : 1;
}

// One process. Bad input (InputError, ModelError from validation) is exit 2 and writes nothing;
// anything that escapes a run after validation is exit 1.
int run_alone(const RunCommand& cmd, const app::ProgramSettings& settings) {
  try {
    RunState& state = new_run_state();
    state.document = read_json_file(cmd.model_path);
    state.model = load_and_check(state.document);
    const RunOptions opt = run_options(cmd, settings, true, 0);
    state.report = run_document(state.model, state.document, opt);
    if (!cmd.quiet) std::cerr << "beamfea: wrote " << (opt.out_dir / "results.json").string() << "\n";
    return state.report.failed ? 1 : 0;
  } catch (const std::exception& e) {
    std::cerr << "beamfea: error: " << e.what() << "\n";
    return exit_code_of(e);
  }
}

#ifdef BEAMFEA_HAVE_MPI
// A process other than rank 0 that fails waits this long before it prints and ends the job: when
// every process fails alike (the same model, the same code), rank 0's message comes first and its
// MPI_Abort ends the others before they print theirs, so that the job says it once. (One second
// was not always enough on a loaded 2-core machine: mpirun's ending of the others can take longer.)
constexpr std::chrono::milliseconds kNonRootAbortDelay{5000};

// One line to stderr in one write: mpirun forwards each process's output as it arrives and
// prints its own notices (MPI_Abort's) among them, so a line written piece by piece can be cut.
void print_line(const std::string& line) {
  const std::string text = line + "\n";
  std::cerr.write(text.data(), static_cast<std::streamsize>(text.size()));
  std::cerr.flush();
}

// Ends every process of the job with this process's message (MPI_Abort, exit `code`).
[[noreturn]] void end_job(const MpiWorld& world, const std::string& what, int code) {
  if (world.rank() != 0) std::this_thread::sleep_for(kNonRootAbortDelay);
  print_line(fmt::format("beamfea: error: rank {} of {}: {} (ending all {} processes; no results written)", world.rank(),
                         world.size(), what, world.size()));
  world.abort(code);
}

// Several processes, one model. What is distributed and what is replicated:
//   - every process reads and checks the model; the processes agree on the outcome (one
//     collective) before anything else, so that bad input, or a file one process cannot read,
//     ends all of them with exit 2 and nothing written (rank 0's message, else the failing rank's);
//   - then PETSc starts on all the processes (PETSC_COMM_WORLD = MPI_COMM_WORLD), so that each
//     iterative solve is distributed over them (solvers/petsc_solver.hpp); everything else (the
//     assembly of K_ff, direct solves, eigen-solves, the results) is replicated: every process
//     runs every analysis alike, hence makes the same collective calls in the same order;
//   - rank 0 alone writes the outputs, staged as in one process and moved into place once every
//     process has finished (RunOptions::before_commit), and prints the progress and the warnings.
// A process that throws during the run (a failure of its own: memory, a PETSc error) cannot tell
// the others, which may be waiting in a collective call: it ends the job (MPI_Abort) with its
// message naming it. So does an analysis that throws anything but a ModelError (which the model
// decides, hence every process meets alike and reports as the analysis's failure, as one process
// does): where one process alone may have met it, an analysis failure of that process alone would
// leave the others waiting. Rank 0's staged files are then never moved into place (no results.json; its
// hidden staging folder may stay in DIR, as when a one-process run is killed).
int run_distributed(const RunCommand& cmd, const app::ProgramSettings& settings, const MpiWorld& world) {
  const bool root = world.rank() == 0;
  const int ranks = world.size();
  // The cores of this host shared among its processes: the BLAS (a replicated direct solve) and
  // the threads of the element matrices and of results.json.
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const unsigned per_process = std::max(1u, cores / static_cast<unsigned>(ranks_on_this_host(ranks)));
  app::set_blas_threads(static_cast<int>(per_process));

  RunState& state = new_run_state();
  int code = 0;
  std::string message;
  try {
    state.document = read_json_file(cmd.model_path);
    state.model = load_and_check(state.document);
  } catch (const std::exception& e) {
    code = exit_code_of(e);
    message = e.what();
  }
  const int agreed = world.max_over_ranks(code);
  const int root_code = world.from_rank_0(code);
  if (agreed != 0) {
    if (root && code != 0) print_line("beamfea: error: " + message);
    if (!root && code != 0 && root_code == 0)
      print_line(fmt::format("beamfea: error: rank {} of {}: {}", world.rank(), ranks, message));
    return agreed;
  }
  try {
    // Collective (PETSc's initialisation is): only once every process has its model.
    if (petsc_available()) initialize_petsc_on_all_processes();
    RunOptions opt = run_options(cmd, settings, root, per_process);
    // Rank 0 moves its staged outputs into place only once every process has finished its run
    // (one collective; a process that failed ends the job instead of joining it).
    bool finished_together = false;
    const auto finish_together = [&] {
      world.max_over_ranks(0);
      finished_together = true;
    };
    if (root) opt.before_commit = finish_together;
    opt.on_analysis_error = [&world](const std::string& id, const std::exception& e) {
      if (!dynamic_cast<const ModelError*>(&e)) end_job(world, "analysis '" + id + "': " + e.what(), 1);
    };
    if (root && !cmd.quiet)
      std::cerr << "beamfea: one model on " << ranks << " processes (iterative solves distributed, rank 0 writes)\n";
    state.report = run_document(state.model, state.document, opt);
    if (!finished_together) finish_together();  // the other ranks, and rank 0 when it wrote nothing
    if (root && !cmd.quiet) std::cerr << "beamfea: wrote " << (opt.out_dir / "results.json").string() << "\n";
    return state.report.failed ? 1 : 0;  // the same on every process: the analyses ran alike
  } catch (const std::exception& e) {
    end_job(world, e.what(), exit_code_of(e));
  }
}
#endif

}  // namespace

std::unique_ptr<RunCommand> add_run_command(CLI::App& app) {
  auto cmd = std::make_unique<RunCommand>();
  auto* run = app.add_subcommand("run", "Run the analyses of a model file");
  run->add_option("model", cmd->model_path, "Model file (JSON)")->required();
  run->add_option("--out,-o", cmd->out_dir, "Output folder (created if needed)")->capture_default_str();
  run->add_flag("--no-vtk", cmd->no_vtk, "Write results.json only");
  run->add_flag("--quiet,-q", cmd->quiet, "No progress lines on stderr");
  run->add_option("--analysis,-a", cmd->only, "Run only these analysis ids");
  cmd->app = run;
  return cmd;
}

int run_run_command(const RunCommand& cmd, const app::ProgramSettings& settings) {
  const int launched = launched_ranks();
  if (launched <= 1) return run_alone(cmd, settings);
#ifdef BEAMFEA_HAVE_MPI
  const MpiWorld world(MpiWorld::Threads::Serialized);
  return run_distributed(cmd, settings, world);
#else
  std::cerr << "beamfea: error: started as one of " << launched
            << " MPI processes, but this beamfea was built without MPI (install libopenmpi-dev and rebuild)\n";
  return 2;
#endif
}

}  // namespace beamfea::cli
