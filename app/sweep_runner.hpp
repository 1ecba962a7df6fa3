#pragma once
// The loop of a sweep (docs/sweep.md): runs the cases of a Sweep on worker threads, shares them
// among the processes of a multi-process run, and writes the one table DIR/cases.csv. It is the
// program's layer (io <- app <- cli): io reads the sweep file, runs one case and writes the
// table; this loop composes them. Nothing here touches the process: no signal handlers, no
// environment variables, no BLAS settings, no terminal output. The caller stops it with a flag
// and sees its progress through a callback (cli/sweep_command.cpp ties them to Ctrl-C and to
// the progress bar).
#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "io/sweep.hpp"

namespace beamfea {

// Transport between the processes of a multi-process sweep (MPI lives in the program, so that
// this library does not depend on it). Rank 0 writes the table; the others send it rows.
class SweepComm {
 public:
  virtual ~SweepComm() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  // Rank 0's text to every rank.
  virtual void broadcast(std::string& text) = 0;
  // Not rank 0: sends a batch of rows to rank 0; `last` marks this rank's final batch.
  virtual void send(const std::string& batch, bool last) = 0;
  // Rank 0: receives one pending batch if there is one (does not block); `from`: its rank.
  virtual bool receive(std::string& batch, bool& last, int& from) = 0;
  // Rank 0, after a run that lost ranks (SweepSummary::lost): ends the transport without waiting
  // for them (MPI: the job is aborted rather than finalized).
  virtual void abandon() {}
};

// Where the cases stand, for a progress display. Counts are of the cases to run now (all
// ranks), not of those already in the table or run to settle the columns.
struct SweepProgress {
  std::size_t done = 0;
  std::size_t total = 0;
  std::size_t failed = 0;    // done, and not "ok"
  double elapsed_s = 0.0;    // since the cases started
  bool final = false;        // the last call, after every worker has ended
};

struct SweepOptions {
  std::filesystem::path out_dir = "out";
  int jobs = 0;              // worker threads (0: all cores, divided among ranks_on_host)
  int ranks_on_host = 1;     // processes of this sweep on this host (with jobs = 0 and several ranks)
  bool keep = false;         // per-case results.json and VTK in DIR/cases/<id>/
  bool resume = false;       // skip the cases already in DIR/cases.csv
  // Set (from any thread, or a signal handler) to stop handing out cases: the running ones
  // finish and are written, the table is sorted, the summary says interrupted. May be null.
  const std::atomic<bool>* stop = nullptr;
  // Called on rank 0 only, on the calling thread, while the cases run (each time rows reach the
  // table: every few tens of milliseconds at most, more often when a single worker's rows fill
  // their buffer first) and once with final = true at the end. May be empty.
  std::function<void(const SweepProgress&)> progress;
  // Several ranks: every rank sends rank 0 a message at least every few hundred milliseconds while
  // it runs (rows, or nothing but that it is alive). A rank silent this long is lost (it died, or
  // its host did): rank 0 stops waiting for it, finishes the table with the other ranks' rows and
  // names it and the cases it held that are not in the table (SweepSummary::lost). Once the stop
  // flag is set, a rank silent for half a second is lost (OpenMPI's mpirun, when one rank dies,
  // sends the others SIGTERM and a second later SIGKILL).
  double rank_timeout_s = 30.0;
  void validate() const;
};

struct SweepSummary {
  std::size_t cases = 0;     // in the sweep
  std::size_t skipped = 0;   // already in the table (--resume)
  std::size_t ran = 0;       // run now (all ranks)
  std::size_t ok = 0, analysis_failed = 0, bad_input = 0;  // over the whole table
  int processes = 1;         // ranks
  bool interrupted = false;  // the stop flag was set: the table holds the finished cases
  // Ranks that stopped answering (rank 0's summary): each with the ids of its cases that are not
  // in the table (--resume runs them).
  struct LostRank {
    int rank = 0;
    std::vector<std::string> cases;
  };
  std::vector<LostRank> lost;
  double wall_time_s = 0.0;
  std::filesystem::path table;
  std::string report() const;  // one line
  // What became of the lost ranks (empty when none): one line each.
  std::string lost_report() const;
  // 0 every case ok; 1 some case failed (see the table) or a rank was lost; 130 interrupted.
  int exit_code() const;
};

// Runs the sweep (all ranks of `comm` call it; null: one process). Throws InputError for a
// bad sweep or a table that --resume cannot continue.
SweepSummary run_sweep(const Sweep& sweep, const SweepOptions& options, SweepComm* comm = nullptr);

}  // namespace beamfea
