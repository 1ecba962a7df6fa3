// bench_path_step: cost of one arc-length step of the path analysis against the number of DOFs.
//
// The frame: n x n bays (6 m x 6 m) and S storeys of 3.5 m, a column on every grid point of every
// storey, beams along x and y at every floor (co-rotational beams), bases fixed, every floor node
// loaded by (1, 0.5, -10) kN (the load pattern). Stages, as the path solver runs them
// (solvers/path_following.cpp) at the reference state:
//   assembly   NonlinearStructure::evaluate with tangent (co-rotational response of every beam,
//              T^T K T, constraint curvature) and restriction to the free coordinates
//   factor     UMFPACK numeric LU of the tangent, symbolic analysis done once and reused
//   inertia    SimplicialLDLT (AMD, symbolic analysis reused) of the symmetrised tangent: the count of
//              negative eigenvalues
//   min eig    lowest eigenvalue of the Jacobi-scaled symmetrised tangent (solvers/eigen_lowest.hpp:
//              dense below 200 DOFs, Spectra shift-invert with CHOLMOD above)
//   step       one whole arc-length step of follow_path (predictor, chord or KINSOL Newton iterations,
//              stability, the record of the step): the least of the times between the progress
//              lines of consecutive steps (steady state: setup, linearised buckling of the scales and
//              the first step excluded); "no stab." the same without the stability analysis
//   ratio      step / (assembly + LU factor), with and without stability: the median of the ratios of
//              each step to one assembly + LU measured right after it (paired)
// Times are CPU seconds of the calling thread (CLOCK_THREAD_CPUTIME_ID), the least of `reps`
// repetitions for the stages: the machine is shared, wall clock is not a measure there. The last
// column, process CPU / thread CPU over the runs, shows CPU that other threads burn (OpenBLAS's
// workers spinning between factorisations). The solvers' BLAS-thread hook is installed as the
// program installs it (follow_path runs with one BLAS thread); the stages run with the BLAS's
// threads unless OPENBLAS_NUM_THREADS=1 (the honest setting for thread CPU figures).
// Usage: bench_path_step [--sizes 2,4,8,12] [--stories S] [--steps K] [--reps R]
//        bench_path_step --classic [--arc auto|DS] [--max-steps N]
//   --classic [--arch-elements N]: the deep arch (80 elements, unit load) to its first limit point and Lee's frame (P = 1)
//   to its second limit point, under arc length ("auto" or a given first step DS), the stop one step
//   after the critical point; prints steps, critical load, CPU time, free DOFs.
// Output: a Markdown table on stdout.
#include <fmt/format.h>

#include <Eigen/SparseCholesky>
#include <Eigen/UmfPackSupport>
#include <algorithm>
#include <cmath>
#include <ctime>
#include <functional>
#include <cstdlib>
#include <cstring>
#include <time.h>
#include <sstream>
#include <string>
#include <vector>

#include "app/openblas.hpp"
#include "bench_blas.hpp"
#include "bench_timing.hpp"
#include "solvers/eigen_lowest.hpp"
#include "solvers/nonlinear_structure.hpp"
#include "solvers/path_following.hpp"
// The benchmark models of the path tests (JSON written as users write them).
#include "../tests/solvers/path_models.hpp"

using namespace beamfea;
#ifndef BEAMFEA_ARC_AUTO
#define BEAMFEA_ARC_AUTO(o) ((o).arc_length_auto = true)
#endif

namespace {

Model frame(int n, int storeys) {
  Model m;
  m.materials.push_back({"steel", 210e9, 81e9});
  m.sections.push_back({"col", 7.81e-3, 5.7e-5, 2.0e-5, 5.9e-7, 0, 0});
  auto id = [&](int i, int j, int k) { return (k * (n + 1) + j) * (n + 1) + i; };
  for (int k = 0; k <= storeys; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) m.nodes.push_back({fmt::format("n{}_{}_{}", i, j, k), Vec3(6.0 * i, 6.0 * j, 3.5 * k), -1});
  auto add = [&](int a, int b, const Vec3& o) {
    Element e;
    e.id = fmt::format("e{}", m.elements.size());
    e.type = MemberType::Beam;
    e.nodes = {a, b};
    e.material = 0;
    e.section = 0;
    e.orientation = o;
    m.elements.push_back(e);
  };
  for (int k = 0; k < storeys; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) add(id(i, j, k), id(i, j, k + 1), Vec3(1, 0, 0));
  for (int k = 1; k <= storeys; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        if (i < n) add(id(i, j, k), id(i + 1, j, k), Vec3(0, 0, 1));
        if (j < n) add(id(i, j, k), id(i, j + 1, k), Vec3(0, 0, 1));
        m.default_case.nodal.push_back({id(i, j, k), Vec3(1e3, 0.5e3, -10e3), Vec3::Zero()});
      }
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      Support s;
      s.node = id(i, j, 0);
      s.fixed.fill(true);
      m.supports.push_back(s);
    }
  return m;
}

double cpu_clock(clockid_t id) {
  timespec ts{};
  clock_gettime(id, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
double thread_cpu() { return cpu_clock(CLOCK_THREAD_CPUTIME_ID); }
double process_cpu() { return cpu_clock(CLOCK_PROCESS_CPUTIME_ID); }

// The least of repeated timings: on a shared machine the others only add (cache and memory
// bandwidth taken by other processes inflate even the thread's own CPU time).
double least(const std::vector<double>& v) { return v.empty() ? NAN : *std::min_element(v.begin(), v.end()); }

// A path of `steps` arc-length steps: the least thread CPU time of a steady step (between the
// progress lines of consecutive steps, from the second on), and the median of the paired ratios
// step / (assembly + LU), `reference` (one assembly and one LU) being measured right after each step
// (inside the progress line, its time taken out of the next step's): a slow phase of the shared
// machine slows both sides of a ratio. Also Newton iterations per step, and the process and
// thread CPU of the whole run.
struct PathRun {
  double step = NAN, ratio = NAN, iterations = 0.0, chord_iterations = 0.0, process = 0.0, thread = 0.0;
};
PathRun time_path(const Model& m, int steps, bool stability, const std::function<double()>& reference) {
  PathOptions o;
  o.control = PathControl::ArcLength;
  o.arc_length = 0.05;
  o.max_steps = steps;
  o.stability = stability;
  std::vector<double> marks, refs;
  double taken_out = 0.0;  // thread CPU spent measuring the reference
  o.progress = [&](const std::string& line) {
    if (line.rfind("step ", 0) != 0 || line.find("load factor") == std::string::npos) return;
    const double t = thread_cpu();
    marks.push_back(t - taken_out);
    refs.push_back(reference());
    taken_out += thread_cpu() - t;
  };
  PathRun out;
  const double p0 = process_cpu(), t0 = thread_cpu();
  const PathResult r = follow_path(m, o);
  out.process = process_cpu() - p0 - taken_out;  // (the reference runs on this thread)
  out.thread = thread_cpu() - t0 - taken_out;
  std::vector<double> d, q;
  for (std::size_t i = 1; i < marks.size(); ++i) {
    d.push_back(marks[i] - marks[i - 1]);
    q.push_back(d.back() / refs[i]);
  }
  out.step = least(d);
  out.ratio = bench::median(q);
  long its = 0, chord = 0;
  for (const auto& s : r.steps) {
    its += s.iterations;
    chord += s.chord_iterations;
  }
  out.iterations = static_cast<double>(its) / std::max<int>(1, static_cast<int>(r.steps.size()) - 1);
  out.chord_iterations = static_cast<double>(chord) / std::max<int>(1, static_cast<int>(r.steps.size()) - 1);
  return out;
}

// One classic benchmark: steps to the `nth` critical point, its load, CPU seconds. The run is ended
// (by an exception from the progress sink) at the step after that critical point.
struct Reached {};
void classic(const char* name, const Model& m, const char* track, double P, int nth, bool autostep, double ds,
             int max_steps) {
  PathOptions o;
  o.control = PathControl::ArcLength;
  o.track = {m.find_node(track)};
  o.max_steps = max_steps;
  if (autostep) {
    BEAMFEA_ARC_AUTO(o);
  } else {
    o.arc_length = ds;
  }
  int found = 0, steps = 0, at = -1;
  double load = 0.0;
  o.progress = [&](const std::string& line) {
    if (line.rfind("critical point", 0) == 0 && ++found == nth) {
      const auto p = line.find("load factor ");
      load = std::atof(line.c_str() + p + 12) * P;
      at = steps;
    } else if (line.rfind("step ", 0) == 0 && line.find("load factor") != std::string::npos) {
      steps = std::atoi(line.c_str() + 5);
      if (at >= 0 && steps > at) throw Reached{};
    }
  };
  const auto t0 = std::clock();
  std::string end = "reached";
  try {
    const PathResult r = follow_path(m, o);
    end = r.brief_report();
  } catch (const Reached&) {
  }
  const double cpu = static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC;
  fmt::print("| {} | {} | {} | {} | {:.2f} |\n", name, autostep ? std::string("auto") : fmt::format("{}", ds),
             at >= 0 ? fmt::format("{}", at) : fmt::format("not reached: {} steps, {}", steps, end),
             at >= 0 ? fmt::format("{:.6g}", load) : std::string("-"), cpu);
  std::fflush(stdout);
}

// --classic: the deep arch and Lee's frame to their critical points (options --arc, --max-steps,
// --arch-elements read from the whole command line).
int run_classic(int argc, char** argv) {
  bool autostep = true;
  double ds = 0.0;
  int max_steps = 500, arch_elements = 80;
  for (int k = 1; k < argc; ++k) {
    if (!std::strcmp(argv[k], "--arc") && k + 1 < argc) {
      autostep = !std::strcmp(argv[k + 1], "auto");
      if (!autostep) ds = std::atof(argv[k + 1]);
    }
    if (!std::strcmp(argv[k], "--max-steps") && k + 1 < argc) max_steps = std::atoi(argv[k + 1]);
    if (!std::strcmp(argv[k], "--arch-elements") && k + 1 < argc) arch_elements = std::atoi(argv[k + 1]);
  }
  fmt::print("| benchmark | arc_length | step of the critical point | P there | CPU [s] |\n|---|---|---|---|---|\n");
  classic("deep arch, 1st limit", read_model(test::deep_arch(arch_elements, 1.0)), "apex", 1.0, 1, autostep, ds, max_steps);
  classic("Lee's frame, 2nd limit", read_model(test::lees_frame(1.0)), "P", 1.0, 2, autostep, ds, max_steps);
  return 0;
}

// One row of the table: the frame of n x n bays and `storeys` storeys, its stages timed `reps`
// times at the reference state, then two paths of `steps` steps (with and without stability).
void run_size(int n, int storeys, int steps, int reps) {
  const Model m = frame(n, storeys);
  const NonlinearStructure ns(m);
  const NonlinearState s0 = ns.reference_state();
  const Eigen::VectorXd f = Eigen::VectorXd::Zero(ns.reference_map().raw_size());
  std::vector<int> free;
  std::vector<int> g2f(ns.size(), -1);
  for (int i = 0; i < ns.size(); ++i)
    if (ns.reference_map().prescribed_index(ns.gens()[i].raw) < 0) {
      g2f[i] = static_cast<int>(free.size());
      free.push_back(i);
    }
  std::vector<double> t_asm, t_lu, t_ldl, t_eig;
  SparseMatrix K;
  Eigen::UmfPackLU<SparseMatrix> lu;
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt;
  // K = the tangent restricted to the free coordinates (g2f: generalised -> free index or -1).
  const auto restrict_to_free = [&](const SparseMatrix& tangent) {
    std::vector<Eigen::Triplet<double>> t;
    for (int j = 0; j < tangent.outerSize(); ++j)
      if (g2f[j] >= 0)
        for (SparseMatrix::InnerIterator it(tangent, j); it; ++it)
          if (g2f[it.row()] >= 0) t.emplace_back(g2f[it.row()], g2f[j], it.value());
    K.resize(static_cast<int>(free.size()), static_cast<int>(free.size()));
    K.setFromTriplets(t.begin(), t.end());
  };
  int negative = 0;
  for (int r = 0; r < reps; ++r) {
    double t0 = thread_cpu();
    const auto ev = ns.evaluate(s0, f, true);
    restrict_to_free(ev.tangent);
    t_asm.push_back(thread_cpu() - t0);
    if (r == 0) {
      lu.analyzePattern(K);
      ldlt.analyzePattern(K);
    }
    t0 = thread_cpu();
    lu.factorize(K);
    t_lu.push_back(thread_cpu() - t0);
    t0 = thread_cpu();
    const SparseMatrix S = SparseMatrix(0.5 * (K + SparseMatrix(K.transpose())));
    ldlt.factorize(S);
    negative = static_cast<int>((ldlt.vectorD().array() < 0).count());
    t_ldl.push_back(thread_cpu() - t0);
    const Eigen::VectorXd sc = S.diagonal().cwiseAbs().cwiseSqrt().cwiseInverse();
    const SparseMatrix A = SparseMatrix(sc.asDiagonal() * S * sc.asDiagonal());
    t0 = thread_cpu();
    const EigenPairs ep = lowest_eigenpairs(A, 1, -1e-6);
    t_eig.push_back(thread_cpu() - t0);
    (void)ep;
  }
  const double a = least(t_asm), l = least(t_lu);
  // One assembly and one LU, as the stages above (paired with each path step).
  const auto reference = [&] {
    const double t0 = thread_cpu();
    const auto ev = ns.evaluate(s0, f, true);
    restrict_to_free(ev.tangent);
    lu.factorize(K);
    return thread_cpu() - t0;
  };
  const PathRun with = time_path(m, steps, true, reference), without = time_path(m, steps, false, reference);
  fmt::print("| {}x{} | {} | {} | {:.2f} | {:.2f} | {:.2f} | {:.1f} | {:.1f} | {:.1f} | {:.2f} | {:.2f} | {:.1f} + {:.1f} | {:.2f} |\n", n,
             n, storeys, free.size(), 1e3 * a, 1e3 * l, 1e3 * least(t_ldl), 1e3 * least(t_eig), 1e3 * with.step,
             1e3 * without.step, with.ratio, without.ratio, with.iterations, with.chord_iterations,
             (with.process + without.process) / (with.thread + without.thread));
  std::fflush(stdout);
  if (negative != 0) fmt::print(stderr, "warning: {} negative eigenvalues at the reference state\n", negative);
}

}  // namespace

int main(int argc, char** argv) {
  // As the program does (cli/main.cpp): its BLAS kernels and the solvers' BLAS-thread hook.
  fmt::print(stderr, "BLAS: {}\n", bench::choose_libraries_as_the_program());
  app::install_openblas_threads_hook();
  for (int i = 1; i < argc; ++i)
    if (!std::strcmp(argv[i], "--classic")) return run_classic(argc, argv);
  std::vector<int> sizes{2, 4, 8, 12};
  int storeys = 3, steps = 6, reps = 5;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) {
      sizes.clear();
      std::stringstream ss(argv[++i]);
      std::string t;
      while (std::getline(ss, t, ',')) sizes.push_back(std::stoi(t));
    } else if (!std::strcmp(argv[i], "--stories") && i + 1 < argc) {
      storeys = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--steps") && i + 1 < argc) {
      steps = std::max(3, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--reps") && i + 1 < argc) {
      reps = std::max(1, std::atoi(argv[++i]));
    }
  }
  fmt::print("| bays | storeys | free DOFs | assembly [ms] | LU factor [ms] | LDL' inertia [ms] | min eig [ms] | step [ms] | "
             "step, no stab. [ms] | step / (asm + LU) | no stab. / (asm + LU) | Newton + chord it./step | process / thread CPU |\n");
  fmt::print("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (int n : sizes) run_size(n, storeys, steps, reps);
  return 0;
}
