// libFuzzer target over the sweep file: parsing, read_sweep's checks, and for a few
// cases of an accepted sweep (the first, the middle and the last) the case document, one
// bounded run, and the table's header and row; then, for a small sweep (at most kMaxLoopCases
// cases of small models), the program's own sweep loop (app/sweep_runner.hpp, run_sweep: the loop
// `beamfea sweep` runs) into a temporary folder: one or two worker threads, one or two ranks
// (two: a second rank on a thread, linked by an in-process SweepComm), --keep, a stop flag set
// at the first progress report, and --resume over a table cut after some rows (a torn last
// line included). Built with fuzz_model (-DBEAMFEA_BUILD_FUZZERS=ON, clang); how to build and
// run it: scripts/fuzz.sh, docs/testing.md.
//
// A "base" file name is always replaced by tests/fuzz/corpus_sweep/base.json: the fuzzer never
// reads the machine's files (a "base" of /dev/zero would only measure the disk).
//
// The rules, beside "no crash, no sanitizer report, only beamfea's errors":
// - an accepted sweep has cases, each with a case id that can be a folder name (--keep) and one
//   value per parameter column;
// - a case runs in the sweep as it runs alone: run_sweep_case's status is the exit code that
//   `beamfea run` gives for the case's document (ok 0, analysis failed 1, bad input 2);
// - the table stays readable: the header and every row are one line each that splits back into
//   the same cells, and a table's own header gives back its columns (--resume);
// - the loop's table has one row per case, in case order, each with the status that the case's
//   document alone gives, and the summary counts them; an interrupted loop's table holds whole
//   rows of finished cases; a resumed table (after a cut or an interruption) has the rows of an
//   uninterrupted one (wall times aside), and the summary counts the rows it skipped.
#include <unistd.h>

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>

#include "app/sweep_runner.hpp"
#include "fuzz/harness.hpp"
#include "io/sweep.hpp"
#include "io/sweep_table.hpp"

namespace {

using beamfea::fuzz::broken_rule;
using nlohmann::json;

int expected_code(beamfea::SweepCaseResult::Status s) {
  switch (s) {
    case beamfea::SweepCaseResult::Status::Succeeded: return 0;
    case beamfea::SweepCaseResult::Status::AnalysisFailed: return 1;
    case beamfea::SweepCaseResult::Status::BadInput: return 2;
  }
  return -1;
}

void check_line(const std::string& line, const std::vector<std::string>& cells, const std::string& what) {
  if (line.empty() || line.back() != '\n' || line.find('\n') != line.size() - 1)
    broken_rule(what + " is not one line: " + line);
  if (beamfea::csv_split(line.substr(0, line.size() - 1)) != cells)
    broken_rule(what + " does not split back into its cells: " + line);
}

// The exit code that the case's document alone gives, or nullopt when it cannot be compared with
// the sweep's run (bounding changed it, or the model is too big to run here).
std::optional<int> alone_code(const beamfea::Sweep& s, std::size_t i) {
  try {
    const json doc = s.document(i);
    json bounded = doc;
    beamfea::fuzz::bound(bounded);
    const auto outcome = beamfea::fuzz::run_document_case(bounded, s.analyses);
    // run_sweep_case runs the document as it is: compare only when bounding changed nothing and
    // the model was small enough to run.
    if (!(bounded == doc && (outcome.ran || outcome.code == 2))) return std::nullopt;
    return outcome.code;
  } catch (const beamfea::InputError&) {
    return 2;  // the case's changes do not apply: a "bad input" row
  } catch (const std::exception& e) {
    broken_rule(std::string("a case's document threw a non-beamfea exception: ") + e.what());
  }
}

void check_case(const beamfea::Sweep& s, std::size_t i) {
  const std::string id = s.case_id(i);
  if (id.empty() || id == "." || id == ".." || id.find('/') != std::string::npos || id.find('\0') != std::string::npos)
    broken_rule("case id '" + id + "' cannot be a folder name");
  if (s.parameters(i).size() != s.parameter_names.size()) broken_rule("a case without one value per parameter column");

  // The case alone: its document, bounded, checked and run as `beamfea run` would.
  const std::optional<int> alone = alone_code(s, i);
  if (!alone) return;
  const beamfea::SweepCaseResult r = beamfea::run_sweep_case(s, i);
  if (expected_code(r.status) != *alone)
    broken_rule("case " + id + ": the sweep says '" + beamfea::to_string(r.status) + "' (" + r.message +
                "), the same document alone gives exit " + std::to_string(*alone));

  // Its row in a table whose columns it settles.
  const beamfea::SweepColumns columns =
      beamfea::sweep_columns(s, r.status == beamfea::SweepCaseResult::Status::Succeeded ? &r : nullptr);
  const auto header = columns.header(s);
  check_line(beamfea::csv_line(header), header, "the header");
  const std::string row = beamfea::sweep_row(s, i, columns, r);
  if (row.find('\n') != row.size() - 1) broken_rule("a row is not one line: " + row);
  if (beamfea::csv_split(row.substr(0, row.size() - 1)).size() != header.size())
    broken_rule("a row without one cell per column: " + row);
  try {
    if (beamfea::sweep_columns_from_header(s, header, "table").outputs != columns.outputs)
      broken_rule("a table's header gives back other columns (--resume would mix them up)");
  } catch (const beamfea::InputError& e) {
    broken_rule(std::string("a table's own header is not one of its sweep: ") + e.what());
  }
}

// ---------------------------------------------------------------------------------------------
// The program's sweep loop (run_sweep) over a small sweep.

// Sweeps of more cases are only checked case by case (above): each loop runs every case several times.
constexpr std::size_t kMaxLoopCases = 6;

// This process's folder for the loop's tables, removed at exit.
const std::filesystem::path& work_dir() {
  static const std::filesystem::path dir = [] {
    std::string templ = (std::filesystem::temp_directory_path() / "beamfea_fuzz_sweep_XXXXXX").string();
    if (!::mkdtemp(templ.data())) broken_rule("cannot create a temporary folder");
    static const std::filesystem::path made = templ;
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(made, ec);
    });
    return made;
  }();
  return dir;
}

// Two ranks in one process: rank 0 on the fuzzer's thread, rank 1 on another; the plan and the
// row batches pass through memory as they pass through MPI in the program.
struct TwoRanks {
  std::mutex mutex;
  std::condition_variable cv;
  std::optional<std::string> plan;
  std::deque<std::pair<std::string, bool>> batches;
};

class ThreadComm : public beamfea::SweepComm {
 public:
  ThreadComm(TwoRanks& link, int rank) : link_(link), rank_(rank) {}
  int rank() const override { return rank_; }
  int size() const override { return 2; }
  void broadcast(std::string& text) override {
    std::unique_lock lock(link_.mutex);
    if (rank_ == 0) {
      link_.plan = text;
      link_.cv.notify_all();
    } else {
      link_.cv.wait(lock, [&] { return link_.plan.has_value(); });
      text = *link_.plan;
    }
  }
  void send(const std::string& batch, bool last) override {
    std::lock_guard lock(link_.mutex);
    link_.batches.emplace_back(batch, last);
  }
  bool receive(std::string& batch, bool& last, int& from) override {
    std::lock_guard lock(link_.mutex);
    if (link_.batches.empty()) return false;
    batch = std::move(link_.batches.front().first);
    last = link_.batches.front().second;
    from = 1;
    link_.batches.pop_front();
    return true;
  }

 private:
  TwoRanks& link_;
  int rank_;
};

// How one input drives the loop, from a hash of its text (the same input, the same run).
struct LoopVariant {
  int jobs = 1;
  bool two_ranks = false;
  bool keep = false;
  bool interrupt = false;  // the stop flag set at the first progress report
  std::size_t cut = 0;     // --resume over the table cut after this many rows
};
LoopVariant loop_variant(const std::string& text, std::size_t cases) {
  std::size_t h = std::hash<std::string>{}(text);
  auto take = [&](std::size_t n) {
    const std::size_t v = h % n;
    h /= n;
    return v;
  };
  LoopVariant v;
  v.jobs = 1 + static_cast<int>(take(2));
  v.two_ranks = take(4) == 0;
  v.keep = take(4) == 0;
  v.interrupt = take(4) == 0;
  v.cut = take(cases + 1);
  return v;
}

// Runs the loop (on two ranks when asked) and returns rank 0's summary; an exception of either rank
// is thrown here.
beamfea::SweepSummary run_loop(const beamfea::Sweep& s, const beamfea::SweepOptions& opt, bool two_ranks) {
  if (!two_ranks) return beamfea::run_sweep(s, opt);
  TwoRanks link;
  ThreadComm comm0(link, 0), comm1(link, 1);
  beamfea::SweepOptions opt1 = opt;
  opt1.progress = nullptr;  // rank 0 only, as in the program
  std::exception_ptr error1;
  std::thread rank1([&] {
    try {
      beamfea::run_sweep(s, opt1, &comm1);
    } catch (...) {
      error1 = std::current_exception();
    }
  });
  beamfea::SweepSummary summary;
  std::exception_ptr error0;
  try {
    summary = beamfea::run_sweep(s, opt, &comm0);
  } catch (...) {
    error0 = std::current_exception();
  }
  rank1.join();
  if (error0) std::rethrow_exception(error0);
  if (error1) std::rethrow_exception(error1);
  return summary;
}

std::string read_all(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The table's rows without their wall_time_s cell (the one cell that differs between two runs).
// The rows without their times: the case's wall time (the last column) and any analysis's
// `wall_time_s` that the outputs asked for (a re-run case takes another time).
std::vector<std::string> rows_without_time(const beamfea::SweepTable& t) {
  const auto is_time = [&t](std::size_t column) {
    if (column >= t.header.size()) return false;
    const std::string& h = t.header[column];
    return column + 1 == t.header.size() || h == "wall_time_s" || h.ends_with(".wall_time_s");
  };
  std::vector<std::string> rows;
  for (const auto& row : t.rows) {
    const auto cells = beamfea::csv_split(row.substr(0, row.size() - 1));
    std::vector<std::string> kept;
    for (std::size_t c = 0; c < cells.size(); ++c)
      if (!is_time(c)) kept.push_back(cells[c]);
    rows.push_back(beamfea::csv_line(kept));
  }
  return rows;
}

// The table after a loop: whole rows of this sweep, one per finished case, in case order once
// the loop has ended (all: every case), each with the status its document alone gives.
beamfea::SweepTable check_table(const beamfea::Sweep& s, const std::filesystem::path& table,
                                const std::vector<int>& alone, bool all, const std::string& when) {
  const beamfea::SweepTable t = beamfea::read_sweep_table(table);
  if (t.partial_tail) broken_rule(when + ": the table ends in a torn row");
  if (t.header.size() < 4) broken_rule(when + ": the table has no header");
  try {
    beamfea::sweep_columns_from_header(s, t.header, "table");
  } catch (const beamfea::InputError& e) {
    broken_rule(when + ": the loop's table is not one of its sweep: " + e.what());
  }
  if (all && t.rows.size() != s.size())
    broken_rule(when + ": " + std::to_string(t.rows.size()) + " rows for " + std::to_string(s.size()) + " cases");
  std::size_t next = 0;
  for (const auto& row : t.rows) {
    const auto cells = beamfea::csv_split(row.substr(0, row.size() - 1));
    if (cells.size() != t.header.size()) broken_rule(when + ": a row without one cell per column: " + row);
    std::size_t i = next;
    while (i < s.size() && s.case_id(i) != cells[0]) ++i;
    if (i == s.size()) broken_rule(when + ": a row out of case order, twice, or of no case: " + row);
    next = i + 1;
    const std::string& status = cells[cells.size() - 3];
    const int code = status == "ok" ? 0 : status == "analysis failed" ? 1 : status == "bad input" ? 2 : -1;
    if (code != alone[i])
      broken_rule(when + ": case " + cells[0] + " is '" + status + "' in the table, its document alone gives exit " +
                  std::to_string(alone[i]));
  }
  return t;
}

void check_loop(const beamfea::Sweep& s, const std::string& text) {
  const std::size_t n = s.size();
  if (n > kMaxLoopCases) return;
  std::vector<int> alone(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto code = alone_code(s, i);
    if (!code) return;  // a case that cannot run here unbounded
    alone[i] = *code;
  }
  const LoopVariant v = loop_variant(text, n);
  const std::filesystem::path out = work_dir() / "out";
  std::filesystem::remove_all(out);
  const auto table = out / "cases.csv";

  std::atomic<bool> stop{false};
  beamfea::SweepOptions opt;
  opt.out_dir = out;
  opt.jobs = v.jobs;
  opt.keep = v.keep;
  opt.stop = &stop;
  if (v.interrupt) opt.progress = [&](const beamfea::SweepProgress&) { stop = true; };
  beamfea::SweepSummary first;
  try {
    first = run_loop(s, opt, v.two_ranks);
  } catch (const std::exception& e) {
    broken_rule(std::string("the sweep loop threw on an accepted sweep: ") + e.what());
  }
  if (first.cases != n) broken_rule("the summary counts other cases than the sweep's");
  if (!first.interrupted && (first.ran != n || first.ok + first.analysis_failed + first.bad_input != n))
    broken_rule("an uninterrupted loop's summary does not count every case once: " + first.report());
  check_table(s, table, alone, !first.interrupted, "the loop's table");

  // Resumed: after the interruption, or after a cut of a whole table (a torn row after it).
  opt.stop = nullptr;
  opt.progress = nullptr;
  opt.resume = true;
  std::vector<std::string> whole;
  std::size_t kept = 0;
  if (!first.interrupted) {
    const auto t = beamfea::read_sweep_table(table);
    whole = rows_without_time(t);
    kept = v.cut;
    std::string cut = beamfea::csv_line(t.header);
    for (std::size_t k = 0; k < v.cut; ++k) cut += t.rows[k];
    if (v.cut < n) cut += t.rows[v.cut].substr(0, t.rows[v.cut].size() / 2);  // a row torn by a kill
    std::ofstream(table, std::ios::binary | std::ios::trunc) << cut;
  } else {
    kept = beamfea::read_sweep_table(table).rows.size();
  }
  beamfea::SweepSummary resumed;
  try {
    resumed = run_loop(s, opt, v.two_ranks);
  } catch (const std::exception& e) {
    broken_rule(std::string("--resume threw on the loop's own table: ") + e.what());
  }
  if (resumed.interrupted || resumed.skipped != kept || resumed.ran != n - kept)
    broken_rule("the resumed loop's summary does not match the table it resumed: " + resumed.report() + " (" +
                std::to_string(kept) + " rows kept)");
  const auto t = check_table(s, table, alone, true, "the resumed table");
  if (!whole.empty() && rows_without_time(t) != whole)
    broken_rule("the resumed table's rows differ from the uninterrupted one's:\n" + read_all(table));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  json doc;
  try {
    doc = beamfea::parse_json_text(text, "fuzz");
  } catch (const beamfea::InputError&) {
    return 0;
  } catch (const std::exception& e) {
    broken_rule(std::string("parsing threw a non-beamfea exception: ") + e.what());
  }
  if (doc.is_object() && doc.contains("base") && doc["base"].is_string()) doc["base"] = "base.json";
  if (doc.is_object() && doc.contains("model")) beamfea::fuzz::bound(doc["model"]);
  beamfea::Sweep s;
  try {
    s = beamfea::read_sweep(doc, BEAMFEA_FUZZ_SWEEP_DIR);
  } catch (const beamfea::InputError&) {
    return 0;
  } catch (const beamfea::ModelError&) {
    return 0;
  } catch (const std::exception& e) {
    broken_rule(std::string("reading a sweep threw a non-beamfea exception: ") + e.what());
  }
  const std::size_t n = s.size();
  if (n == 0) broken_rule("a sweep without cases was accepted");
  // Three cases at most (the first, the middle, the last): each runs twice, bounded.
  const std::set<std::size_t> picks{0, n / 2, n - 1};
  std::set<std::string> ids;
  for (std::size_t i : picks) {
    if (!ids.insert(s.case_id(i)).second) broken_rule("two cases with the id '" + s.case_id(i) + "'");
    check_case(s, i);
  }
  check_loop(s, text);
  return 0;
}
