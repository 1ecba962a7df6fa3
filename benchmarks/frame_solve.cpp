// bench_frame_solve: timing and peak memory of beamfea's linear static pipeline on a regular
// 3-D space frame, with baselines in the same process.
//
// The frame: nx x ny x nz bays (6 m x 6 m x 3.5 m), a column on every grid point of every
// storey, beams along x and y at every floor, all base nodes fixed in 6 DOF, every other node
// loaded by (1, 0.5, -10) kN. nx = ny = nz by default (a cube: the hardest shape for a direct
// solver, since nested-dissection separators grow as n^2); `--stories S` fixes nz = S instead
// (a building), which makes the fill nearly two-dimensional.
//
// Stages timed, in the order the library runs them (solvers/linear_static.cpp):
//   model      generating the Model (not part of the library; for scale)
//   dofmap     DofMap construction (numbering, constraint elimination: none here)
//   elements   LinearStructure construction (12x12 global stiffness of every beam)
//   asm1       first SystemAssembler pass: triplets, CSC pattern, positions
//   asm2       second pass over the same calls: values written through the stored positions
//   symbolic   CHOLMOD analysis (ordering + supernodal symbolic factorisation)
//   numeric    CHOLMOD supernodal numeric factorisation
//   solve      forward/back substitution for one right-hand side
// The factorisation is that of solvers/sparse_factor.cpp: CholmodSupernodalLLT (Eigen's
// defaults) on the Jacobi-scaled S K S, timed stage by stage. The library's SparseFactor is then
// run too (analysis and factorisation in one call, plus its scaling and condition estimate) where
// the numeric stage took less than `--library-path-max-s`, and its solution is the one checked:
// relative residual |K u - f| / |f| and |sum of base reactions + sum of loads| / |sum of loads|,
// the reactions obtained as the library does (DofMap::constraint_forces).
//
// Baselines in the same process: Eigen's setFromTriplets assembly (direct raw -> free indices,
// valid here since the frame has no constraints) against the pattern-reusing pass; Eigen's
// SimplicialLDLT (AMD ordering) against CHOLMOD, for sizes where CHOLMOD's flop count says it
// is affordable (`--max-simplicial-gflop`).
//
// Peak memory per size: each size runs in a fresh child process (the program re-executes
// itself with --single N); the child reports VmHWM after assembly and after the library path
// (before the baselines), the parent the child's ru_maxrss from wait4 (whole run, baselines
// included).
//
// Usage: bench_frame_solve [--sizes 1000,10000,100000,1000000] [--stories S] [--repeat R]
//                          [--max-gflop G] [--max-simplicial-gflop G] [--mem-margin-gb M]
//                          [--library-path-max-s T] [--ordering default|amd|metis|nesdis|metis+nesdis]
//                          [--settle-s S]  (pause before each of the two compared timings, default 3)
// Output: Markdown tables on stdout, progress on stderr.
#include <fmt/format.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "app/thread_tasks.hpp"
#include "core/assembly.hpp"
#include "core/dof_map.hpp"
#include "core/model.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/sparse_factor.hpp"
#include "solvers/structure.hpp"
#include "bench_blas.hpp"
#include "bench_timing.hpp"
#include "frame_models.hpp"

namespace {

using beamfea::bench::choose_dims;
using beamfea::bench::Dims;
using beamfea::bench::make_frame;

using beamfea::SparseMatrix;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// CPU time of the whole process (all threads), seconds.
double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// Wall-clock and process CPU time of a stage. On a shared machine the CPU time of a
// single-threaded stage is the better measure of its cost; wall time is what a user waits.
struct Stopwatch {
  Clock::time_point wall0 = Clock::now();
  double cpu0 = cpu_seconds();
  double wall() const { return seconds_since(wall0); }
  double cpu() const { return cpu_seconds() - cpu0; }
};

// A field of /proc/self/status or /proc/meminfo, in kB (-1 if absent).
long proc_kb(const char* file, const char* key) {
  std::ifstream in(file);
  std::string line;
  const std::size_t n = std::strlen(key);
  while (std::getline(in, line))
    if (line.compare(0, n, key) == 0 && line.size() > n && line[n] == ':') return std::atol(line.c_str() + n + 1);
  return -1;
}

// The OpenBLAS kernels chosen at start (bench_blas.hpp).
std::string g_kernels;

// The BLAS library mapped into this process (CHOLMOD's supernodal kernels run on it).
std::string blas_in_use() {
  std::ifstream in("/proc/self/maps");
  std::string line;
  while (std::getline(in, line)) {
    const auto slash = line.find('/');
    if (slash == std::string::npos) continue;
    const std::string path = line.substr(slash);
    if (path.find("blas") != std::string::npos) return path;
  }
  return "none";
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  double one = 0.0;
  in >> one;
  return fmt::format("{:.1f}", one);
}


// CHOLMOD's supernodal LLT with access to its statistics (fill, flops, chosen ordering).
class Cholmod : public Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> {
 public:
  cholmod_common& common() { return cholmod(); }
  const cholmod_factor* factor() const { return m_cholmodFactor; }
};

const char* ordering_name(int o) {
  switch (o) {
    case CHOLMOD_NATURAL: return "natural";
    case CHOLMOD_GIVEN: return "given";
    case CHOLMOD_AMD: return "AMD";
    case CHOLMOD_METIS: return "METIS";
    case CHOLMOD_NESDIS: return "NESDIS";
    case CHOLMOD_COLAMD: return "COLAMD";
    case CHOLMOD_POSTORDERED: return "postordered";
  }
  return "?";
}

struct Options {
  std::vector<long> sizes{1000, 10000, 100000, 1000000};
  int stories = 0;
  int repeat = 0;                       // 0: 3 for N <= 1e4, else 1
  double max_gflop = 20000.0;           // skip the numeric factorisation above this
  double max_simplicial_gflop = 60.0;   // run SimplicialLDLT only below this (CHOLMOD's count)
  double mem_margin_gb = 3.0;           // memory left to others when deciding to factorise
  double library_path_max_s = 90.0;     // run SparseFactor too when the numeric stage took less
  std::string ordering = "default";     // staged CHOLMOD's ordering: default (its trials), amd, metis, nesdis
  std::string nrelax, zrelax;           // CHOLMOD's supernodal amalgamation (three values each; empty: its defaults)
  double settle_s = 3.0;                // pause before the staged numeric factorisation and before the pipeline
};

// The pause before each of the two timings compared in "The whole linear static analysis against
// the numeric factorisation" (the staged numeric factorisation, then solve_linear_static), so that
// both start from the same state of the machine, the state a fresh `beamfea run` meets:
// - OpenBLAS's workers asleep: after a threaded factorisation they spin (sched_yield) for a while
//   before they sleep, and on two cores they took the core of the pipeline's second task;
// - the memory freed before it handed back to the host where the kernel reports free pages
//   (page_reporting, about 2 s after it is freed): each timing then faults its factor in from
//   memory as cold as a new process gets. Before (session 13) only the pipeline waited, a second.
void settle(const Options& o) {
  if (o.settle_s > 0.0) std::this_thread::sleep_for(std::chrono::duration<double>(o.settle_s));
}

// CHOLMOD's relaxed supernodal amalgamation (cholmod_common nrelax[3], zrelax[3]): columns are
// merged into a supernode while the supernode has fewer than nrelax[k] columns or the fraction of
// explicit zeros stays under zrelax[k]; larger supernodes mean larger BLAS-3 calls.
void set_relax(cholmod_common& c, const std::string& nrelax, const std::string& zrelax) {
  const auto three = [](const std::string& s) {
    std::vector<double> v;
    std::size_t start = 0;
    while (start <= s.size()) {
      const std::size_t end = std::min(s.find(',', start), s.size());
      v.push_back(std::atof(s.substr(start, end - start).c_str()));
      start = end + 1;
    }
    if (v.size() != 3) throw std::runtime_error("--nrelax/--zrelax: three comma-separated values");
    return v;
  };
  if (!nrelax.empty()) {
    const auto v = three(nrelax);
    for (int k = 0; k < 3; ++k) c.nrelax[k] = static_cast<std::size_t>(v[k]);
  }
  if (!zrelax.empty()) {
    const auto v = three(zrelax);
    for (int k = 0; k < 3; ++k) c.zrelax[k] = v[k];
  }
}

// Restricts CHOLMOD to one ordering ("default" leaves its own trials: AMD, then METIS when AMD's
// fill looks poor, keeping the better).
void set_ordering(cholmod_common& c, const std::string& name) {
  if (name == "default") return;
  c.nmethods = 1;
  c.method[0].ordering = name == "amd" ? CHOLMOD_AMD : name == "metis" ? CHOLMOD_METIS : CHOLMOD_NESDIS;
  c.postorder = 1;
  if (name == "metis+nesdis") {  // both, CHOLMOD keeping the one of smaller nnz(L)
    c.nmethods = 2;
    c.method[0].ordering = CHOLMOD_METIS;
    c.method[1].ordering = CHOLMOD_NESDIS;
  }
}

double num_or(const std::map<std::string, std::string>& r, const std::string& k) {
  auto it = r.find(k);
  return it == r.end() ? 0.0 : std::atof(it->second.c_str());
}

// ---- child: one size -------------------------------------------------------------------------

int run_single(long target, const Options& o) {
  using namespace beamfea;
  std::map<std::string, std::string> out;
  auto put = [&](const std::string& k, auto v) { out[k] = fmt::format("{}", v); };
  auto stage = [&](const std::string& name, const Stopwatch& w) {
    put("t_" + name, w.wall());
    put("c_" + name, w.cpu());
  };
  auto emit = [&] {
    std::string line = "RESULT";
    for (const auto& [k, v] : out) line += " " + k + "=" + v;
    std::puts(line.c_str());
    std::fflush(stdout);
  };

  put("load_start", load_average());
  const Dims d = choose_dims(target, o.stories);
  put("dims", fmt::format("{}x{}x{}", d.nx, d.ny, d.nz));
  put("nodes", d.nodes());
  put("elements", d.elements());

  Stopwatch t0;
  const Model model = make_frame(d);
  stage("model", t0);

  t0 = Stopwatch();
  const DofMap map(model);
  stage("dofmap", t0);
  const int n = map.free_size();
  put("dofs", n);

  t0 = Stopwatch();
  const LinearStructure structure(model);
  stage("elements", t0);

  SystemAssembler assembler(map);
  t0 = Stopwatch();
  assembler.begin();
  structure.assemble(map, assembler);
  Stopwatch t_end;
  assembler.end();
  stage("asm1", t0);
  stage("asm1_end", t_end);  // of which: building the CSC pattern and positions from the triplets
  t0 = Stopwatch();
  assembler.begin();
  structure.assemble(map, assembler);
  assembler.end();
  stage("asm2", t0);
  const SparseMatrix& K = assembler.K_ff();
  put("nnz_K", K.nonZeros());
  put("hwm_asm_kb", proc_kb("/proc/self/status", "VmHWM"));

  const Eigen::VectorXd up = map.prescribed_values();
  const Eigen::VectorXd f_raw = external_force(model, map);
  Eigen::VectorXd f = map.reduce(f_raw);
  if (map.prescribed_size() > 0) f -= assembler.K_fp() * up;

  // CHOLMOD, stage by stage, on the matrix SparseFactor factorises.
  Eigen::VectorXd s(n);
  for (int i = 0; i < n; ++i) s[i] = 1.0 / std::sqrt(K.coeff(i, i));
  const SparseMatrix A = scaled(K, s);
  double fl = 0.0;
  bool factorised = false;
  Eigen::VectorXd uf;  // free displacements from the staged CHOLMOD factorisation
  {
    Cholmod llt;
    set_ordering(llt.common(), o.ordering);
    set_relax(llt.common(), o.nrelax, o.zrelax);
    t0 = Stopwatch();
    llt.analyzePattern(A);
    stage("symbolic", t0);
    cholmod_common& c = llt.common();
    fl = c.fl;
    put("lnz", c.lnz);
    put("gflop", c.fl / 1e9);
    put("ordering", ordering_name(c.method[c.selected].ordering));
    if (llt.info() != Eigen::Success || llt.factor() == nullptr) {
      // CHOLMOD's int interface (Eigen's SparseMatrix<double, 0, int>) stops at 2^31 entries in L.
      put("skip", fmt::format("cholmod-analysis-failed-status-{}", c.status));
      put("hwm_lib_kb", proc_kb("/proc/self/status", "VmHWM"));
      put("blas", blas_in_use());
      put("load_end", load_average());
      emit();
      return 0;
    }
    const double factor_gb = (llt.factor()->is_super ? double(llt.factor()->xsize) : c.lnz) * 8.0 / 1e9;
    put("factor_gb", factor_gb);
    const double avail_gb = proc_kb("/proc/meminfo", "MemAvailable") / 1e6;
    if (factor_gb > avail_gb - o.mem_margin_gb) {
      put("skip", fmt::format("factor-needs-{:.1f}GB-of-{:.1f}GB-available", factor_gb, avail_gb));
    } else if (fl / 1e9 > o.max_gflop) {
      put("skip", fmt::format("{:.0f}-GFlop-over-limit-{:.0f}", fl / 1e9, o.max_gflop));
    } else {
      settle(o);
      t0 = Stopwatch();
      llt.factorize(A);
      stage("numeric", t0);
      if (llt.info() != Eigen::Success) {
        put("skip", "cholmod-factorisation-failed");
      } else {
        const Eigen::VectorXd sf = s.cwiseProduct(f);
        t0 = Stopwatch();
        const Eigen::VectorXd y = llt.solve(sf);
        stage("solve", t0);
        uf = s.cwiseProduct(y);
        put("cholmod_peak_gb", c.memory_usage / 1e9);
        factorised = true;
      }
    }
  }
  if (!factorised) {
    put("hwm_lib_kb", proc_kb("/proc/self/status", "VmHWM"));
    put("blas", blas_in_use());
    put("load_end", load_average());
    emit();
    return 0;
  }

  // The library path: SparseFactor (analysis + scaling + factorisation + rcond), whose
  // solution replaces the staged one; skipped where the numeric factorisation is long.
  if (num_or(out, "t_numeric") <= o.library_path_max_s) {
    {
      // Its own scope, so that its factor is freed before the pipeline runs: held on (0.73 GB at
      // 97,344 DOFs), it made the pipeline 6.0-7.4 s against 4.8-5.0 s freed, in a process fuller
      // than `beamfea run` ever is (session 14).
      SparseFactor factor;
      t0 = Stopwatch();
      const FactorStatus fs = factor.factorize(K);
      stage("lib_factor", t0);
      put("lib_status", to_string(fs));
      std::string ordering = factor.ordering();  // the record is words: spaces travel as '_'
      std::replace(ordering.begin(), ordering.end(), ' ', '_');
      put("lib_ordering", ordering);
      put("rcond", factor.rcond());
      const Eigen::VectorXd ul = factor.solve(f);
      put("lib_vs_staged", (ul - uf).norm() / uf.norm());
      uf = ul;
    }
    // The whole library analysis as `beamfea run` calls it (DofMap, elements, assembly, scaling,
    // analysis, factorisation, solve, reactions, end forces), against the numeric stage above,
    // both after the same pause (settle). With the program's threads: the element matrices beside
    // the ordering of the pattern.
    LinearStaticOptions lso;
    lso.parallel = app::thread_tasks();
    settle(o);
    t0 = Stopwatch();
    const LinearStaticResult lin = solve_linear_static(model, lso);
    stage("linear_static", t0);
    put("linear_static_vs_staged", (lin.u - map.expand(uf, up)).norm() / map.expand(uf, up).norm());
  }
  // Checks, with the reactions as solve_linear_static computes them.
  {
    put("residual", (K * uf - f).norm() / f.norm());
    const Eigen::VectorXd u = map.expand(uf, up);
    const Eigen::VectorXd r = structure.internal_force(map, u) - f_raw;
    const auto cf = map.constraint_forces(r);
    Vec3 reaction = Vec3::Zero(), load = Vec3::Zero();
    for (int p = 0; p < map.prescribed_size(); ++p) {
      const auto& dof = map.prescribed()[p].dof;
      if (dof.owner == DofRef::Owner::Node && dof.comp < 3) reaction[dof.comp] += cf.prescribed[p];
    }
    for (const auto& l : model.default_case.nodal) load += l.force;
    put("reaction_err", (reaction + load).norm() / load.norm());
    put("max_u", u.cwiseAbs().maxCoeff());
  }
  put("hwm_lib_kb", proc_kb("/proc/self/status", "VmHWM"));

  // Baseline 1: Eigen setFromTriplets assembly (raw -> free directly: no constraints here).
  {
    t0 = Stopwatch();
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(model.elements.size() * 144);
    for (int e = 0; e < static_cast<int>(model.elements.size()); ++e) {
      const auto dofs = structure.element_dofs(map, e);
      std::array<int, 12> fi{};
      for (int a = 0; a < 12; ++a) fi[a] = map.free_index(dofs[a]);
      const auto& Ke = structure.beam(e)->stiffness();
      for (int b = 0; b < 12; ++b) {
        if (fi[b] < 0) continue;
        for (int a = 0; a < 12; ++a)
          if (fi[a] >= 0) t.emplace_back(fi[a], fi[b], Ke(a, b));
      }
    }
    SparseMatrix Kt(n, n);
    Kt.setFromTriplets(t.begin(), t.end());
    stage("triplets", t0);
    put("triplets_diff", (Kt - K).norm() / K.norm());
  }

  // Baseline 2: Eigen SimplicialLDLT (AMD) on the same scaled matrix.
  if (fl / 1e9 <= o.max_simplicial_gflop) {
    Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> ldlt;
    t0 = Stopwatch();
    ldlt.analyzePattern(A);
    stage("ldlt_symbolic", t0);
    t0 = Stopwatch();
    ldlt.factorize(A);
    stage("ldlt_numeric", t0);
    put("ldlt_nnz", ldlt.matrixL().nestedExpression().nonZeros());
    t0 = Stopwatch();
    const Eigen::VectorXd u = s.cwiseProduct(Eigen::VectorXd(ldlt.solve(s.cwiseProduct(f))));
    stage("ldlt_solve", t0);
    put("ldlt_residual", (K * u - f).norm() / f.norm());
  }
  put("hwm_all_kb", proc_kb("/proc/self/status", "VmHWM"));
  put("blas", blas_in_use());
  put("load_end", load_average());
  emit();
  return 0;
}

// ---- parent: run each size in a child, print tables ------------------------------------------

using Record = std::map<std::string, std::string>;

Record run_child(const char* self, long size, const Options& o, long& maxrss_kb, int& status) {
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

double num(const Record& r, const std::string& k) {
  auto it = r.find(k);
  return it == r.end() ? std::nan("") : std::atof(it->second.c_str());
}
bool has(const Record& r, const std::string& k) { return r.count(k) > 0; }
std::string spaced(std::string s) {
  std::replace(s.begin(), s.end(), '_', ' ');
  return s;
}

std::string str(const Record& r, const std::string& k) {
  auto it = r.find(k);
  return it == r.end() ? "-" : it->second;
}

// Times: ms below 1 s, s above.
std::string tm(const Record& r, const std::string& k) {
  if (!has(r, k)) return "-";
  const double t = num(r, k);
  return t < 1.0 ? fmt::format("{:.1f} ms", t * 1e3) : fmt::format("{:.2f} s", t);
}
// Wall time with the process CPU time in parentheses, in the same unit.
std::string tmc(const Record& r, const std::string& stage) {
  const std::string k = "t_" + stage, c = "c_" + stage;
  if (!has(r, k)) return "-";
  const double t = num(r, k), u = num(r, c);
  return t < 1.0 ? fmt::format("{:.1f} ({:.1f}) ms", t * 1e3, u * 1e3) : fmt::format("{:.2f} ({:.2f}) s", t, u);
}
std::string ratio(double a, double b) { return std::isfinite(a / b) ? fmt::format("{:.2f}", a / b) : "-"; }
std::string sci(const Record& r, const std::string& k) { return has(r, k) ? fmt::format("{:.1e}", num(r, k)) : "-"; }
std::string mb(const Record& r, const std::string& k) {
  return has(r, k) ? fmt::format("{:.0f}", num(r, k) / 1024.0) : "-";
}

int run_all(const char* self, const Options& o) {
  std::vector<Record> recs;
  for (long size : o.sizes) {
    const int reps = o.repeat > 0 ? o.repeat : (size <= 10000 ? 3 : 1);
    Record best;
    std::vector<double> paired;  // each repetition's own solve_linear_static / numeric (wall)
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
      best["paired"] = fmt::format("{} (median {:.2f})", list, beamfea::bench::median(paired));
    }
    recs.push_back(best);
  }

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

  fmt::print("\n### The whole linear static analysis against the numeric factorisation\n\n");
  fmt::print("| free DOFs | numeric | solve_linear_static | ratio (wall) | ratio (CPU) | ratio (wall), each run's own | u vs SparseFactor |\n");
  fmt::print("|---:|---:|---:|---:|---:|---|---:|\n");
  for (const auto& r : recs)
    fmt::print("| {} | {} | {} | {} | {} | {} | {} |\n", str(r, "dofs"), tmc(r, "numeric"), tmc(r, "linear_static"),
               ratio(num(r, "t_linear_static"), num(r, "t_numeric")), ratio(num(r, "c_linear_static"), num(r, "c_numeric")),
               has(r, "paired") ? r.at("paired") : "-", sci(r, "linear_static_vs_staged"));
  fmt::print("\nRatios: of the minimum times over the repetitions; \"each run's own\": every repetition's pipeline over\n"
             "its own staged factorisation (the two a few seconds apart in one process), and their median.\n");

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
  fmt::print("\nBLAS: {}, {}. Load average (1 min) at the start of each size: {}.\n",
             recs.empty() ? "-" : str(recs.front(), "blas"), g_kernels, [&] {
               std::string l;
               for (const auto& r : recs) l += (l.empty() ? "" : ", ") + str(r, "target") + ": " + str(r, "load_start");
               return l;
             }());
  return 0;
}

std::vector<long> parse_sizes(const std::string& s) {
  std::vector<long> v;
  std::istringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) v.push_back(static_cast<long>(std::atof(item.c_str())));
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  g_kernels = beamfea::bench::choose_libraries_as_the_program();  // as `beamfea` runs
  Options o;
  long single = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        fmt::print(stderr, "{} needs a value\n", a);
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--single") single = static_cast<long>(std::atof(next().c_str()));
    else if (a == "--sizes") o.sizes = parse_sizes(next());
    else if (a == "--stories") o.stories = std::atoi(next().c_str());
    else if (a == "--repeat") o.repeat = std::atoi(next().c_str());
    else if (a == "--max-gflop") o.max_gflop = std::atof(next().c_str());
    else if (a == "--max-simplicial-gflop") o.max_simplicial_gflop = std::atof(next().c_str());
    else if (a == "--mem-margin-gb") o.mem_margin_gb = std::atof(next().c_str());
    else if (a == "--library-path-max-s") o.library_path_max_s = std::atof(next().c_str());
    else if (a == "--settle-s") o.settle_s = std::atof(next().c_str());
    else if (a == "--ordering") {
      o.ordering = next();
      if (o.ordering != "default" && o.ordering != "amd" && o.ordering != "metis" && o.ordering != "nesdis" &&
          o.ordering != "metis+nesdis") {
        fmt::print(stderr, "--ordering: default, amd, metis, nesdis or metis+nesdis\n");
        return 2;
      }
    }
    else if (a == "--nrelax") o.nrelax = next();
    else if (a == "--zrelax") o.zrelax = next();
    else {
      fmt::print(stderr,
                 "usage: {} [--nrelax a,b,c] [--zrelax x,y,z] [--sizes N1,N2,...] [--stories S] [--repeat R] [--max-gflop G] "
                 "[--max-simplicial-gflop G] [--mem-margin-gb M] [--library-path-max-s T] [--ordering O] [--settle-s S] [--single N]\n",
                 argv[0]);
      return a == "--help" || a == "-h" ? 0 : 2;
    }
  }
  try {
    return single > 0 ? run_single(single, o) : run_all(argv[0], o);
  } catch (const std::exception& e) {
    fmt::print(stderr, "bench_frame_solve: {}\n", e.what());
    return 1;
  }
}
