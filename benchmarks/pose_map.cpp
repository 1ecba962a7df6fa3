// Poses per second of a workspace map: a six-axis serial arm with revolute joint springs and
// flexible beam links (14 beam elements, 21 nodes, 126 + 6 DOFs), posed by its six joint angles,
// the stiffness analysis of its tool node with indices (stiffness at two directions, the
// deflection under a reference wrench). 10,000 poses: a grid over q2, q3, q4 and q5 (10 values each),
// the same code path as `beamfea sweep` over /pose/joints/... (docs/poses.md, docs/performance.md):
//   pose                 solve_pose + apply_pose on the read model (one forward kinematics)
//   stiffness            run_document of the posed model, kept report (the analysis alone)
//   in-process pose      load_and_check + run_document of the posed document into a kept
//                        ModelBuffer and RunReport (reading, posing, checking, the analysis)
//   sweep case, kept     run_sweep_case with a kept SweepWorkspace + the CSV row (what a sweep
//                        worker does per case)
//   run_sweep --jobs 1   the whole 10,000-pose sweep, table written to a temporary folder, per case
// Thread CPU time per call, median of 9 rounds, the stages interleaved round by round; the last
// column is the stage's time over the sweep case's, round by round (bench_timing.hpp). OpenBLAS
// held to one thread.
//
// Usage: taskset -c 1 bench_pose_map [seconds_per_stage] [poses_per_axis]
//        bench_pose_map --write sweep.json [poses_per_axis]   (the sweep file, for `beamfea sweep`)
#include <unistd.h>
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/openblas.hpp"
#include "app/sweep_runner.hpp"
#include "bench_timing.hpp"
#include "io/model_reader.hpp"
#include "io/run.hpp"
#include "io/sweep.hpp"
#include "io/sweep_table.hpp"
#include "solvers/pose.hpp"

using json = nlohmann::json;
using namespace beamfea;
namespace fs = std::filesystem;

namespace {

// A six-axis arm drawn stretched along x at the reference (all angles zero): a base column of
// 0.4 m (q1 about z at its foot), an upper arm of 0.45 m (q2 about y at the shoulder), a forearm
// of 0.4 m (q3 about y at the elbow), wrist links of 0.1 and 0.08 m (q4 about x, q5 about y) and
// a flange of 0.07 m to the tool node T (q6 about x). Aluminium links (rectangular sections, each
// link 1 to 3 beam elements), gearbox springs of 2e5 to 5e3 N m/rad from base to hand.
json six_axis_arm() {
  json nodes = json::array(), elements = json::array(), joints = json::array();
  auto node = [&](const std::string& id, double x, double z) { nodes.push_back({{"id", id}, {"xyz", {x, 0.0, z}}}); };
  auto link = [&](const std::string& id, const std::string& a, const std::string& b, const char* section, int divisions) {
    elements.push_back({{"id", id}, {"type", "beam"}, {"nodes", {a, b}}, {"material", "al"}, {"section", section},
                        {"divisions", divisions}, {"orientation", {0, 0, 1}}});
  };
  // Joint k from the end of link k-1 (`from`) to the start of link k (`to`), both at one point.
  auto joint = [&](int k, const std::string& from, const std::string& to, const std::vector<double>& axis, double stiffness) {
    joints.push_back({{"id", fmt::format("q{}", k)}, {"type", "revolute"}, {"nodes", {from, to}}, {"axes", {axis}},
                      {"stiffness", {stiffness}}});
  };
  node("G", 0, 0), node("B", 0, 0), node("S0", 0, 0.4), node("S", 0, 0.4), node("E0", 0.45, 0.4), node("E", 0.45, 0.4);
  node("W0", 0.85, 0.4), node("W", 0.85, 0.4), node("V0", 0.95, 0.4), node("V", 0.95, 0.4), node("F0", 1.03, 0.4);
  node("F", 1.03, 0.4), node("T", 1.10, 0.4);
  elements.push_back({{"id", "column"}, {"type", "beam"}, {"nodes", {"B", "S0"}}, {"material", "al"}, {"section", "big"},
                      {"divisions", 2}, {"orientation", {1, 0, 0}}});
  link("upper", "S", "E0", "big", 3), link("fore", "E", "W0", "mid", 3), link("wrist1", "W", "V0", "small", 2);
  link("wrist2", "V", "F0", "small", 2), link("flange", "F", "T", "small", 2);
  joint(1, "G", "B", {0, 0, 1}, 2e5), joint(2, "S0", "S", {0, 1, 0}, 2e5), joint(3, "E0", "E", {0, 1, 0}, 8e4);
  joint(4, "W0", "W", {1, 0, 0}, 1e4), joint(5, "V0", "V", {0, 1, 0}, 1e4), joint(6, "F0", "F", {1, 0, 0}, 5e3);
  return json{{"nodes", nodes},
              {"materials", {{{"id", "al"}, {"E", 7e10}, {"nu", 0.33}}}},
              {"sections",
               {{{"id", "big"}, {"shape", "rectangle"}, {"b", 0.08}, {"h", 0.10}},
                {{"id", "mid"}, {"shape", "rectangle"}, {"b", 0.06}, {"h", 0.07}},
                {{"id", "small"}, {"shape", "rectangle"}, {"b", 0.04}, {"h", 0.05}}}},
              {"elements", elements},
              {"joints", joints},
              {"supports", {{{"node", "G"}, {"fix", "all"}}}},
              {"pose", {{"joints", {{"q1", 0.3}, {"q2", -0.4}, {"q3", 0.9}, {"q4", 0.2}, {"q5", -0.7}, {"q6", 0.1}}}}},
              {"analyses",
               {{{"id", "K"},
                 {"type", "stiffness"},
                 {"node", "T"},
                 {"directions", {{1, 0, 0}, {0, 0, 1}}},
                 {"reference_wrench", {0, 0, -100, 0, 0, 0}}}}}};
}

std::vector<double> values(double lo, double hi, std::size_t n) {
  std::vector<double> v;
  for (std::size_t i = 0; i < n; ++i) v.push_back(n == 1 ? lo : lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(n - 1));
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  app::set_blas_threads(1);
  const bool write = argc > 2 && std::string(argv[1]) == "--write";
  const double budget = argc > 1 && !write ? std::atof(argv[1]) : 1.0;
  const std::size_t per_axis = argc > 3 || (argc > 2 && !write) ? std::strtoul(argv[write ? 3 : 2], nullptr, 10) : 10;

  const json doc = six_axis_arm();
  json unposed = doc;
  unposed.erase("pose");
  const Model reference = load_and_check(unposed);
  const Model posed = load_and_check(doc);
  int dofs = 0;
  for (const auto& j : posed.joints) dofs += j.coordinates();
  fmt::print("six-axis arm: {} nodes, {} elements, {} joints, {} + {} DOFs\n", posed.nodes.size(), posed.elements.size(),
             posed.joints.size(), 6 * posed.nodes.size(), dofs);

  const json tail = {{"grid",
                      {json{{"pointer", "/pose/joints/q2"}, {"values", values(-0.8, 0.8, per_axis)}},
                       json{{"pointer", "/pose/joints/q3"}, {"values", values(-1.5, 1.5, per_axis)}},
                       json{{"pointer", "/pose/joints/q4"}, {"values", values(-1.5, 1.5, per_axis)}},
                       json{{"pointer", "/pose/joints/q5"}, {"values", values(-1.2, 1.2, per_axis)}}}},
                     {"outputs",
                      {"analyses.K.indices.translational.min", "analyses.K.indices.condition_translational",
                       "analyses.K.indices.along", "analyses.K.indices.deflection_norm"}}};
  json sweep_doc = tail;
  sweep_doc["model"] = doc;
  if (write) {
    std::ofstream(argv[2]) << sweep_doc.dump(1) << '\n';
    return 0;
  }
  const Sweep sweep = read_sweep(sweep_doc, fs::temp_directory_path());
  const SweepCaseResult first = run_sweep_case(sweep, 0);
  if (first.status != SweepCaseResult::Status::Succeeded) {
    fmt::print(stderr, "the first pose failed: {}\n", first.message);
    return 1;
  }
  const SweepColumns columns = sweep_columns(sweep, &first);
  // The map is one: the arm's tool stiffness changes from pose to pose.
  const SweepCaseResult other = run_sweep_case(sweep, sweep.size() / 2 + 3);
  std::string row0, row1;
  append_sweep_row(row0, sweep, 0, columns, first);
  append_sweep_row(row1, sweep, sweep.size() / 2 + 3, columns, other);
  fmt::print("two rows of the map:\n  {}  {}", row0, row1);
  const fs::path out = fs::temp_directory_path() / fmt::format("beamfea_bench_pose_map_{}", static_cast<long>(getpid()));

  volatile double sink = 0;
  Pose pose = posed.pose;
  pose.solved.clear();
  RunReport stiffness_report, kept_report;
  ModelBuffer kept_model;
  SweepWorkspace workspace(sweep);
  SweepCaseResult kept_result;
  std::string line;
  std::size_t next = 0;
  const std::vector<std::function<void()>> stages = {
      [&] {
        Model m = reference;
        apply_pose(m, solve_pose(reference, pose));
        sink = sink + m.nodes.back().x[0];
      },
      [&] {
        run_document(posed, doc, {}, stiffness_report);
        sink = sink + static_cast<double>(stiffness_report.failed);
      },
      [&] {
        const Model& m = load_and_check(doc, kept_model);
        run_document(m, doc, {}, kept_report);
        sink = sink + static_cast<double>(kept_report.failed);
      },
      [&] {
        const std::size_t i = next++ % sweep.size();
        run_sweep_case(sweep, i, {}, workspace, kept_result);
        line.clear();
        append_sweep_row(line, sweep, i, columns, kept_result);
        sink = sink + static_cast<double>(line.size());
      },
      [&] {
        fs::remove_all(out);
        SweepOptions o;
        o.out_dir = out;
        o.jobs = 1;
        const SweepSummary s = run_sweep(sweep, o);
        if (s.ok != sweep.size()) fmt::print(stderr, "warning: {} of {} poses ok\n", s.ok, sweep.size());
        sink = sink + static_cast<double>(s.ok);
      }};
  const std::vector<double> per_call = {1, 1, 1, 1, static_cast<double>(sweep.size())};
  const bench::PairedTimes t = bench::paired_rounds(stages, budget, per_call, 3, 9);
  fs::remove_all(out);
  const char* names[] = {"pose (solve_pose + apply_pose)", "stiffness analysis of the posed model",
                         "in-process pose + analysis, kept model and report", "sweep case, kept workspace (+ CSV row)",
                         "run_sweep --jobs 1, per pose"};
  fmt::print("{} poses in the map\n\n", sweep.size());
  fmt::print("| stage (one core) | us per pose | poses per second | / sweep case, paired (min-max) |\n");
  fmt::print("|---|---:|---:|---|\n");
  for (std::size_t i = 0; i < t.median.size(); ++i)
    fmt::print("| {} | {:.1f} | {:.0f} | {:.2f} ({:.2f}-{:.2f}) |\n", names[i], 1e6 * t.median[i], 1.0 / t.median[i],
               t.ratio_median[i], t.ratio_min[i], t.ratio_max[i]);
  return 0;
}
