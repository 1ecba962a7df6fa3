// bench_frame_solve's child process: one size of the frame, timed stage by stage (the stages are
// listed in frame_solve.cpp's opening comment), its figures printed as one "RESULT key=value ..."
// line on stdout for the parent (frame_solve_report.hpp).
#pragma once

#include <fmt/format.h>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <stdexcept>
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
#include "bench_timing.hpp"
#include "frame_models.hpp"

namespace beamfea::bench::frame_solve {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The wall-clock and process CPU time of a stage (bench_timing.hpp).
using beamfea::bench::Stopwatch;

// A field of /proc/self/status or /proc/meminfo, in kB (-1 if absent).
inline long proc_kb(const char* file, const char* key) {
  std::ifstream in(file);
  std::string line;
  const std::size_t n = std::strlen(key);
  while (std::getline(in, line))
    if (line.compare(0, n, key) == 0 && line.size() > n && line[n] == ':') return std::atol(line.c_str() + n + 1);
  return -1;
}

// The BLAS library mapped into this process (CHOLMOD's supernodal kernels run on it).
inline std::string blas_in_use() {
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

inline std::string load_average() {
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

inline const char* ordering_name(int o) {
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
//   memory as cold as a new process gets.
inline void settle(const Options& o) {
  if (o.settle_s > 0.0) std::this_thread::sleep_for(std::chrono::duration<double>(o.settle_s));
}

// CHOLMOD's relaxed supernodal amalgamation (cholmod_common nrelax[3], zrelax[3]): columns are
// merged into a supernode while the supernode has fewer than nrelax[k] columns or the fraction of
// explicit zeros stays under zrelax[k]; larger supernodes mean larger BLAS-3 calls.
inline void set_relax(cholmod_common& c, const std::string& nrelax, const std::string& zrelax) {
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
inline void set_ordering(cholmod_common& c, const std::string& name) {
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

// The child's figures, key by key (printed in key order).
class ChildRecord {
 public:
  template <class T>
  void put(const std::string& k, const T& v) {
    out_[k] = fmt::format("{}", v);
  }
  // Stage `name`'s wall (t_name) and CPU (c_name) seconds.
  void stage(const std::string& name, const Stopwatch& w) {
    put("t_" + name, w.wall());
    put("c_" + name, w.cpu());
  }
  double number(const std::string& k) const {
    auto it = out_.find(k);
    return it == out_.end() ? 0.0 : std::atof(it->second.c_str());
  }
  // The BLAS and the load at the end, then the RESULT line.
  void finish() {
    put("blas", blas_in_use());
    put("load_end", load_average());
    std::string line = "RESULT";
    for (const auto& [k, v] : out_) line += " " + k + "=" + v;
    std::puts(line.c_str());
    std::fflush(stdout);
  }

 private:
  std::map<std::string, std::string> out_;
};

// The two SystemAssembler passes: the first builds the pattern (of which end() builds the CSC
// pattern and positions from the triplets), the second writes values through the positions.
inline void assemble_twice(const LinearStructure& structure, const DofMap& map, SystemAssembler& assembler,
                           ChildRecord& rec) {
  Stopwatch t0;
  assembler.begin();
  structure.assemble(map, assembler);
  Stopwatch t_end;
  assembler.end();
  rec.stage("asm1", t0);
  rec.stage("asm1_end", t_end);
  t0 = Stopwatch();
  assembler.begin();
  structure.assemble(map, assembler);
  assembler.end();
  rec.stage("asm2", t0);
}

// CHOLMOD stage by stage on A = S K S: symbolic, then (memory and flops allowing) numeric and one
// solve; `uf` the free displacements where it factorised.
struct StagedFactor {
  double flops = 0.0;  // CHOLMOD's count for the numeric factorisation
  bool factorised = false;
  Eigen::VectorXd uf;
};
inline StagedFactor factor_staged(const SparseMatrix& A, const Eigen::VectorXd& s, const Eigen::VectorXd& f,
                                  const Options& o, ChildRecord& rec) {
  StagedFactor out;
  Cholmod llt;
  set_ordering(llt.common(), o.ordering);
  set_relax(llt.common(), o.nrelax, o.zrelax);
  Stopwatch t0;
  llt.analyzePattern(A);
  rec.stage("symbolic", t0);
  cholmod_common& c = llt.common();
  out.flops = c.fl;
  rec.put("lnz", c.lnz);
  rec.put("gflop", c.fl / 1e9);
  rec.put("ordering", ordering_name(c.method[c.selected].ordering));
  if (llt.info() != Eigen::Success || llt.factor() == nullptr) {
    // CHOLMOD's int interface (Eigen's SparseMatrix<double, 0, int>) stops at 2^31 entries in L.
    rec.put("skip", fmt::format("cholmod-analysis-failed-status-{}", c.status));
    return out;
  }
  const double factor_gb = (llt.factor()->is_super ? double(llt.factor()->xsize) : c.lnz) * 8.0 / 1e9;
  rec.put("factor_gb", factor_gb);
  const double avail_gb = proc_kb("/proc/meminfo", "MemAvailable") / 1e6;
  if (factor_gb > avail_gb - o.mem_margin_gb) {
    rec.put("skip", fmt::format("factor-needs-{:.1f}GB-of-{:.1f}GB-available", factor_gb, avail_gb));
    return out;
  }
  if (out.flops / 1e9 > o.max_gflop) {
    rec.put("skip", fmt::format("{:.0f}-GFlop-over-limit-{:.0f}", out.flops / 1e9, o.max_gflop));
    return out;
  }
  settle(o);
  t0 = Stopwatch();
  llt.factorize(A);
  rec.stage("numeric", t0);
  if (llt.info() != Eigen::Success) {
    rec.put("skip", "cholmod-factorisation-failed");
    return out;
  }
  const Eigen::VectorXd sf = s.cwiseProduct(f);
  t0 = Stopwatch();
  const Eigen::VectorXd y = llt.solve(sf);
  rec.stage("solve", t0);
  out.uf = s.cwiseProduct(y);
  rec.put("cholmod_peak_gb", c.memory_usage / 1e9);
  out.factorised = true;
  return out;
}

// The library path: SparseFactor (analysis + scaling + factorisation + rcond), whose solution
// replaces the staged one in `uf`; then the whole solve_linear_static against the staged numeric
// stage, both after the same pause (settle).
inline void library_path(const Model& model, const DofMap& map, const SparseMatrix& K, const Eigen::VectorXd& f,
                         const Eigen::VectorXd& up, const Options& o, ChildRecord& rec, Eigen::VectorXd& uf) {
  {
    // Its own scope, so that its factor is freed before the pipeline runs: held on (0.73 GB at
    // 97,344 DOFs), it made the pipeline 6.0-7.4 s against 4.8-5.0 s freed, in a process fuller
    // than `beamfea run` ever is.
    SparseFactor factor;
    Stopwatch t0;
    const FactorStatus fs = factor.factorize(K);
    rec.stage("lib_factor", t0);
    rec.put("lib_status", to_string(fs));
    std::string ordering = factor.ordering();  // the record is words: spaces travel as '_'
    std::replace(ordering.begin(), ordering.end(), ' ', '_');
    rec.put("lib_ordering", ordering);
    rec.put("rcond", factor.rcond());
    const Eigen::VectorXd ul = factor.solve(f);
    rec.put("lib_vs_staged", (ul - uf).norm() / uf.norm());
    uf = ul;
  }
  // The whole library analysis as `beamfea run` calls it (DofMap, elements, assembly, scaling,
  // analysis, factorisation, solve, reactions, end forces). With the program's threads: the
  // element matrices beside the ordering of the pattern.
  LinearStaticOptions lso;
  lso.parallel = app::thread_tasks();
  settle(o);
  Stopwatch t0;
  const LinearStaticResult lin = solve_linear_static(model, lso);
  rec.stage("linear_static", t0);
  rec.put("linear_static_vs_staged", (lin.u - map.expand(uf, up)).norm() / map.expand(uf, up).norm());
}

// Checks of the solution: the relative residual, and the base reactions (as solve_linear_static
// computes them) against the loads.
inline void check_solution(const Model& model, const DofMap& map, const LinearStructure& structure, const SparseMatrix& K,
                           const Eigen::VectorXd& f, const Eigen::VectorXd& f_raw, const Eigen::VectorXd& up,
                           const Eigen::VectorXd& uf, ChildRecord& rec) {
  rec.put("residual", (K * uf - f).norm() / f.norm());
  const Eigen::VectorXd u = map.expand(uf, up);
  const Eigen::VectorXd r = structure.internal_force(map, u) - f_raw;
  const auto cf = map.constraint_forces(r);
  Vec3 reaction = Vec3::Zero(), load = Vec3::Zero();
  for (int p = 0; p < map.prescribed_size(); ++p) {
    const auto& dof = map.prescribed()[p].dof;
    if (dof.owner == DofRef::Owner::Node && dof.comp < 3) reaction[dof.comp] += cf.prescribed[p];
  }
  for (const auto& l : model.default_case.nodal) load += l.force;
  rec.put("reaction_err", (reaction + load).norm() / load.norm());
  rec.put("max_u", u.cwiseAbs().maxCoeff());
}

// Baseline 1: Eigen setFromTriplets assembly (raw -> free directly: no constraints here).
inline void baseline_triplets(const Model& model, const DofMap& map, const LinearStructure& structure,
                              const SparseMatrix& K, ChildRecord& rec) {
  const int n = map.free_size();
  Stopwatch t0;
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
  rec.stage("triplets", t0);
  rec.put("triplets_diff", (Kt - K).norm() / K.norm());
}

// Baseline 2: Eigen SimplicialLDLT (AMD) on the same scaled matrix A = S K S.
inline void baseline_ldlt(const SparseMatrix& A, const Eigen::VectorXd& s, const SparseMatrix& K,
                          const Eigen::VectorXd& f, ChildRecord& rec) {
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> ldlt;
  Stopwatch t0;
  ldlt.analyzePattern(A);
  rec.stage("ldlt_symbolic", t0);
  t0 = Stopwatch();
  ldlt.factorize(A);
  rec.stage("ldlt_numeric", t0);
  rec.put("ldlt_nnz", ldlt.matrixL().nestedExpression().nonZeros());
  t0 = Stopwatch();
  const Eigen::VectorXd u = s.cwiseProduct(Eigen::VectorXd(ldlt.solve(s.cwiseProduct(f))));
  rec.stage("ldlt_solve", t0);
  rec.put("ldlt_residual", (K * u - f).norm() / f.norm());
}

// The child: the frame closest to `target` elements, every stage, one RESULT line.
inline int run_single(long target, const Options& o) {
  ChildRecord rec;
  rec.put("load_start", load_average());
  const Dims d = choose_dims(target, o.stories);
  rec.put("dims", fmt::format("{}x{}x{}", d.nx, d.ny, d.nz));
  rec.put("nodes", d.nodes());
  rec.put("elements", d.elements());

  Stopwatch t0;
  const Model model = make_frame(d);
  rec.stage("model", t0);
  t0 = Stopwatch();
  const DofMap map(model);
  rec.stage("dofmap", t0);
  const int n = map.free_size();
  rec.put("dofs", n);
  t0 = Stopwatch();
  const LinearStructure structure(model);
  rec.stage("elements", t0);

  SystemAssembler assembler(map);
  assemble_twice(structure, map, assembler, rec);
  const SparseMatrix& K = assembler.K_ff();
  rec.put("nnz_K", K.nonZeros());
  rec.put("hwm_asm_kb", proc_kb("/proc/self/status", "VmHWM"));

  const Eigen::VectorXd up = map.prescribed_values();
  const Eigen::VectorXd f_raw = external_force(model, map);
  Eigen::VectorXd f = map.reduce(f_raw);
  if (map.prescribed_size() > 0) f -= assembler.K_fp() * up;

  // CHOLMOD, stage by stage, on the matrix SparseFactor factorises.
  Eigen::VectorXd s(n);
  for (int i = 0; i < n; ++i) s[i] = 1.0 / std::sqrt(K.coeff(i, i));
  const SparseMatrix A = scaled(K, s);
  StagedFactor staged = factor_staged(A, s, f, o, rec);
  if (!staged.factorised) {
    rec.put("hwm_lib_kb", proc_kb("/proc/self/status", "VmHWM"));
    rec.finish();
    return 0;
  }
  // Skipped where the numeric factorisation is long.
  if (rec.number("t_numeric") <= o.library_path_max_s) library_path(model, map, K, f, up, o, rec, staged.uf);
  check_solution(model, map, structure, K, f, f_raw, up, staged.uf, rec);
  rec.put("hwm_lib_kb", proc_kb("/proc/self/status", "VmHWM"));

  baseline_triplets(model, map, structure, K, rec);
  if (staged.flops / 1e9 <= o.max_simplicial_gflop) baseline_ldlt(A, s, K, f, rec);
  rec.put("hwm_all_kb", proc_kb("/proc/self/status", "VmHWM"));
  rec.finish();
  return 0;
}

}  // namespace beamfea::bench::frame_solve
