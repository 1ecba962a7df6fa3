#include "cli/sweep_command.hpp"

#include <cstdlib>
#include <iostream>

#include "core/errors.hpp"
#include "io/sweep.hpp"

#ifdef BEAMFEA_HAVE_MPI
#include <mpi.h>
#endif

namespace beamfea::cli {

namespace {

// Number of processes the launcher started, from its environment (1 when not under mpirun).
int launched_ranks() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
    if (const char* v = std::getenv(var)) return std::max(1, std::atoi(v));
  return 1;
}

#ifdef BEAMFEA_HAVE_MPI
// MPI transport: rank 0's plan broadcast, rows sent to rank 0. Only the main thread calls MPI.
class MpiComm : public SweepComm {
 public:
  MpiComm() {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  ~MpiComm() override { MPI_Finalize(); }
  MpiComm(const MpiComm&) = delete;
  MpiComm& operator=(const MpiComm&) = delete;

  int rank() const override { return rank_; }
  int size() const override { return size_; }

  void broadcast(std::string& text) override {
    unsigned long long n = text.size();
    MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
    text.resize(n);
    if (n > 0) MPI_Bcast(text.data(), static_cast<int>(n), MPI_CHAR, 0, MPI_COMM_WORLD);
  }

  void send(const std::string& batch, bool last) override {
    MPI_Send(batch.data(), static_cast<int>(batch.size()), MPI_CHAR, 0, last ? kLast : kRows, MPI_COMM_WORLD);
  }

  bool receive(std::string& batch, bool& last) override {
    int flag = 0;
    MPI_Status st;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
    if (!flag) return false;
    int n = 0;
    MPI_Get_count(&st, MPI_CHAR, &n);
    batch.resize(n);
    MPI_Recv(batch.data(), n, MPI_CHAR, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    last = st.MPI_TAG == kLast;
    return true;
  }

 private:
  static constexpr int kRows = 1, kLast = 2;
  int rank_ = 0, size_ = 1;
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
    opt.keep = cmd.keep;
    opt.resume = cmd.resume;
    opt.progress = cmd.quiet                   ? SweepProgress::None
                   : cmd.progress == "bar"     ? SweepProgress::Bar
                   : cmd.progress == "lines"   ? SweepProgress::Lines
                   : cmd.progress == "none"    ? SweepProgress::None
                                               : SweepProgress::Auto;
    const SweepSummary summary = run_sweep(sweep, opt, comm.get());
    if (!root) return summary.interrupted ? 130 : 0;
    if (!cmd.quiet) std::cerr << "beamfea sweep: " << summary.report() << "\n";
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
