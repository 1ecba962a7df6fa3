// Stiffness analyses per second of the three-link chain (bench_models.hpp: 63 raw, 39 free DOFs)
// on one core, at each stage a sweep case goes through (the aims: 30,000 per second, a sweep within
// 1.2x of the in-process analysis):
//   linear_node_stiffness      DOF map, element matrices, assembly, condensation, rank
//   in-process analysis        load_and_check + run_document on the parsed document (the model
//                              built and checked, the results JSON built): bench_sweep_rate's
//                              baseline
//   sweep case                 run_sweep_case + sweep_row: the case's document, the analysis,
//                              the outputs flattened and formatted as a CSV row
//   run_sweep --jobs 1         the whole sweep inline (table written to a temporary folder),
//                              per case
//   in-process, kept           stage 2 into a kept ModelBuffer and RunReport (what a sweep worker
//                              keeps from case to case)
//   sweep case, kept           stage 3 with a kept SweepWorkspace and SweepCaseResult, the row
//                              appended to a kept line (run_sweep's per-case work, without its
//                              table and fixed costs)
// The last column divides each batch's time by the in-process analysis's time of the same batch
// round and gives the median of those ratios (15 rounds), a paired figure less exposed to the
// host's changes of speed than the ratio of two medians.
// Only long-standing interfaces are used, so that the same source measures an older build
// (paired ratios of two builds: run both binaries alternately).
//
// Usage: taskset -c 1 bench_chain_rate [seconds_per_stage] [sweep_cases]
// Thread CPU time per call (the machine's load makes wall clock meaningless at this scale),
// median of 15 rounds, the stages interleaved round by round. OpenBLAS held to one thread.
// "allocations per call": calls of operator new (this executable replaces it with a counting
// one) per call of the stage, counted over a separate pass after the timing.
#include <unistd.h>
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <new>
#include <nlohmann/json.hpp>
#include <vector>

#include "app/sweep_runner.hpp"
#include "app/openblas.hpp"
#include "bench_models.hpp"
#include "bench_timing.hpp"
#include "io/model_reader.hpp"
#include "io/run.hpp"
#include "io/sweep.hpp"
#include "io/sweep_table.hpp"
#include "solvers/condensed_stiffness.hpp"

using json = nlohmann::json;
using namespace beamfea;
namespace fs = std::filesystem;

// Calls of operator new in the whole process (the sized, aligned and array forms all end here or
// in the aligned overload below).
static std::atomic<long> g_allocations{0};

// GCC 12 flags free() of memory from a replaced operator new as mismatched; here both are ours.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

void* operator new(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t n, std::align_val_t a) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  const std::size_t al = static_cast<std::size_t>(a);
  if (void* p = std::aligned_alloc(al, (n + al - 1) / al * al)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop

int main(int argc, char** argv) {
  beamfea::app::set_blas_threads(1);
  const double budget = argc > 1 ? std::atof(argv[1]) : 1.0;
  const std::size_t sweep_cases = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 343;

  const json doc = bench::chain();
  const Model model = read_model(doc);
  const int tip = model.find_node("T");
  // A grid over the three actuator stiffnesses (bench_sweep_rate's sweep): every case a new model.
  const std::size_t n = std::max<std::size_t>(1, static_cast<std::size_t>(std::cbrt(static_cast<double>(sweep_cases)) + 0.5));
  std::vector<double> k;
  for (std::size_t i = 0; i < n; ++i) k.push_back(500.0 + 100.0 * static_cast<double>(i));
  const json tail = {{"grid", {json{{"pointer", "/joints/0/stiffness/0"}, {"values", k}},
                               json{{"pointer", "/joints/1/stiffness/0"}, {"values", k}},
                               json{{"pointer", "/joints/2/stiffness/0"}, {"values", k}}}},
                     {"outputs", {"analyses.K.matrix"}}};
  json sweep_doc = tail;
  sweep_doc["model"] = doc;
  const Sweep sweep = read_sweep(sweep_doc, fs::temp_directory_path());
  const SweepCaseResult first = run_sweep_case(sweep, 0);
  const SweepColumns columns = sweep_columns(sweep, &first);
  const fs::path out = fs::temp_directory_path() / fmt::format("beamfea_bench_chain_rate_{}", static_cast<long>(getpid()));

  volatile double sink = 0;
  std::size_t next = 0;
  std::vector<std::function<void()>> stages = {[&] { sink = sink + linear_node_stiffness(model, tip).K(0, 0); },
       [&] {
         const Model m = load_and_check(doc);
         sink = sink + static_cast<double>(run_document(m, doc, {}).failed);
       },
       [&] {
         const std::size_t i = next++ % sweep.size();
         sink = sink + static_cast<double>(sweep_row(sweep, i, columns, run_sweep_case(sweep, i)).size());
       },
       [&] {
         fs::remove_all(out);
         SweepOptions o;
         o.out_dir = out;
         o.jobs = 1;
         sink = sink + static_cast<double>(run_sweep(sweep, o).ok);
       }};
  ModelBuffer kept_model;
  RunReport kept_report;
  SweepWorkspace workspace(sweep);
  SweepCaseResult kept_result;
  std::string line;
  std::size_t next_kept = 0;
  stages.push_back([&] {
    const Model& m = load_and_check(doc, kept_model);
    run_document(m, doc, {}, kept_report);
    sink = sink + static_cast<double>(kept_report.failed);
  });
  stages.push_back([&] {
    const std::size_t i = next_kept++ % sweep.size();
    run_sweep_case(sweep, i, {}, workspace, kept_result);
    line.clear();
    append_sweep_row(line, sweep, i, columns, kept_result);
    sink = sink + static_cast<double>(line.size());
  });
  const std::vector<double> per_call = {1.0, 1.0, 1.0, static_cast<double>(sweep.size()), 1.0, 1.0};
  const bench::PairedTimes t = bench::paired_rounds(stages, budget, per_call, 1, 15);
  std::vector<double> allocations;
  for (std::size_t i = 0; i < stages.size(); ++i) {
    constexpr int kCalls = 20;
    const long a0 = g_allocations.load();
    for (int r = 0; r < kCalls; ++r) stages[i]();
    allocations.push_back(static_cast<double>(g_allocations.load() - a0) / kCalls / per_call[i]);
  }
  fs::remove_all(out);
  const char* names[] = {"linear_node_stiffness", "in-process analysis (load_and_check + run_document)",
                         "sweep case (run_sweep_case + sweep_row)", "run_sweep --jobs 1, per case",
                         "in-process analysis, kept model and report", "sweep case, kept workspace, result and line"};
  fmt::print(
      "| stage (three-link chain, {} free DOFs, one core) | us per call | calls per second | / in-process | "
      "allocations per call | / in-process, paired (min-max) |\n",
      39);
  fmt::print("|---|---:|---:|---:|---:|---|\n");
  for (std::size_t i = 0; i < t.median.size(); ++i)
    fmt::print("| {} | {:.1f} | {:.0f} | {:.2f} | {:.0f} | {:.2f} ({:.2f}-{:.2f}) |\n", names[i], 1e6 * t.median[i],
               1.0 / t.median[i], t.median[i] / t.median[1], allocations[i], t.ratio_median[i], t.ratio_min[i],
               t.ratio_max[i]);
}
