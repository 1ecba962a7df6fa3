#include "io/sweep.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>
#include <unordered_map>

#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/json_util.hpp"
#include "io/model_reader.hpp"
#include "io/run.hpp"

namespace beamfea {

using json = nlohmann::json;
using json_in::child;

namespace {

// Array indices in output paths have at most this many digits (no array is that long; more would
// overflow the conversion).
constexpr std::size_t kMaxIndexDigits = 9;


// ---------------------------------------------------------------------------------------------
// Cells and rows

std::string sanitize(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

template <class J>
std::string cell_text(const J& v) {
  switch (v.type()) {
    case J::value_t::null: return "";
    case J::value_t::boolean: return v.template get<bool>() ? "true" : "false";
    case J::value_t::string: return sanitize(v.template get<std::string>());
    case J::value_t::number_integer: return std::to_string(v.template get<std::int64_t>());
    case J::value_t::number_unsigned: return std::to_string(v.template get<std::uint64_t>());
    case J::value_t::number_float: return fmt::format("{}", v.template get<double>());  // shortest round trip
    default: return v.dump();
  }
}

void flatten(const ojson& v, const std::string& name, std::vector<std::pair<std::string, std::string>>& out) {
  if (v.is_array()) {
    for (std::size_t i = 0; i < v.size(); ++i) flatten(v[i], name + "[" + std::to_string(i) + "]", out);
  } else if (v.is_object()) {
    for (const auto& [k, x] : v.items()) flatten(x, name + "." + k, out);
  } else {
    out.emplace_back(name, cell_text(v));
  }
}

const ojson* find_path(const ojson& root, const SweepOutput& o) {
  const ojson* v = &root;
  for (const auto& t : o.path) {
    if (t.index >= 0 || (v->is_array() && !t.key.empty() &&
                         t.key.find_first_not_of("0123456789") == std::string::npos)) {
      if (t.index < 0 && t.key.size() > kMaxIndexDigits) return nullptr;  // beyond any array
      const std::size_t i = t.index >= 0 ? static_cast<std::size_t>(t.index) : std::stoul(t.key);
      if (!v->is_array() || i >= v->size()) return nullptr;
      v = &(*v)[i];
    } else {
      if (!v->is_object()) return nullptr;
      auto it = v->find(t.key);
      if (it == v->end()) return nullptr;
      v = &*it;
    }
  }
  return v;
}

// The table's columns: case, parameters, each output's flattened columns, status, message, time.
struct Columns {
  std::vector<std::vector<std::string>> outputs;
  std::vector<std::string> header(const Sweep& s) const {
    std::vector<std::string> h{"case"};
    h.insert(h.end(), s.parameter_names.begin(), s.parameter_names.end());
    for (const auto& o : outputs) h.insert(h.end(), o.begin(), o.end());
    h.insert(h.end(), {"status", "message", "wall_time_s"});
    return h;
  }
};

std::string join_row(const std::vector<std::string>& cells) {
  std::string line;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i) line += ',';
    line += csv_field(cells[i]);
  }
  line += '\n';
  return line;
}

std::string format_row(const Sweep& s, std::size_t index, const Columns& cols, const SweepCaseResult& r) {
  std::vector<std::string> cells{s.case_id(index)};
  for (const auto& p : s.parameters(index)) cells.push_back(p.is_null() ? "" : cell_text(p));
  for (std::size_t o = 0; o < cols.outputs.size(); ++o) {
    const auto& names = cols.outputs[o];
    const auto& got = r.outputs[o];
    bool same = got.size() == names.size();
    for (std::size_t k = 0; same && k < names.size(); ++k) same = got[k].first == names[k];
    if (same) {
      for (const auto& g : got) cells.push_back(g.second);
      continue;
    }
    std::unordered_map<std::string, const std::string*> byname;
    for (const auto& g : got) byname.emplace(g.first, &g.second);
    for (const auto& n : names) {
      auto it = byname.find(n);
      cells.push_back(it == byname.end() ? "" : *it->second);
    }
  }
  cells.push_back(to_string(r.status));
  cells.push_back(sanitize(r.message));
  cells.push_back(fmt::format("{:.6f}", r.wall_time_s));
  return join_row(cells);
}

// ---------------------------------------------------------------------------------------------
// Process-wide matters of a run, each undone on exit.

std::atomic<bool> g_stop{false};

extern "C" void on_stop_signal(int) {
  if (g_stop.load()) _exit(130);  // a second Ctrl-C: stop now (the table is valid CSV already)
  g_stop.store(true);
}

class SignalGuard {
 public:
  SignalGuard() {
    g_stop = false;
    old_int_ = std::signal(SIGINT, on_stop_signal);
    old_term_ = std::signal(SIGTERM, on_stop_signal);
  }
  ~SignalGuard() {
    std::signal(SIGINT, old_int_);
    std::signal(SIGTERM, old_term_);
  }

 private:
  void (*old_int_)(int);
  void (*old_term_)(int);
};

// The model reader warns on std::cerr; the base model's warnings were shown once when the sweep
// was read, so the cases' identical warnings are silenced while they run. (Progress goes to
// stderr through stdio, not std::cerr.)
class CerrSilencer {
 public:
  CerrSilencer() : old_(std::cerr.rdbuf(nullptr)) {}
  ~CerrSilencer() { std::cerr.rdbuf(old_); }

 private:
  std::streambuf* old_;
};

// Cases are the unit of parallelism, one per thread: OpenBLAS's own threads would only
// oversubscribe the cores (and spin in sched_yield between the small factorisations).
void single_threaded_blas() {
  using SetThreads = void (*)(int);
  if (auto f = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) f(1);
}

void write_all(int fd, const std::string& text, const std::filesystem::path& path) {
  const char* p = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw Error("error writing '" + path.string() + "'");
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string duration_text(double s) {
  if (!(s >= 0.0) || s > 1e7) return "--:--";
  const long t = static_cast<long>(s + 0.5);
  if (t >= 3600) return fmt::format("{}:{:02}:{:02}", t / 3600, (t / 60) % 60, t % 60);
  return fmt::format("{}:{:02}", t / 60, t % 60);
}

// Index of a case id; throws when the id is not one of the sweep's.
class CaseIndex {
 public:
  explicit CaseIndex(const Sweep& s) : sweep_(s) {
    if (s.grid.empty())
      for (std::size_t i = 0; i < s.list.size(); ++i) ids_.emplace(s.list[i].id, i);
  }
  bool find(const std::string& id, std::size_t& index) const {
    if (!sweep_.grid.empty()) {
      if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos || id.size() > 18) return false;
      index = std::stoull(id);
      return index < sweep_.size();
    }
    auto it = ids_.find(id);
    if (it == ids_.end()) return false;
    index = it->second;
    return true;
  }

 private:
  const Sweep& sweep_;
  std::unordered_map<std::string, std::size_t> ids_;
};

// The table as read back: header and complete rows (a trailing line without '\n' is dropped).
struct Table {
  std::vector<std::string> header;
  std::vector<std::string> rows;  // each with its '\n'
  bool partial_tail = false;
};

Table read_table(const std::filesystem::path& path) {
  Table t;
  const std::string text = read_text(path);
  std::size_t pos = 0;
  bool first = true;
  while (pos < text.size()) {
    const auto nl = text.find('\n', pos);
    if (nl == std::string::npos) {
      t.partial_tail = true;
      break;
    }
    std::string line = text.substr(pos, nl - pos + 1);
    pos = nl + 1;
    if (first) {
      line.pop_back();
      t.header = csv_split(line);
      first = false;
    } else if (line.size() > 1) {
      t.rows.push_back(std::move(line));
    }
  }
  return t;
}

std::string first_field(const std::string& row) {
  std::string line = row;
  if (!line.empty() && line.back() == '\n') line.pop_back();
  const auto f = csv_split(line);
  return f.empty() ? "" : f[0];
}

// Columns of an existing table, matched to this sweep; throws when they differ.
Columns columns_from_header(const Sweep& s, const std::vector<std::string>& h, const std::string& table) {
  const std::size_t P = s.parameter_names.size();
  auto differ = [&](const std::string& why) {
    return InputError("", "--resume: " + table + " is not a table of this sweep (" + why + "); remove it or use another --out");
  };
  if (h.size() < 4 + P || h[0] != "case" || h[h.size() - 3] != "status" || h[h.size() - 2] != "message" ||
      h.back() != "wall_time_s")
    throw differ("unexpected columns");
  for (std::size_t i = 0; i < P; ++i)
    if (h[1 + i] != s.parameter_names[i]) throw differ("parameter column '" + h[1 + i] + "'");
  Columns c;
  std::size_t k = 1 + P;
  const std::size_t end = h.size() - 3;
  for (const auto& o : s.outputs) {
    std::vector<std::string> mine;
    while (k < end && (h[k] == o.name || h[k].rfind(o.name + "[", 0) == 0 || h[k].rfind(o.name + ".", 0) == 0))
      mine.push_back(h[k++]);
    if (mine.empty()) throw differ("no column for output '" + o.name + "'");
    c.outputs.push_back(std::move(mine));
  }
  if (k != end) throw differ("column '" + h[k] + "' is not an output of this sweep");
  return c;
}

// What rank 0 decides before the cases run: the columns and the cases already in the table.
struct Plan {
  Columns columns;
  std::vector<std::size_t> done;  // in the table already: resumed rows and the probe's rows
  std::size_t probed = 0;         // of which run now by the probe
  std::string error;
};

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

constexpr std::size_t kProbeLimit = 64;

}  // namespace

// ---------------------------------------------------------------------------------------------

const char* to_string(SweepCaseResult::Status s) {
  switch (s) {
    case SweepCaseResult::Status::Ok: return "ok";
    case SweepCaseResult::Status::AnalysisFailed: return "analysis failed";
    case SweepCaseResult::Status::BadInput: return "bad input";
  }
  return "?";
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  q += '"';
  return q;
}

std::vector<std::string> csv_split(const std::string& line) {
  std::vector<std::string> out;
  std::string f;
  bool quoted = false, in_quotes = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (in_quotes) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        f += '"';
        ++i;
      } else if (c == '"') {
        in_quotes = false;
      } else {
        f += c;
      }
    } else if (c == '"' && f.empty() && !quoted) {
      in_quotes = quoted = true;
    } else if (c == ',') {
      out.push_back(std::move(f));
      f.clear();
      quoted = false;
    } else if (c != '\r') {
      f += c;
    }
  }
  out.push_back(std::move(f));
  return out;
}


SweepCaseResult run_sweep_case(const Sweep& sweep, std::size_t index, const std::filesystem::path& keep_dir) {
  const auto t0 = std::chrono::steady_clock::now();
  SweepCaseResult r;
  r.outputs.resize(sweep.outputs.size());
  try {
    const json doc = sweep.document(index);
    const Model model = load_and_check(doc);
    RunOptions opt;
    opt.out_dir = keep_dir;
    opt.write_vtk = !keep_dir.empty();
    opt.only = sweep.analyses;
    const RunReport report = run_document(model, doc, opt);
    std::string missing;
    for (std::size_t o = 0; o < sweep.outputs.size(); ++o) {
      if (const ojson* v = find_path(report.results, sweep.outputs[o])) flatten(*v, sweep.outputs[o].name, r.outputs[o]);
      else missing += (missing.empty() ? "" : ", ") + sweep.outputs[o].name;
    }
    if (report.failed) {
      r.status = SweepCaseResult::Status::AnalysisFailed;
      for (const auto& [id, a] : report.results["analyses"].items()) {
        if (!a.is_object() || !a.contains("status") || a["status"] == "ok") continue;
        const std::string m = a.contains("message") && a["message"].is_string() ? a["message"].get<std::string>()
                                                                                : a["status"].dump();
        r.message += (r.message.empty() ? "" : "; ") + id + ": " + m;
      }
      if (r.message.empty()) r.message = "an analysis failed";
    } else if (!missing.empty()) {
      r.message = "not in the results: " + missing;
    }
  } catch (const InputError& e) {
    r.status = SweepCaseResult::Status::BadInput;
    r.message = e.what();
  } catch (const ModelError& e) {
    r.status = SweepCaseResult::Status::BadInput;
    r.message = e.what();
  } catch (const std::exception& e) {
    r.status = SweepCaseResult::Status::AnalysisFailed;
    r.message = e.what();
  }
  r.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

void SweepOptions::validate() const {
  if (out_dir.empty()) throw InputError("", "sweep: the output folder must not be empty");
  if (jobs < 0) throw InputError("", "sweep: --jobs must be at least 1 (or 0 for all cores)");
  if (!(line_interval_s > 0.0)) throw InputError("", "sweep: the progress line interval must be positive");
}

std::string SweepSummary::report() const {
  return fmt::format("{} cases ({} run now, {} already in the table): {} ok, {} analysis failed, {} bad input; {:.2f} s{}{}; table {}",
                     cases, ran, skipped, ok, analysis_failed, bad_input, wall_time_s,
                     processes > 1 ? fmt::format(" on {} processes", processes) : std::string(),
                     interrupted ? " (interrupted: the table holds the finished cases)" : "", table.string());
}

int SweepSummary::exit_code() const {
  if (interrupted) return 130;
  return analysis_failed + bad_input > 0 ? 1 : 0;
}

SweepSummary run_sweep(const Sweep& sweep, const SweepOptions& options, SweepComm* comm) {
  options.validate();
  const auto t_start = std::chrono::steady_clock::now();
  const int rank = comm ? comm->rank() : 0, ranks = comm ? comm->size() : 1;
  const bool root = rank == 0;
  const std::size_t total = sweep.size();
  const auto table = options.out_dir / "cases.csv";
  const CaseIndex case_index(sweep);
  auto keep_dir = [&](std::size_t i) {
    return options.keep ? options.out_dir / "cases" / sweep.case_id(i) : std::filesystem::path();
  };
  SignalGuard signals;
  CerrSilencer quiet_cerr;

  // Rank 0 settles the columns and the cases already done, and starts the table.
  Plan plan;
  if (root) {
    try {
      std::filesystem::create_directories(options.out_dir);
      std::vector<char> done(total, 0);
      bool have_columns = false;
      if (options.resume && std::filesystem::exists(table)) {
        Table t = read_table(table);
        if (!t.header.empty()) {
          plan.columns = columns_from_header(sweep, t.header, table.string());
          have_columns = true;
          for (const auto& row : t.rows) {
            std::size_t i;
            if (!case_index.find(first_field(row), i))
              throw InputError("", "--resume: " + table.string() + " has a row for case '" + first_field(row) +
                                       "', which is not in this sweep");
            done[i] = 1;
          }
          if (t.partial_tail) {  // cannot happen with whole-row writes; repair anyway
            std::string text = join_row(t.header);
            for (const auto& row : t.rows) text += row;
            write_text_atomic(table, text);
          }
        }
      }
      if (!have_columns) {
        // The columns of each output are those of the first case that succeeds (arrays are
        // flattened to name[i][j]); the probe's cases are rows of the table like any other.
        std::vector<std::pair<std::size_t, SweepCaseResult>> probe;
        const SweepCaseResult* ok = nullptr;
        for (std::size_t i = 0; i < total && probe.size() < kProbeLimit && !g_stop; ++i) {
          if (done[i]) continue;
          probe.emplace_back(i, run_sweep_case(sweep, i, keep_dir(i)));
          if (probe.back().second.status == SweepCaseResult::Status::Ok) {
            ok = &probe.back().second;
            break;
          }
        }
        plan.columns.outputs.resize(sweep.outputs.size());
        for (std::size_t o = 0; o < sweep.outputs.size(); ++o) {
          if (ok && !ok->outputs[o].empty())
            for (const auto& kv : ok->outputs[o]) plan.columns.outputs[o].push_back(kv.first);
          else
            plan.columns.outputs[o].push_back(sweep.outputs[o].name);
        }
        std::string text = join_row(plan.columns.header(sweep));
        for (const auto& [i, r] : probe) {
          text += format_row(sweep, i, plan.columns, r);
          done[i] = 1;
        }
        plan.probed = probe.size();
        write_text_atomic(table, text);
      }
      for (std::size_t i = 0; i < total; ++i)
        if (done[i]) plan.done.push_back(i);
    } catch (const std::exception& e) {
      plan.error = e.what();
    }
  }
  if (ranks > 1) {
    std::string text = root ? plan_to_json(plan).dump() : std::string();
    comm->broadcast(text);
    if (!root) plan = plan_from_json(json::parse(text));
  }
  if (!plan.error.empty()) throw InputError("", plan.error);

  // This rank's share: every ranks-th case not yet done.
  std::vector<std::size_t> pending;
  {
    std::vector<char> done(total, 0);
    for (auto i : plan.done) done[i] = 1;
    for (std::size_t i = 0; i < total; ++i)
      if (!done[i] && static_cast<int>(i % ranks) == rank) pending.push_back(i);
  }
  const std::size_t todo_all = total - plan.done.size();

  int jobs = options.jobs;
  if (jobs == 0) {
    jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    if (ranks > 1) {
      int local = ranks;
      if (const char* l = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE")) local = std::max(1, std::atoi(l));
      jobs = std::max(1, jobs / local);
    }
  }
  jobs = static_cast<int>(std::max<std::size_t>(1, std::min<std::size_t>(jobs, pending.size())));
  single_threaded_blas();

  // Workers run cases and hand whole rows to this thread, the only one that writes or sends.
  std::mutex mutex;
  std::condition_variable cv;
  std::string batch;
  std::size_t batch_rows = 0, batch_failed = 0;
  int finished_workers = 0;
  std::atomic<std::size_t> next{0};
  std::vector<std::thread> workers;
  for (int w = 0; w < jobs; ++w) {
    workers.emplace_back([&] {
      for (;;) {
        if (g_stop) break;
        const std::size_t k = next++;
        if (k >= pending.size()) break;
        const std::size_t i = pending[k];
        const SweepCaseResult r = run_sweep_case(sweep, i, keep_dir(i));
        std::string row = format_row(sweep, i, plan.columns, r);
        {
          std::lock_guard lock(mutex);
          batch += row;
          ++batch_rows;
          if (r.status != SweepCaseResult::Status::Ok) ++batch_failed;
        }
        cv.notify_one();
      }
      std::lock_guard lock(mutex);
      ++finished_workers;
      cv.notify_one();
    });
  }

  int fd = -1;
  if (root) {
    fd = ::open(table.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
    if (fd < 0) {
      g_stop = true;
      for (auto& t : workers) t.join();
      throw Error("cannot append to '" + table.string() + "'");
    }
  }
  SweepProgress mode = options.progress;
  if (mode == SweepProgress::Auto) mode = ::isatty(2) ? SweepProgress::Bar : SweepProgress::Lines;
  if (!root) mode = SweepProgress::None;
  std::size_t done_now = 0, failed_now = 0;
  int ranks_finished = 0;
  const auto t_cases = std::chrono::steady_clock::now();
  auto last_draw = t_cases;
  bool drew_bar = false;
  auto draw = [&](bool final) {
    const auto now = std::chrono::steady_clock::now();
    const double elapsed = std::chrono::duration<double>(now - t_cases).count();
    const double since = std::chrono::duration<double>(now - last_draw).count();
    const double rate = elapsed > 0 ? done_now / elapsed : 0.0;
    const double left = rate > 0 ? (todo_all - done_now) / rate : -1.0;
    if (mode == SweepProgress::Bar && (final || since >= 0.1)) {
      constexpr int width = 30;
      const int filled = todo_all ? static_cast<int>(width * done_now / todo_all) : width;
      std::fprintf(stderr, "\r[%s%s] %zu/%zu cases  %zu failed  %.0f cases/s  %s left \033[K",
                   std::string(filled, '#').c_str(), std::string(width - filled, '.').c_str(), done_now, todo_all,
                   failed_now, rate, duration_text(left).c_str());
      if (final) std::fputc('\n', stderr);
      std::fflush(stderr);
      last_draw = now;
      drew_bar = true;
    } else if (mode == SweepProgress::Lines && (final || since >= options.line_interval_s)) {
      std::fprintf(stderr, "beamfea sweep: %zu/%zu cases, %zu failed, %.0f cases/s, %s left\n", done_now, todo_all,
                   failed_now, rate, duration_text(left).c_str());
      std::fflush(stderr);
      last_draw = now;
    }
  };

  bool sent_last = false;
  for (;;) {
    std::string mine;
    std::size_t rows = 0, failed = 0;
    bool workers_done;
    {
      std::unique_lock lock(mutex);
      cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return !batch.empty() || finished_workers == jobs; });
      mine.swap(batch);
      rows = batch_rows;
      failed = batch_failed;
      batch_rows = batch_failed = 0;
      workers_done = finished_workers == jobs;
    }
    if (root) {
      if (!mine.empty()) write_all(fd, mine, table);
      done_now += rows;
      failed_now += failed;
      std::string remote;
      bool last = false;
      while (comm && ranks > 1 && comm->receive(remote, last)) {
        const auto nl = remote.find('\n');
        std::size_t r = 0, f = 0;
        std::sscanf(remote.c_str(), "%zu %zu", &r, &f);
        if (nl + 1 < remote.size()) write_all(fd, remote.substr(nl + 1), table);
        done_now += r;
        failed_now += f;
        if (last) ++ranks_finished;
      }
      draw(false);
      if (workers_done && ranks_finished == ranks - 1) break;
    } else {
      if (!mine.empty() || workers_done) {
        comm->send(fmt::format("{} {}\n", rows, failed) + mine, workers_done);
        sent_last = workers_done;
      }
      if (sent_last) break;
    }
  }
  for (auto& t : workers) t.join();
  if (drew_bar || mode == SweepProgress::Lines) draw(true);

  SweepSummary summary;
  summary.cases = total;
  summary.skipped = plan.done.size() - plan.probed;
  summary.ran = done_now + plan.probed;
  summary.interrupted = g_stop;
  summary.processes = ranks;
  summary.table = table;
  if (root) {
    ::close(fd);
    // Sort by case order (one row per case, the last written wins) and replace atomically.
    Table t = read_table(table);
    std::vector<std::pair<std::size_t, std::string>> rows;
    std::map<std::size_t, std::size_t> where;
    const std::size_t status_col = t.header.size() - 3;
    for (auto& row : t.rows) {
      std::size_t i;
      if (!case_index.find(first_field(row), i)) continue;
      auto [it, fresh] = where.emplace(i, rows.size());
      if (fresh) rows.emplace_back(i, std::move(row));
      else rows[it->second].second = std::move(row);
    }
    std::sort(rows.begin(), rows.end());
    std::string text = join_row(t.header);
    for (const auto& [i, row] : rows) {
      text += row;
      std::string line = row;
      line.pop_back();
      const auto f = csv_split(line);
      const std::string status = f.size() > status_col ? f[status_col] : "";
      if (status == "ok") ++summary.ok;
      else if (status == "bad input") ++summary.bad_input;
      else ++summary.analysis_failed;
    }
    write_text_atomic(table, text);
  }
  summary.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  return summary;
}

}  // namespace beamfea
