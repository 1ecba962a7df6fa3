// The cost of a pose solve (solvers/pose.hpp) against the stiffness analysis it precedes, for a
// planar 3-RRR parallel manipulator with beam links driven by its platform's position and
// orientation (docs/poses.md, docs/performance.md):
//   pose solve        solve_pose + apply_pose on the read model: continuation from the reference,
//                     Newton on the 9 joint angles (3 actuators, 6 passive) against 2 loops and
//                     the platform target
//   stiffness         run_document of the posed model's stiffness analysis (results in memory)
//   both, in process  load_and_check (reading, posing, checking) + run_document of the posed
//                     document: what one case of a sweep over platform positions costs
// Thread CPU time per call, the median of 5 interleaved batches (bench_timing.hpp's paired).
//
// Usage: taskset -c 1 bench_pose_solve [seconds_per_stage]
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "bench_timing.hpp"
#include "io/run.hpp"
#include "solvers/pose.hpp"

using json = nlohmann::json;
using namespace beamfea;

namespace {

// The platform's target: its centre at (x, y), turned by phi about z.
json platform_target(double x, double y, double phi) {
  const double c = std::cos(phi), s = std::sin(phi);
  return {{"nodes", {{{"node", "O"}, {"xyz", {x, y, 0}}, {"rotation", {{c, -s, 0}, {s, c, 0}, {0, 0, 1}}}}}}};
}

// Base joints on a circle of radius 0.4 at 90 + 120 k degrees, cranks of 0.2 turned 60 degrees
// from the radius, distal links to the platform's corners (radius 0.1) about the centre O.
json three_rrr() {
  json nodes = json::array(), elements = json::array(), joints = json::array(), supports = json::array();
  auto node = [&](const std::string& id, double x, double y) { nodes.push_back({{"id", id}, {"xyz", {x, y, 0.0}}}); };
  auto beam = [&](const std::string& id, const std::string& a, const std::string& b) {
    elements.push_back({{"id", id}, {"type", "beam"}, {"nodes", {a, b}}, {"material", "al"}, {"section", "s"}});
  };
  auto revolute = [&](const std::string& id, const std::string& a, const std::string& b, double k) {
    joints.push_back({{"id", id}, {"type", "revolute"}, {"nodes", {a, b}}, {"axes", {{0, 0, 1}}}, {"stiffness", {k}}});
  };
  node("O", 0, 0);
  for (int k = 0; k < 3; ++k) {
    const std::string s = std::to_string(k + 1);
    const double t = M_PI / 2 + 2 * M_PI * k / 3, c = t + M_PI + M_PI / 3;
    const double bx = 0.4 * std::cos(t), by = 0.4 * std::sin(t);
    const double px = bx + 0.2 * std::cos(c), py = by + 0.2 * std::sin(c);
    const double cx = 0.1 * std::cos(t), cy = 0.1 * std::sin(t);
    node("G" + s, bx, by), node("B" + s, bx, by), node("P" + s, px, py), node("Q" + s, px, py);
    node("C" + s, cx, cy), node("D" + s, cx, cy);
    beam("crank" + s, "B" + s, "P" + s), beam("distal" + s, "Q" + s, "C" + s), beam("plate" + s, "D" + s, "O");
    revolute("a" + s, "G" + s, "B" + s, 2000), revolute("e" + s, "P" + s, "Q" + s, 0), revolute("p" + s, "C" + s, "D" + s, 0);
    supports.push_back({{"node", "G" + s}, {"fix", "all"}});
  }
  return json{{"nodes", nodes},
              {"materials", {{{"id", "al"}, {"E", 7e10}, {"nu", 0.33}}}},
              {"sections", {{{"id", "s"}, {"shape", "rectangle"}, {"b", 0.02}, {"h", 0.03}}}},
              {"elements", elements},
              {"joints", joints},
              {"supports", supports},
              {"pose", platform_target(0.03, -0.02, 0.0)},
              {"analyses", {{{"id", "K"}, {"type", "stiffness"}, {"node", "O"}}}}};
}

}  // namespace

void measure(const json& doc, double budget) {
  json reference = doc;
  reference.erase("pose");
  const Model at_reference = load_and_check(reference);
  const Model posed = load_and_check(doc);
  Pose pose = posed.pose;
  pose.solved.clear();
  RunReport report;
  const PoseSolution s = solve_pose(at_reference, pose);
  fmt::print(
      "3-RRR, beam links: {} nodes, {} joints; the pose takes {} continuation steps, {} Newton iterations, {} Jacobians\n",
      posed.nodes.size(), posed.joints.size(), s.steps, s.newton_iterations, s.jacobians);
  const std::vector<double> t = bench::paired(
      {[&] {
         Model m = at_reference;
         apply_pose(m, solve_pose(at_reference, pose));
       },
       [&] { run_document(posed, doc, {}, report); },
       [&] {
         const Model m = load_and_check(doc);
         run_document(m, doc, {}, report);
       }},
      budget);
  fmt::print("{:<20} {:>12}\n", "stage", "us per call");
  fmt::print("{:<20} {:>12.1f}\n", "pose solve", 1e6 * t[0]);
  fmt::print("{:<20} {:>12.1f}\n", "stiffness", 1e6 * t[1]);
  fmt::print("{:<20} {:>12.1f}\n", "both, in process", 1e6 * t[2]);
  fmt::print("pose solve / stiffness analysis: {:.2f}\n\n", t[0] / t[1]);
}

int main(int argc, char** argv) {
  const double budget = argc > 1 ? std::atof(argv[1]) : 1.0;
  json doc = three_rrr();
  measure(doc, budget);                              // a small move: one continuation step
  doc["pose"] = platform_target(0.08, 0.05, 0.25);  // a large one: several steps
  measure(doc, budget);
  return 0;
}
