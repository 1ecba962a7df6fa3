#include "app/sweep_runner.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

#include "app/openmp.hpp"
#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/sweep_table.hpp"

namespace beamfea {

using json = nlohmann::json;

namespace {

// The columns of a new table come from the first case that ends ok; at most this many cases are
// run one after the other to find it (they are rows of the table like any other).
constexpr std::size_t kProbeLimit = 64;

// How long the collecting thread waits for rows before it looks at the other ranks and reports
// progress.
constexpr auto kCollectPeriod = std::chrono::milliseconds(50);
// Inline cases (one worker) hand their rows to the table once this many bytes have gathered, if
// that comes before kCollectPeriod: the rows' buffer stays small and is reused (a buffer of 50 ms
// of a small model's rows is megabytes, new pages each time it grows).
constexpr std::size_t kInlineRowBytes = 64 * 1024;
// A rank other than 0 sends at least this often (an empty batch when it has no rows): rank 0 tells a
// live rank from a lost one by it (SweepOptions::rank_timeout_s).
constexpr auto kHeartbeat = std::chrono::milliseconds(200);
// Once the stop flag is set, a rank silent this long is lost (a live one sends every kHeartbeat).
constexpr double kStoppedRankSilence_s = 0.5;
// Case ids listed per lost rank in the one-line report (the count says how many more).
constexpr std::size_t kLostCasesListed = 20;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// What rank 0 decides before the cases run: the columns and the cases already in the table.
struct Plan {
  SweepColumns columns;
  std::vector<std::size_t> done;  // in the table already: resumed rows and the probe's rows
  std::size_t probed = 0;         // of which run now by the probe
  SweepTableCounts probe_counts;  // the probe's rows by status (rank 0's own: not broadcast)
  std::string error;
};

void count_status(SweepTableCounts& c, SweepCaseResult::Status s) {
  switch (s) {
    case SweepCaseResult::Status::Succeeded: ++c.ok; break;
    case SweepCaseResult::Status::AnalysisFailed: ++c.analysis_failed; break;
    case SweepCaseResult::Status::BadInput: ++c.bad_input; break;
  }
}

json plan_to_json(const Plan& p) {
  return json{{"columns", p.columns.outputs}, {"done", p.done}, {"probed", p.probed}, {"error", p.error}};
}
Plan plan_from_json(const json& j) {
  Plan p;
  p.columns.outputs = j.at("columns").get<std::vector<std::vector<std::string>>>();
  p.done = j.at("done").get<std::vector<std::size_t>>();
  p.probed = j.at("probed").get<std::size_t>();
  p.error = j.at("error").get<std::string>();
  return p;
}

bool stop_requested(const SweepOptions& o) { return o.stop && o.stop->load(); }

std::filesystem::path keep_dir(const Sweep& s, const SweepOptions& o, std::size_t i) {
  return o.keep ? o.out_dir / "cases" / s.case_id(i) : std::filesystem::path();
}

// Rank 0: reads the table to resume, or starts a new one whose columns are those of the first
// case that ends ok (the probe). Errors are returned in the plan, to be broadcast.
// `workspace`: the calling thread's, for the probe's cases (and then for the inline cases).
Plan make_plan(const Sweep& sweep, const SweepOptions& options, const std::filesystem::path& table,
               SweepWorkspace& workspace) {
  Plan plan;
  try {
    std::filesystem::create_directories(options.out_dir);
    SweepResume resumed;
    if (options.resume) resumed = resume_sweep_table(sweep, table);
    std::vector<char> done = resumed.found ? resumed.done : std::vector<char>(sweep.size(), 0);
    if (resumed.found) {
      plan.columns = resumed.columns;
    } else {
      std::vector<std::pair<std::size_t, SweepCaseResult>> probe;
      const SweepCaseResult* ok = nullptr;
      for (std::size_t i = 0; i < sweep.size() && probe.size() < kProbeLimit && !stop_requested(options); ++i) {
        if (done[i]) continue;
        run_sweep_case(sweep, i, keep_dir(sweep, options, i), workspace, probe.emplace_back(i, SweepCaseResult()).second);
        if (probe.back().second.status == SweepCaseResult::Status::Succeeded) {
          ok = &probe.back().second;
          break;
        }
      }
      plan.columns = sweep_columns(sweep, ok);
      std::string text = csv_line(plan.columns.header(sweep));
      for (const auto& [i, r] : probe) {
        text += sweep_row(sweep, i, plan.columns, r);
        count_status(plan.probe_counts, r.status);
        done[i] = 1;
      }
      plan.probed = probe.size();
      write_text_atomic(table, text);
    }
    for (std::size_t i = 0; i < sweep.size(); ++i)
      if (done[i]) plan.done.push_back(i);
  } catch (const std::exception& e) {
    plan.error = e.what();
  }
  return plan;
}

// This rank's share of the cases not yet done: every ranks-th case.
std::vector<std::size_t> share(std::size_t total, const Plan& plan, int rank, int ranks) {
  std::vector<char> done(total, 0);
  for (auto i : plan.done) done[i] = 1;
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < total; ++i)
    if (!done[i] && static_cast<int>(i % ranks) == rank) mine.push_back(i);
  return mine;
}

int worker_count(const SweepOptions& options, int ranks, std::size_t cases) {
  int jobs = options.jobs;
  if (jobs == 0) {
    jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    if (ranks > 1) jobs = std::max(1, jobs / std::max(1, options.ranks_on_host));
  }
  return static_cast<int>(std::max<std::size_t>(1, std::min<std::size_t>(jobs, cases)));
}

// Worker threads run the cases and hand whole rows to the collecting thread (the caller's, the
// only one that writes or sends). With one worker on one process there is no thread at all: the
// collecting thread runs the cases itself, inline, in take() (no hand-off, no wake-ups per case).
class WorkerPool {
 public:
  // `workspace`: the calling thread's, for the inline cases.
  WorkerPool(const Sweep& sweep, const SweepOptions& options, const SweepColumns& columns,
             const std::vector<std::size_t>& pending, int jobs, bool run_inline, SweepWorkspace& workspace)
      : sweep_(sweep), options_(options), columns_(columns), pending_(pending), jobs_(run_inline ? 0 : jobs),
        inline_workspace_(workspace) {
    for (int w = 0; w < jobs_; ++w)
      threads_.emplace_back([this] {
        app::apply_library_openmp_to_this_thread();  // the program's choice, per thread (app/openmp.hpp)
        SweepWorkspace workspace(sweep_);  // this worker's, reused case after case
        SweepCaseResult result;            // likewise
        for (;;) {
          if (abort_ || stop_requested(options_)) break;
          const std::size_t k = next_++;
          if (k >= pending_.size()) break;
          Batch one;
          run_one(pending_[k], one, workspace, result);
          {
            std::lock_guard lock(mutex_);
            batch_.rows += one.rows;
            batch_.count += one.count;
            batch_.failed += one.failed;
            batch_.bad_input += one.bad_input;
          }
          cv_.notify_one();
        }
        std::lock_guard lock(mutex_);
        ++finished_;
        cv_.notify_one();
      });
  }
  ~WorkerPool() {
    abort_ = true;
    join();
  }
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  struct Batch {
    std::string rows;
    std::size_t count = 0, failed = 0;  // failed: not ok
    std::size_t bad_input = 0;          // of which bad input
    bool all_done = false;  // every worker has ended: this is the last batch
  };
  // Waits up to `period` for rows (inline: runs cases for up to `period`, or until kInlineRowBytes
  // of rows); hands over those finished so far in `into`, whose rows string is cleared and refilled
  // (its capacity kept, and swapped with the workers' buffer: no allocation per batch).
  void take(std::chrono::milliseconds period, Batch& into) {
    into.rows.clear();
    into.count = into.failed = into.bad_input = 0;
    if (jobs_ == 0) {
      const auto t0 = std::chrono::steady_clock::now();
      while (next_ < pending_.size() && !stop_requested(options_) && into.rows.size() < kInlineRowBytes &&
             std::chrono::steady_clock::now() - t0 < period)
        run_one(pending_[next_++], into, inline_workspace_, inline_result_);
      into.all_done = next_ >= pending_.size() || stop_requested(options_);
      return;
    }
    std::unique_lock lock(mutex_);
    cv_.wait_for(lock, period, [&] { return !batch_.rows.empty() || finished_ == jobs_; });
    into.rows.swap(batch_.rows);
    std::swap(into.count, batch_.count);
    std::swap(into.failed, batch_.failed);
    std::swap(into.bad_input, batch_.bad_input);
    into.all_done = finished_ == jobs_;
  }
  void join() {
    for (auto& t : threads_)
      if (t.joinable()) t.join();
  }

 private:
  // `workspace` and `r`: the calling thread's, reused case after case.
  void run_one(std::size_t i, Batch& into, SweepWorkspace& workspace, SweepCaseResult& r) const {
    run_sweep_case(sweep_, i, keep_dir(sweep_, options_, i), workspace, r);
    append_sweep_row(into.rows, sweep_, i, columns_, r);
    ++into.count;
    if (r.status != SweepCaseResult::Status::Succeeded) ++into.failed;
    if (r.status == SweepCaseResult::Status::BadInput) ++into.bad_input;
  }

  const Sweep& sweep_;
  const SweepOptions& options_;
  const SweepColumns& columns_;
  const std::vector<std::size_t>& pending_;
  int jobs_;  // worker threads; 0: the cases run inline in take()
  SweepWorkspace& inline_workspace_;  // the inline cases' workspace (the caller's)
  SweepCaseResult inline_result_;     // and their result, reused
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable cv_;
  Batch batch_;
  int finished_ = 0;
  std::atomic<std::size_t> next_{0};
  std::atomic<bool> abort_{false};
};

// A batch of rows between ranks: "<count> <failed> <bad input>\n" then the rows.
std::string encode_batch(const WorkerPool::Batch& b) {
  return fmt::format("{} {} {}\n", b.count, b.failed, b.bad_input) + b.rows;
}
WorkerPool::Batch decode_batch(const std::string& text) {
  WorkerPool::Batch b;
  const auto nl = text.find('\n');
  std::sscanf(text.c_str(), "%zu %zu %zu", &b.count, &b.failed, &b.bad_input);
  if (nl != std::string::npos && nl + 1 < text.size()) b.rows = text.substr(nl + 1);
  return b;
}

}  // namespace

void SweepOptions::validate() const {
  if (out_dir.empty()) throw InputError("", "sweep: the output folder must not be empty");
  if (!(rank_timeout_s > 0.0)) throw InputError("", "sweep: the rank timeout must be positive");
  if (jobs < 0) throw InputError("", "sweep: --jobs must be at least 1 (or 0 for all cores)");
  if (ranks_on_host < 1) throw InputError("", "sweep: the number of processes on this host must be at least 1");
}

std::string SweepSummary::report() const {
  return fmt::format("{} cases ({} run now, {} already in the table): {} ok, {} analysis failed, {} bad input; {:.2f} s{}{}; table {}",
                     cases, ran, skipped, ok, analysis_failed, bad_input, wall_time_s,
                     processes > 1 ? fmt::format(" on {} processes", processes) : std::string(),
                     interrupted ? " (interrupted: the table holds the finished cases)" : "", table.string());
}

std::string SweepSummary::lost_report() const {
  std::string text;
  for (const auto& l : lost) {
    std::string ids;
    for (std::size_t k = 0; k < l.cases.size() && k < kLostCasesListed; ++k) ids += (k ? ", " : "") + l.cases[k];
    if (l.cases.size() > kLostCasesListed) ids += fmt::format(" and {} more", l.cases.size() - kLostCasesListed);
    text += fmt::format("rank {} stopped answering (it died or its host did); ", l.rank) +
            (l.cases.empty() ? std::string("every case it held is in the table\n")
                             : fmt::format("{} case(s) it held are not in the table: {} (--resume runs them)\n",
                                           l.cases.size(), ids));
  }
  return text;
}

int SweepSummary::exit_code() const {
  if (interrupted) return 130;
  return analysis_failed + bad_input > 0 || !lost.empty() ? 1 : 0;
}

SweepSummary run_sweep(const Sweep& sweep, const SweepOptions& options, SweepComm* comm) {
  options.validate();
  const auto t_start = std::chrono::steady_clock::now();
  const int rank = comm ? comm->rank() : 0, ranks = comm ? comm->size() : 1;
  const bool root = rank == 0;
  const auto table = options.out_dir / "cases.csv";

  // Rank 0 settles the columns and the cases already done, and starts the table.
  // The calling thread's case workspace: the probe's cases, then the inline cases, reuse it.
  SweepWorkspace workspace(sweep);
  Plan plan;
  if (root) plan = make_plan(sweep, options, table, workspace);
  if (ranks > 1) {
    std::string text = root ? plan_to_json(plan).dump() : std::string();
    comm->broadcast(text);
    if (!root) plan = plan_from_json(json::parse(text));
  }
  if (!plan.error.empty()) throw InputError("", plan.error);

  const std::vector<std::size_t> pending = share(sweep.size(), plan, rank, ranks);
  SweepProgress progress;
  progress.total = sweep.size() - plan.done.size();
  // Opened before the workers start: a table that cannot be appended to ends the sweep first.
  std::unique_ptr<SweepTableAppender> appender;
  if (root) appender = std::make_unique<SweepTableAppender>(table);

  const int workers = worker_count(options, ranks, pending.size());
  const bool run_inline = workers == 1 && ranks == 1;
  // Inline on a new table (no rows resumed), the table is written in case order, one row per case:
  // the probe's cases first, then the others as they come. Its statuses are then counted here, as
  // the rows are written, and it needs no sorting pass (finish_sweep_table reads it back whole).
  const bool table_in_order = root && run_inline && plan.done.size() == plan.probed;
  SweepTableCounts written = plan.probe_counts;
  WorkerPool pool(sweep, options, plan.columns, pending, workers, run_inline, workspace);
  const auto t_cases = std::chrono::steady_clock::now();
  // Rank 0: per rank, whether its last batch came, and when it was last heard from.
  std::vector<char> rank_ended(static_cast<std::size_t>(ranks), 0), rank_lost(static_cast<std::size_t>(ranks), 0);
  rank_ended[0] = 1;
  std::vector<std::chrono::steady_clock::time_point> heard(static_cast<std::size_t>(ranks), t_cases);
  int ranks_finished = 0;  // ended or lost
  auto last_sent = t_cases;
  WorkerPool::Batch mine;
  for (;;) {
    pool.take(kCollectPeriod, mine);
    if (!root) {
      const auto now = std::chrono::steady_clock::now();
      if (!mine.rows.empty() || mine.all_done || now - last_sent >= kHeartbeat) {
        comm->send(encode_batch(mine), mine.all_done);
        last_sent = now;
      }
      if (mine.all_done) break;
      continue;
    }
    auto add = [&](const WorkerPool::Batch& b) {
      if (!b.rows.empty()) appender->append(b.rows);
      progress.done += b.count;
      progress.failed += b.failed;
      written.ok += b.count - b.failed;
      written.bad_input += b.bad_input;
      written.analysis_failed += b.failed - b.bad_input;
    };
    add(mine);
    std::string remote;
    bool last = false;
    int from = 0;
    while (ranks > 1 && comm->receive(remote, last, from)) {
      if (from <= 0 || from >= ranks || rank_ended[from] || rank_lost[from]) continue;  // a lost rank's late rows
      add(decode_batch(remote));
      heard[from] = std::chrono::steady_clock::now();
      if (last) {
        rank_ended[from] = 1;
        ++ranks_finished;
      }
    }
    // Ranks silent too long are lost: the table is finished without them.
    const double silence_limit = stop_requested(options) ? kStoppedRankSilence_s : options.rank_timeout_s;
    for (int k = 1; k < ranks; ++k)
      if (!rank_ended[k] && !rank_lost[k] && seconds_since(heard[k]) > silence_limit) {
        rank_lost[k] = 1;
        ++ranks_finished;
      }
    progress.elapsed_s = seconds_since(t_cases);
    if (options.progress) options.progress(progress);
    if (mine.all_done && ranks_finished == ranks - 1) break;
  }
  pool.join();

  SweepSummary summary;
  summary.cases = sweep.size();
  summary.skipped = plan.done.size() - plan.probed;
  summary.ran = progress.done + plan.probed;
  summary.interrupted = stop_requested(options);
  summary.processes = ranks;
  summary.table = table;
  if (root) {
    appender.reset();
    progress.elapsed_s = seconds_since(t_cases);
    progress.final = true;
    if (options.progress) options.progress(progress);
    const SweepTableCounts counts = table_in_order ? written : finish_sweep_table(sweep, table);
    summary.ok = counts.ok;
    summary.analysis_failed = counts.analysis_failed;
    summary.bad_input = counts.bad_input;
    if (options.keep) write_case_series(sweep, options.out_dir);
    if (std::find(rank_lost.begin(), rank_lost.end(), 1) != rank_lost.end()) {
      const SweepResume in_table = resume_sweep_table(sweep, table);
      for (int k = 1; k < ranks; ++k) {
        if (!rank_lost[k]) continue;
        SweepSummary::LostRank l{k, {}};
        for (const std::size_t i : share(sweep.size(), plan, k, ranks))
          if (!in_table.done[i]) l.cases.push_back(sweep.case_id(i));
        summary.lost.push_back(std::move(l));
      }
    }
  }
  summary.wall_time_s = seconds_since(t_start);
  return summary;
}

}  // namespace beamfea
