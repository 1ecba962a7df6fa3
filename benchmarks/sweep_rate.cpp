// Cases per second of `beamfea sweep` against the number of worker threads, on a small model
// (a planar three-link chain with revolute actuator joints, tens of DOFs) and a medium one
// (a 3-D lattice frame, about 1e4 DOFs), and the per-case overhead of the sweep over one
// in-process analysis (load_and_check + run_document on an already-parsed document).
//
// Usage: bench_sweep_rate [small_cases] [medium_cases] [max_jobs]
// Prints a Markdown table (docs/performance.md, "Sweeps").
#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

#include "app/sweep_runner.hpp"
#include "app/openblas.hpp"
#include "io/run.hpp"
#include "io/sweep.hpp"
#include "bench_models.hpp"

using json = nlohmann::json;
namespace fs = std::filesystem;

namespace {

using beamfea::bench::chain;
using beamfea::bench::material_and_section;

// An n x n x n lattice of steel tubes, 1 m pitch, clamped at z = 0; 6 n^3 DOFs.
json lattice(int n) {
  json m = material_and_section();
  m["nodes"] = json::array();
  m["elements"] = json::array();
  auto id = [](int i, int j, int k) { return fmt::format("n{}_{}_{}", i, j, k); };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) m["nodes"].push_back({{"id", id(i, j, k)}, {"xyz", {i, j, k}}});
  int e = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        auto beam = [&](int i2, int j2, int k2) {
          if (i2 >= n || j2 >= n || k2 >= n) return;
          m["elements"].push_back({{"id", fmt::format("e{}", e++)}, {"type", "beam"}, {"nodes", {id(i, j, k), id(i2, j2, k2)}},
                                   {"material", "al"}, {"section", "link"}});
        };
        beam(i + 1, j, k);
        beam(i, j + 1, k);
        beam(i, j, k + 1);
      }
  m["supports"] = json::array();
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) m["supports"].push_back({{"node", id(i, j, 0)}, {"fix", "all"}});
  const std::string top = id(n - 1, n - 1, n - 1);
  m["loads"] = {json{{"node", top}, {"force", {1000.0, 0, 0}}}};
  m["analyses"] = {json{{"id", "lin"}, {"type", "linear_static"}}};
  return m;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Seconds per in-process analysis of the base document (parse already done).
double single_analysis_s(const json& doc, int repeats) {
  const auto t0 = std::chrono::steady_clock::now();
  for (int r = 0; r < repeats; ++r) {
    const auto model = beamfea::load_and_check(doc);
    beamfea::run_document(model, doc, {});
  }
  return seconds_since(t0) / repeats;
}

struct Row {
  std::string model;
  int dofs;
  int jobs;
  std::size_t cases;
  double rate;
  double per_case_s;
  double single_s;
};

Row measure(const std::string& name, int dofs, const json& base, const json& sweep_tail, std::size_t cases, int jobs,
            double single_s) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("beamfea_bench_sweep_{}_{}", name, jobs);
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "base.json") << base.dump();
  json s = sweep_tail;
  s["base"] = "base.json";
  std::ofstream(dir / "sweep.json") << s.dump();
  const auto sweep = beamfea::read_sweep_file((dir / "sweep.json").string());
  beamfea::SweepOptions opt;
  opt.out_dir = dir / "out";
  opt.jobs = jobs;
  const auto t0 = std::chrono::steady_clock::now();
  const auto summary = beamfea::run_sweep(sweep, opt);
  const double wall = seconds_since(t0);
  if (summary.ok != cases) fmt::print(stderr, "warning: {} of {} cases ok\n", summary.ok, cases);
  fs::remove_all(dir);
  return {name, dofs, jobs, cases, cases / wall, wall * jobs / cases, single_s};
}

}  // namespace

int main(int argc, char** argv) {
  // As in a sweep: one BLAS thread per analysis, so that both columns measure the same thing.
  beamfea::app::set_blas_threads(1);
  const std::size_t small_cases = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 20000;
  const std::size_t medium_cases = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 16;
  const int max_jobs = argc > 3 ? std::atoi(argv[3]) : static_cast<int>(std::thread::hardware_concurrency());
  std::vector<int> jobs_list;
  for (int j = 1; j <= max_jobs; j *= 2) jobs_list.push_back(j);
  if (jobs_list.back() != max_jobs) jobs_list.push_back(max_jobs);

  std::vector<Row> rows;
  {
    const json base = chain();
    // A grid over the three actuator stiffnesses: every case a fresh model and analysis.
    const std::size_t n = std::max<std::size_t>(1, static_cast<std::size_t>(std::cbrt(static_cast<double>(small_cases)) + 0.5));
    std::vector<double> k;
    for (std::size_t i = 0; i < n; ++i) k.push_back(500.0 + 100.0 * i);
    const json tail = {{"grid", {json{{"pointer", "/joints/0/stiffness/0"}, {"values", k}},
                                 json{{"pointer", "/joints/1/stiffness/0"}, {"values", k}},
                                 json{{"pointer", "/joints/2/stiffness/0"}, {"values", k}}}},
                       {"outputs", {"analyses.K.matrix"}}};
    const double single = single_analysis_s(base, 2000);
    for (int j : jobs_list) rows.push_back(measure("chain", 63, base, tail, n * n * n, j, single));
  }
  {
    const int n = 12;
    const json base = lattice(n);
    std::vector<double> P;
    for (std::size_t i = 0; i < medium_cases; ++i) P.push_back(100.0 * (i + 1));
    const json tail = {{"grid", {json{{"pointer", "/loads/0/force/0"}, {"values", P}}}},
                       {"outputs", {fmt::format("analyses.lin.nodes.n{}_{}_{}.displacement[0]", n - 1, n - 1, n - 1)}}};
    const double single = single_analysis_s(base, 3);
    for (int j : jobs_list) rows.push_back(measure("lattice", 6 * n * n * n, base, tail, medium_cases, j, single));
  }

  fmt::print("| model | DOFs | jobs | cases | cases/s | s per case per job | one in-process analysis, s | overhead per case |\n");
  fmt::print("|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& r : rows)
    fmt::print("| {} | {} | {} | {} | {:.0f} | {:.3g} | {:.3g} | {:+.0f}% |\n", r.model, r.dofs, r.jobs, r.cases, r.rate,
               r.per_case_s, r.single_s, 100.0 * (r.per_case_s / r.single_s - 1.0));
  fmt::print("\n{} hardware threads.\n", std::thread::hardware_concurrency());
}
