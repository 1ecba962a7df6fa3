// bench_frame_solve's parent process: each size run in a fresh child (the program re-executed with
// --single N, frame_solve_stages.hpp), the children's RESULT lines read back, the best of the
// repetitions kept, and the Markdown tables printed.
#pragma once

#include <fmt/format.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_timing.hpp"
#include "frame_solve_stages.hpp"

namespace beamfea::bench::frame_solve {

using Record = std::map<std::string, std::string>;

// The child's record for one size, with its exit `status` and its ru_maxrss from wait4.
inline Record run_child(const char* self, long size, const Options& o, long& maxrss_kb, int& status) {
  std::vector<std::string> args{self, "--single", std::to_string(size), "--stories", std::to_string(o.stories),
                                "--max-gflop", fmt::format("{}", o.max_gflop), "--max-simplicial-gflop",
                                fmt::format("{}", o.max_simplicial_gflop), "--mem-margin-gb",
                                fmt::format("{}", o.mem_margin_gb), "--library-path-max-s",
                                fmt::format("{}", o.library_path_max_s), "--ordering", o.ordering,
                                "--settle-s", fmt::format("{}", o.settle_s)};
  if (!o.nrelax.empty()) args.insert(args.end(), {"--nrelax", o.nrelax});
  if (!o.zrelax.empty()) args.insert(args.end(), {"--zrelax", o.zrelax});
  int fd[2];
  if (pipe(fd) != 0) throw std::runtime_error("pipe failed");
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    dup2(fd[1], STDOUT_FILENO);
    close(fd[0]);
    close(fd[1]);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv("/proc/self/exe", argv.data());
    std::perror("execv");
    _exit(127);
  }
  close(fd[1]);
  std::string text;
  char buf[4096];
  ssize_t k;
  while ((k = read(fd[0], buf, sizeof buf)) > 0) text.append(buf, static_cast<std::size_t>(k));
  close(fd[0]);
  struct rusage ru {};
  wait4(pid, &status, 0, &ru);
  maxrss_kb = ru.ru_maxrss;
  Record r;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind("RESULT ", 0) != 0) continue;
    std::istringstream words(line.substr(7));
    std::string w;
    while (words >> w)
      if (auto eq = w.find('='); eq != std::string::npos) r[w.substr(0, eq)] = w.substr(eq + 1);
  }
  return r;
}

inline double num(const Record& r, const std::string& k) {
  auto it = r.find(k);
  return it == r.end() ? std::nan("") : std::atof(it->second.c_str());
}
inline bool has(const Record& r, const std::string& k) { return r.count(k) > 0; }
inline std::string spaced(std::string s) {
  std::replace(s.begin(), s.end(), '_', ' ');
  return s;
}

inline std::string str(const Record& r, const std::string& k) {
  auto it = r.find(k);
  return it == r.end() ? "-" : it->second;
}

// Times: ms below 1 s, s above.
inline std::string tm(const Record& r, const std::string& k) {
  if (!has(r, k)) return "-";
  const double t = num(r, k);
  return t < 1.0 ? fmt::format("{:.1f} ms", t * 1e3) : fmt::format("{:.2f} s", t);
}
// Wall time with the process CPU time in parentheses, in the same unit.
inline std::string tmc(const Record& r, const std::string& stage) {
  const std::string k = "t_" + stage, c = "c_" + stage;
  if (!has(r, k)) return "-";
  const double t = num(r, k), u = num(r, c);
  return t < 1.0 ? fmt::format("{:.1f} ({:.1f}) ms", t * 1e3, u * 1e3) : fmt::format("{:.2f} ({:.2f}) s", t, u);
}
inline std::string ratio(double a, double b) { return std::isfinite(a / b) ? fmt::format("{:.2f}", a / b) : "-"; }
inline std::string sci(const Record& r, const std::string& k) {
  return has(r, k) ? fmt::format("{:.1e}", num(r, k)) : "-";
}
inline std::string mb(const Record& r, const std::string& k) {
  return has(r, k) ? fmt::format("{:.0f}", num(r, k) / 1024.0) : "-";
}

// One size over its repetitions: the first run's record with each time the minimum over the runs,
// and "paired", each run's own solve_linear_static / numeric (wall) and their median.
inline Record run_size(const char* self, long size, const Options& o) {
  const int reps = o.repeat > 0 ? o.repeat : (size <= 10000 ? 3 : 1);
  Record best;
  std::vector<double> paired;
  for (int rep = 0; rep < reps; ++rep) {
    long rss = 0;
    int status = 0;
    const auto t0 = Clock::now();
    Record r = run_child(self, size, o, rss, status);
    fmt::print(stderr, "N={} run {}/{}: {:.1f} s, maxrss {} MB, {}\n", size, rep + 1, reps, seconds_since(t0),
               rss / 1024, WIFEXITED(status) ? fmt::format("exit {}", WEXITSTATUS(status))
                                             : fmt::format("signal {}", WTERMSIG(status)));
    r["maxrss_kb"] = std::to_string(rss);
    if (!(WIFEXITED(status) && WEXITSTATUS(status) == 0))
      r["skip"] = WIFSIGNALED(status) ? fmt::format("killed-by-signal-{}", WTERMSIG(status)) : "child-failed";
    r["target"] = std::to_string(size);
    if (has(r, "t_linear_static") && has(r, "t_numeric")) paired.push_back(num(r, "t_linear_static") / num(r, "t_numeric"));
    if (rep == 0) {
      best = r;
      continue;
    }
    for (auto& [k, v] : r)  // keep the minimum of each time over the repetitions
      if ((k.rfind("t_", 0) == 0 || k.rfind("c_", 0) == 0) && has(best, k) && num(r, k) < num(best, k)) best[k] = v;
  }
  if (!paired.empty()) {
    std::string list;
    for (double x : paired) list += fmt::format("{}{:.2f}", list.empty() ? "" : ", ", x);
    best["paired"] = fmt::format("{} (median {:.2f})", list, median(paired));
  }
  return best;
}

inline void print_pipeline_and_factor(const std::vector<Record>& recs, const Options& o) {
  fmt::print("### Pipeline (library path), {} frame\n\n", o.stories > 0 ? fmt::format("{}-storey", o.stories) : "cube");
  fmt::print("| N target | bays nx x ny x nz | elements | free DOFs | nnz(K) | DofMap | elements K_e | assembly 1 (pattern) | "
             "assembly 2 (reuse) | symbolic | numeric | solve | peak after assembly MB | peak MB | rel. residual | "
             "reaction err |\n");
  fmt::print("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& r : recs)
    fmt::print("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", str(r, "target"),
               str(r, "dims"), str(r, "elements"), str(r, "dofs"), str(r, "nnz_K"), tmc(r, "dofmap"),
               tmc(r, "elements"), tmc(r, "asm1"), tmc(r, "asm2"), tmc(r, "symbolic"), tmc(r, "numeric"),
               tmc(r, "solve"), mb(r, "hwm_asm_kb"), mb(r, "hwm_lib_kb"), sci(r, "residual"), sci(r, "reaction_err"));

  fmt::print("\nTimes: wall clock (process CPU time in parentheses), minimum over the repetitions.\n");
  fmt::print("\n### Factor\n\n");
  fmt::print("| free DOFs | ordering | nnz(L) | factor GB | GFlop | numeric GFlop/s | SparseFactor::factorize "
             "(analysis+numeric+scaling+rcond) | SparseFactor's ordering | rcond (scaled) | skipped |\n");
  fmt::print("|---:|---|---:|---:|---:|---:|---:|---|---:|---|\n");
  for (const auto& r : recs)
    fmt::print("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", str(r, "dofs"), str(r, "ordering"), sci(r, "lnz"),
               has(r, "factor_gb") ? fmt::format("{:.2f}", num(r, "factor_gb")) : "-",
               has(r, "gflop") ? fmt::format("{:.1f}", num(r, "gflop")) : "-",
               has(r, "t_numeric") ? fmt::format("{:.1f}", num(r, "gflop") / num(r, "t_numeric")) : "-",
               tm(r, "t_lib_factor"), spaced(str(r, "lib_ordering")), sci(r, "rcond"), str(r, "skip"));
}

inline void print_pipeline_ratio(const std::vector<Record>& recs) {
  fmt::print("\n### The whole linear static analysis against the numeric factorisation\n\n");
  fmt::print("| free DOFs | numeric | solve_linear_static | ratio (wall) | ratio (CPU) | ratio (wall), each run's own | u vs SparseFactor |\n");
  fmt::print("|---:|---:|---:|---:|---:|---|---:|\n");
  for (const auto& r : recs)
    fmt::print("| {} | {} | {} | {} | {} | {} | {} |\n", str(r, "dofs"), tmc(r, "numeric"), tmc(r, "linear_static"),
               ratio(num(r, "t_linear_static"), num(r, "t_numeric")), ratio(num(r, "c_linear_static"), num(r, "c_numeric")),
               has(r, "paired") ? r.at("paired") : "-", sci(r, "linear_static_vs_staged"));
  fmt::print("\nRatios: of the minimum times over the repetitions; \"each run's own\": every repetition's pipeline over\n"
             "its own staged factorisation (the two a few seconds apart in one process), and their median.\n");
}

// `kernels`: the OpenBLAS kernels chosen at start (bench_blas.hpp).
inline void print_baselines(const std::vector<Record>& recs, const std::string& kernels) {
  fmt::print("\n### Baselines (same process)\n\n");
  fmt::print("| free DOFs | assembly 1 (pattern) | of which end() | setFromTriplets | assembly 2 (reuse) | setFromTriplets / reuse (CPU) | assembly 1 / "
             "setFromTriplets (CPU) | CHOLMOD sym+num | SimplicialLDLT sym+num | LDLT / CHOLMOD | nnz(L) LDLT / CHOLMOD | "
             "LDLT residual | whole-run maxrss MB |\n");
  fmt::print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& r : recs) {
    const double chol = num(r, "t_symbolic") + num(r, "t_numeric");
    const double ldlt = num(r, "t_ldlt_symbolic") + num(r, "t_ldlt_numeric");
    Record x{{"chol", fmt::format("{}", chol)}, {"ldlt", fmt::format("{}", ldlt)}};
    fmt::print("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", str(r, "dofs"),
               tmc(r, "asm1"), tmc(r, "asm1_end"), tmc(r, "triplets"), tmc(r, "asm2"), ratio(num(r, "c_triplets"), num(r, "c_asm2")),
               ratio(num(r, "c_asm1"), num(r, "c_triplets")), std::isfinite(chol) ? tm(x, "chol") : "-",
               std::isfinite(ldlt) ? tm(x, "ldlt") : "-", ratio(ldlt, chol), ratio(num(r, "ldlt_nnz"), num(r, "lnz")),
               sci(r, "ldlt_residual"), mb(r, "maxrss_kb"));
  }
  std::string loads;
  for (const auto& r : recs) loads += (loads.empty() ? "" : ", ") + str(r, "target") + ": " + str(r, "load_start");
  fmt::print("\nBLAS: {}, {}. Load average (1 min) at the start of each size: {}.\n",
             recs.empty() ? "-" : str(recs.front(), "blas"), kernels, loads);
}

// The parent: every size of o.sizes in children, then the tables.
inline int run_all(const char* self, const Options& o, const std::string& kernels) {
  std::vector<Record> recs;
  for (long size : o.sizes) recs.push_back(run_size(self, size, o));
  print_pipeline_and_factor(recs, o);
  print_pipeline_ratio(recs);
  print_baselines(recs, kernels);
  return 0;
}

}  // namespace beamfea::bench::frame_solve
