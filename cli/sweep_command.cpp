#include "cli/sweep_command.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "app/sweep_runner.hpp"
#include "cli/mpi_world.hpp"
#include "core/errors.hpp"
#include "io/sweep.hpp"
#include "app/openblas.hpp"

#ifdef BEAMFEA_HAVE_MPI
#include <mpi.h>
#endif

namespace beamfea::cli {

namespace {

// ---------------------------------------------------------------------------------------------
// Process-wide matters of a sweep: they belong to the program, never to a library that a Python
// process loads (app/sweep_runner.hpp only sees a stop flag and a progress callback).

// Set by SIGINT/SIGTERM; the sweep loop stops handing out cases when it is.
std::atomic<bool> g_stop{false};

extern "C" void on_stop_signal(int) {
  if (g_stop.load()) _exit(130);  // a second Ctrl-C: stop now (the table is valid CSV already)
  g_stop.store(true);
}

// Ctrl-C and SIGTERM stop the sweep cleanly while it runs; the previous handlers come back after.
class StopOnSignals {
 public:
  StopOnSignals() {
    g_stop = false;
    old_int_ = std::signal(SIGINT, on_stop_signal);
    old_term_ = std::signal(SIGTERM, on_stop_signal);
  }
  ~StopOnSignals() {
    std::signal(SIGINT, old_int_);
    std::signal(SIGTERM, old_term_);
  }
  StopOnSignals(const StopOnSignals&) = delete;
  StopOnSignals& operator=(const StopOnSignals&) = delete;

 private:
  void (*old_int_)(int);
  void (*old_term_)(int);
};

// Cases are the unit of parallelism, one per thread: OpenBLAS's own threads would only
// oversubscribe the cores (and spin in sched_yield between the small factorisations).
void single_threaded_blas() {
  beamfea::app::set_blas_threads(1);
}

// ---------------------------------------------------------------------------------------------
// Progress on stderr: a bar redrawn in place on a terminal, a plain line every few seconds
// otherwise.

enum class ProgressStyle { Bar, Lines, None };

// Redraw period of the bar, and the period of the plain lines (a log file stays short).
constexpr double kBarPeriodS = 0.1;
constexpr double kLinePeriodS = 5.0;

std::string duration_text(double s) {
  if (!(s >= 0.0) || s > 1e7) return "--:--";
  const long t = static_cast<long>(s + 0.5);
  if (t >= 3600) return fmt::format("{}:{:02}:{:02}", t / 3600, (t / 60) % 60, t % 60);
  return fmt::format("{}:{:02}", t / 60, t % 60);
}

class ProgressPrinter {
 public:
  explicit ProgressPrinter(ProgressStyle style) : style_(style) {}

  void operator()(const SweepProgress& p) {
    const auto now = std::chrono::steady_clock::now();
    const double since = std::chrono::duration<double>(now - last_).count();
    const double rate = p.elapsed_s > 0 ? p.done / p.elapsed_s : 0.0;
    const double left = rate > 0 ? (p.total - p.done) / rate : -1.0;
    if (style_ == ProgressStyle::Bar && (p.final ? drew_ : since >= kBarPeriodS)) {
      constexpr int width = 30;
      const int filled = p.total ? static_cast<int>(width * p.done / p.total) : width;
      std::fprintf(stderr, "\r[%s%s] %zu/%zu cases  %zu failed  %.0f cases/s  %s left \033[K",
                   std::string(filled, '#').c_str(), std::string(width - filled, '.').c_str(), p.done, p.total,
                   p.failed, rate, duration_text(left).c_str());
      if (p.final) std::fputc('\n', stderr);
      std::fflush(stderr);
      last_ = now;
      drew_ = true;
    } else if (style_ == ProgressStyle::Lines && (p.final || since >= kLinePeriodS)) {
      std::fprintf(stderr, "beamfea sweep: %zu/%zu cases, %zu failed, %.0f cases/s, %s left\n", p.done, p.total,
                   p.failed, rate, duration_text(left).c_str());
      std::fflush(stderr);
      last_ = now;
    }
  }

 private:
  ProgressStyle style_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
  bool drew_ = false;
};

ProgressStyle progress_style(const SweepCommand& cmd) {
  if (cmd.quiet || cmd.progress == "none") return ProgressStyle::None;
  if (cmd.progress == "bar") return ProgressStyle::Bar;
  if (cmd.progress == "lines") return ProgressStyle::Lines;
  return ::isatty(2) ? ProgressStyle::Bar : ProgressStyle::Lines;
}

// ---------------------------------------------------------------------------------------------
// Processes

#ifdef BEAMFEA_HAVE_MPI
// MPI transport: rank 0's plan broadcast, rows sent to rank 0. Only the main thread calls MPI.
class MpiComm : public SweepComm {
 public:
  MpiComm() {
    // A rank that dies is found by rank 0's heartbeat timeout (app/sweep_runner.hpp), not by an
    // error that aborts the job from inside a receive.
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  }
  ~MpiComm() override {
    if (abandoned_) world_.abort(1);  // a lost rank would never join MPI_Finalize
  }  // then world_ ends PETSc (a case that solved iteratively) and MPI
  MpiComm(const MpiComm&) = delete;
  MpiComm& operator=(const MpiComm&) = delete;

  int rank() const override { return world_.rank(); }
  int size() const override { return world_.size(); }

  void broadcast(std::string& text) override {
    unsigned long long n = text.size();
    MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
    text.resize(n);
    if (n > 0) MPI_Bcast(text.data(), static_cast<int>(n), MPI_CHAR, 0, MPI_COMM_WORLD);
  }

  void send(const std::string& batch, bool last) override {
    MPI_Send(batch.data(), static_cast<int>(batch.size()), MPI_CHAR, 0, last ? kLast : kRows, MPI_COMM_WORLD);
  }

  bool receive(std::string& batch, bool& last, int& from) override {
    int flag = 0;
    MPI_Status st;
    if (MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st) != MPI_SUCCESS || !flag) return false;
    int n = 0;
    MPI_Get_count(&st, MPI_CHAR, &n);
    batch.resize(n);
    if (MPI_Recv(batch.data(), n, MPI_CHAR, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE) != MPI_SUCCESS)
      return false;
    last = st.MPI_TAG == kLast;
    from = st.MPI_SOURCE;
    return true;
  }

  void abandon() override { abandoned_ = true; }

 private:
  static constexpr int kRows = 1, kLast = 2;
  MpiWorld world_{MpiWorld::Threads::MainOnly};  // made first, ended last
  bool abandoned_ = false;
};
#endif

}  // namespace

std::unique_ptr<SweepCommand> add_sweep_command(CLI::App& app) {
  auto cmd = std::make_unique<SweepCommand>();
  auto* s = app.add_subcommand("sweep", "Run many cases of a base model (a grid or a list) into one table DIR/cases.csv");
  s->add_option("sweep", cmd->sweep_path, "Sweep file (JSON, docs/sweep.md)")->required();
  s->add_option("--out,-o", cmd->out_dir, "Output folder (created if needed)")->capture_default_str();
  s->add_option("--jobs,-j", cmd->jobs, "Worker threads per process (0: all cores)")->capture_default_str();
  s->add_flag("--keep", cmd->keep, "Also write each case's results.json and VTK files into DIR/cases/<id>/");
  s->add_flag("--resume", cmd->resume, "Skip the cases already in DIR/cases.csv");
  s->add_option("--progress", cmd->progress, "auto (a bar on a terminal, lines otherwise), bar, lines or none")
      ->check(CLI::IsMember({"auto", "bar", "lines", "none"}))
      ->capture_default_str();
  s->add_flag("--quiet,-q", cmd->quiet, "No progress and no summary on stderr");
  cmd->app = s;
  return cmd;
}

int run_sweep_command(const SweepCommand& cmd) {
  std::unique_ptr<SweepComm> comm;
  const int launched = launched_ranks();
  if (launched > 1) {
#ifdef BEAMFEA_HAVE_MPI
    comm = std::make_unique<MpiComm>();
#else
    std::cerr << "beamfea: error: started as one of " << launched
              << " MPI processes, but this beamfea was built without MPI (install libopenmpi-dev and rebuild)\n";
    return 2;
#endif
  }
  const bool root = !comm || comm->rank() == 0;
  try {
    const Sweep sweep = read_sweep_file(cmd.sweep_path);
    SweepOptions opt;
    opt.out_dir = cmd.out_dir;
    opt.jobs = cmd.jobs;
    opt.ranks_on_host = comm ? ranks_on_this_host(comm->size()) : 1;
    opt.keep = cmd.keep;
    opt.resume = cmd.resume;
    opt.stop = &g_stop;
    const ProgressStyle style = progress_style(cmd);
    if (root && style != ProgressStyle::None) opt.progress = ProgressPrinter(style);
    single_threaded_blas();
    const StopOnSignals signals;
    const SweepSummary summary = run_sweep(sweep, opt, comm.get());
    if (!root) return summary.interrupted ? 130 : 0;
    if (!cmd.quiet) std::cerr << "beamfea sweep: " << summary.report() << "\n";
    // Said even with --quiet: the run is not whole.
    const std::string lost = summary.lost_report();
    for (std::size_t at = 0; at < lost.size();) {
      const std::size_t nl = lost.find('\n', at);
      std::cerr << "beamfea: error: " << lost.substr(at, nl - at) << "\n";
      at = nl + 1;
    }
    if (!summary.lost.empty()) {
      std::cerr.flush();
      comm->abandon();
    }
    return summary.exit_code();
  } catch (const InputError& e) {
    if (root) std::cerr << "beamfea: error: " << cmd.sweep_path << ": " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    if (root) std::cerr << "beamfea: error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace beamfea::cli
