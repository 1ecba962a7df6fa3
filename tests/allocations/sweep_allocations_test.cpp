// Allocations of a sweep case once a worker's workspace is warm (the aim: no per-case
// allocations in sweeps). This executable replaces the global operator new with one that counts
// its calls, so it is a folder (test executable) of its own: no other test runs under the counter.
//
// A case goes through what `beamfea sweep --jobs 1` does for it inline: run_sweep_case with the
// worker's SweepWorkspace and SweepCaseResult, then its CSV row appended to the batch. After one
// pass over the cases (the workspace takes its sizes), a second pass over the same cases must call
// operator new not once: the three-link chain's stiffness sweep (joint springs change), the
// portal frame's load sweep of examples/04 (the lateral load changes, the structure does not) and
// examples/03's workspace map (the geometry changes every case: the structure cache misses), the
// chain's sweep again with its springs set by JSON Patches, and a pose sweep of examples/08's
// five-bar linkage, a closed loop, as beams and as rigid links (redundant constraint rows).
// The results of the warm pass are also checked against fresh runs of the same cases, bit for bit.
// Eigen's and CHOLMOD's arrays are malloc'ed, not new'ed: those are not counted here (heaptrack
// counts them: docs/performance.md).
#include <gtest/gtest.h>

#include <atomic>
#include <fstream>
#include <cmath>
#include <cstdlib>
#include <new>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/sweep.hpp"
#include "io/sweep_table.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

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
// Every other form too: under AddressSanitizer the runtime supplies them, and memory from its
// nothrow new (std::stable_sort's buffer) freed by the delete above would be a mismatch.
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(n == 0 ? 1 : n);
}
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  const std::size_t al = static_cast<std::size_t>(a);
  return std::aligned_alloc(al, (n + al - 1) / al * al);
}
void* operator new[](std::size_t n) { return operator new(n); }
void* operator new[](std::size_t n, std::align_val_t a) { return operator new(n, a); }
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t& t) noexcept { return operator new(n, a, t); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace sweep_allocations_test {

using json = nlohmann::json;
using beamfea::Sweep;
using beamfea::SweepCaseResult;

// The three-link chain of benchmarks/bench_models.hpp (10 nodes, 63 raw DOFs): links of 0.3 m,
// each meshed into 2 elements, revolute joints about z with actuator springs, the ground clamped;
// the stiffness of the tip T. The grid sets the three springs.
json chain_sweep() {
  json m = {{"materials", {json{{"id", "al"}, {"E", 70e9}, {"nu", 0.33}}}},
            {"sections", {json{{"id", "link"}, {"shape", "rectangle"}, {"b", 0.02}, {"h", 0.04}}}},
            {"nodes", {json{{"id", "G"}, {"xyz", {0, 0, 0}}}}},
            {"elements", json::array()},
            {"joints", json::array()}};
  std::string prev = "G";
  for (int l = 1; l <= 3; ++l) {
    const double x0 = 0.3 * (l - 1), x1 = 0.3 * l;
    const std::string k = std::to_string(l);  // (GCC 12 warns falsely on "L" + to_string(l): -Wrestrict)
    const std::string s = std::string("L").append(k).append("s");
    const std::string e = l == 3 ? std::string("T") : std::string("L").append(k).append("e");
    m["nodes"].push_back({{"id", s}, {"xyz", {x0, 0, 0}}});
    m["nodes"].push_back({{"id", e}, {"xyz", {x1, 0, 0}}});
    m["joints"].push_back({{"id", std::string("q").append(k)}, {"type", "revolute"}, {"nodes", {prev, s}},
                           {"axes", {{0, 0, 1}}}, {"stiffness", {2000.0}}});
    m["elements"].push_back({{"id", std::string("link").append(k)}, {"type", "beam"}, {"nodes", {s, e}},
                             {"material", "al"}, {"section", "link"}, {"divisions", 2}});
    prev = e;
  }
  m["supports"] = {json{{"node", "G"}, {"fix", "all"}}};
  m["analyses"] = {json{{"id", "K"}, {"type", "stiffness"}, {"node", "T"}}};
  const json k = {500.0, 800.0, 1100.0};
  return {{"model", m},
          {"grid",
           {json{{"pointer", "/joints/0/stiffness/0"}, {"values", k}}, json{{"pointer", "/joints/1/stiffness/0"}, {"values", k}},
            json{{"pointer", "/joints/2/stiffness/0"}, {"values", k}}}},
          {"outputs", {json{{"name", "K"}, {"path", "analyses.K.matrix"}}, json{{"name", "C"}, {"path", "analyses.K.compliance"}}}}};
}

// examples/04's portal frame (linear_static, 10 nodes) with the lateral load H as the only axis.
json load_sweep() {
  json values = json::array();
  for (int i = 0; i <= 10; ++i) values.push_back(5000.0 * i);
  return {{"base", "model.json"},
          {"grid", {json{{"name", "H"}, {"pointer", "/loads/0/force/0"}, {"values", values}}}},
          {"outputs",
           {json{{"name", "sway"}, {"path", "analyses.lin.nodes.D.displacement[0]"}},
            json{{"name", "base_A"}, {"path", "analyses.lin.nodes.A.reaction"}},
            json{{"name", "ends"}, {"path", "analyses.lin.elements"}}}}};
}

// examples/03's workspace map on 3 x 4 poses, written as its make_cases.py writes them: an explicit
// list of cases, each setting the elbow nodes E1, E2 and the tip T to the forward kinematics of the
// two angles (a new geometry every case, so the structure cache misses every case).
json workspace_map_sweep() {
  constexpr double kPi = 3.14159265358979323846;
  const double L1 = 0.4, L2 = 0.3;
  json cases = json::array();
  for (const double t1 : {0.0, 45.0, 90.0}) {
    for (const double t2 : {-150.0, -45.0, 0.0, 120.0}) {
      const double a = t1 * kPi / 180, b = (t1 + t2) * kPi / 180;
      const json e = {L1 * std::cos(a), L1 * std::sin(a), 0.0};
      const json t = {e[0].get<double>() + L2 * std::cos(b), e[1].get<double>() + L2 * std::sin(b), 0.0};
      const std::string id =
          std::string("t1=").append(std::to_string(static_cast<int>(t1))).append("_t2=").append(std::to_string(static_cast<int>(t2)));
      cases.push_back({{"id", id},
                       {"parameters", {{"theta1_deg", t1}, {"theta2_deg", t2}}},
                       {"set", {{"/nodes/2/xyz", e}, {"/nodes/3/xyz", e}, {"/nodes/4/xyz", t}}}});
    }
  }
  // The example's model posed by node coordinates, as a generator script would write them: its
  // "pose" (the example's own way, solvers/pose.hpp) is taken out. A posed case still allocates
  // in the pose solver (its topology and Newton workspace are made per case).
  std::ifstream in(BEAMFEA_SOURCE_DIR "/examples/03_workspace_stiffness_map/model.json");
  json model = json::parse(in);
  model.erase("pose");
  return {{"model", model}, {"cases", cases}, {"outputs", {json{{"name", "K"}, {"path", "analyses.K.matrix"}}}}};
}

// The chain's sweep with its springs set by JSON Patches instead of pointers: one axis of three
// patches, each a "test" of the ground's support and "replace"s of the three springs.
json chain_patch_sweep() {
  json s = chain_sweep();
  s["grid"] = json::array();
  json patches = json::array();
  for (const double k : {500.0, 800.0, 1100.0}) {
    json patch = {json{{"op", "test"}, {"path", "/supports/0/node"}, {"value", "G"}}};
    for (int j = 0; j < 3; ++j)
      patch.push_back({{"op", "replace"}, {"path", "/joints/" + std::to_string(j) + "/stiffness/0"}, {"value", k + 100.0 * j}});
    patches.push_back(patch);
  }
  s["grid"].push_back({{"name", "springs"}, {"patches", patches}});
  return s;
}

// examples/08's five-bar linkage (a parallel mechanism: two actuated proximal links, two distal
// links, the loop closed by the revolute joint pE) as beams, its tip stiffness over 3 x 4 poses of
// the two actuators: each case sets the elbows B1, B2 and the tip E (and their joint partners) to
// the forward kinematics, so the structure cache misses every case and the loop's DofMap is
// rebuilt. beam.json has the links as beams; lumped.json as rigid links (the lumped model, whose
// planar loop is over-constrained in 3-D: redundant rows, named in the results).
json five_bar_sweep(const char* model) {
  constexpr double kPi = 3.14159265358979323846;
  const double a = 0.2, l1 = 0.25, l2 = 0.25;  // base width, proximal and distal lengths
  json cases = json::array();
  for (const double t1 : {105.0, 115.0, 125.0}) {
    for (const double t2 : {55.0, 65.0, 75.0, 85.0}) {
      const double b1x = l1 * std::cos(t1 * kPi / 180), b1y = l1 * std::sin(t1 * kPi / 180);
      const double b2x = a + l1 * std::cos(t2 * kPi / 180), b2y = l1 * std::sin(t2 * kPi / 180);
      // E: the upper intersection of the circles of radius l2 about B1 and B2.
      const double dx = b2x - b1x, dy = b2y - b1y, d = std::hypot(dx, dy);
      const double h = std::sqrt(l2 * l2 - d * d / 4);
      const double ex = b1x + dx / 2 - h * dy / d, ey = b1y + dy / 2 + h * dx / d;
      const json b1 = {b1x, b1y, 0.0}, b2 = {b2x, b2y, 0.0}, e = {ex, ey, 0.0};
      cases.push_back({{"id", std::string("t1=").append(std::to_string(static_cast<int>(t1)))
                                  .append("_t2=").append(std::to_string(static_cast<int>(t2)))},
                       {"parameters", {{"theta1_deg", t1}, {"theta2_deg", t2}}},
                       {"set",
                        {{"/nodes/4/xyz", b1}, {"/nodes/5/xyz", b1}, {"/nodes/6/xyz", b2}, {"/nodes/7/xyz", b2},
                         {"/nodes/8/xyz", e}, {"/nodes/9/xyz", e}}}});
    }
  }
  json base = json::parse(std::ifstream(std::string(BEAMFEA_SOURCE_DIR "/examples/08_five_bar_lumped_vs_beam/models/") + model));
  base["analyses"] = {json{{"id", "K"}, {"type", "stiffness"}, {"node", "E"}}};
  return {{"model", base},
          {"cases", cases},
          {"outputs",
           {json{{"name", "K"}, {"path", "analyses.K.matrix"}}, json{{"name", "rigid"}, {"path", "analyses.K.rigid_directions"}},
            json{{"name", "redundant"}, {"path", "analyses.K.statically_indeterminate"}}}}};
}

struct Passes {
  long warm_pass_allocations = 0;
  std::vector<std::string> warm_rows;   // each case's row of the warm pass
  std::vector<std::string> fresh_rows;  // the same case run on fresh storage
};

// A CSV row without its last cell (wall_time_s).
std::string without_wall_time(const std::string& row) { return row.substr(0, row.rfind(',')); }

// Two passes over the cases on one workspace (as the inline `--jobs 1` loop), the second counted.
Passes run_twice(const Sweep& sweep) {
  Passes p;
  const SweepCaseResult first = beamfea::run_sweep_case(sweep, 0);  // the probe: the table's columns
  const beamfea::SweepColumns columns = beamfea::sweep_columns(sweep, &first);
  beamfea::SweepWorkspace workspace(sweep);
  SweepCaseResult result;
  std::string rows;
  rows.reserve(1 << 20);
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    beamfea::run_sweep_case(sweep, i, {}, workspace, result);
    beamfea::append_sweep_row(rows, sweep, i, columns, result);
  }
  std::vector<std::size_t> ends(sweep.size());
  rows.clear();
  const long before = g_allocations.load();
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    beamfea::run_sweep_case(sweep, i, {}, workspace, result);
    beamfea::append_sweep_row(rows, sweep, i, columns, result);
    ends[i] = rows.size();
  }
  p.warm_pass_allocations = g_allocations.load() - before;
  for (std::size_t i = 0, start = 0; i < sweep.size(); start = ends[i++]) {
    p.warm_rows.push_back(without_wall_time(rows.substr(start, ends[i] - start)));
    const SweepCaseResult fresh = beamfea::run_sweep_case(sweep, i);
    EXPECT_EQ(fresh.status, SweepCaseResult::Status::Succeeded) << "case " << i << ": " << fresh.message;
    p.fresh_rows.push_back(without_wall_time(beamfea::sweep_row(sweep, i, columns, fresh)));
  }
  return p;
}

TEST(SweepAllocations, AChainStiffnessCaseAllocatesNothingOnceTheWorkspaceIsWarm) {
  const Sweep sweep = beamfea::read_sweep(chain_sweep(), BEAMFEA_SOURCE_DIR);
  ASSERT_EQ(sweep.size(), 27u);
  const Passes p = run_twice(sweep);
  EXPECT_EQ(p.warm_pass_allocations, 0) << "operator new calls over 27 warm cases";
  EXPECT_EQ(p.warm_rows, p.fresh_rows);  // CSV rows: every number written in full (17 digits)
}

TEST(SweepAllocations, ALoadSweepCaseAllocatesNothingOnceTheWorkspaceIsWarm) {
  const Sweep sweep = beamfea::read_sweep(load_sweep(), BEAMFEA_SOURCE_DIR "/examples/04_load_sweep");
  ASSERT_EQ(sweep.size(), 11u);
  const Passes p = run_twice(sweep);
  EXPECT_EQ(p.warm_pass_allocations, 0) << "operator new calls over 11 warm cases";
  EXPECT_EQ(p.warm_rows, p.fresh_rows);
}

TEST(SweepAllocations, AWorkspaceMapCaseAllocatesNothingOnceTheWorkspaceIsWarm) {
  const Sweep sweep =
      beamfea::read_sweep(workspace_map_sweep(), BEAMFEA_SOURCE_DIR "/examples/03_workspace_stiffness_map");
  ASSERT_EQ(sweep.size(), 12u);
  const Passes p = run_twice(sweep);
  EXPECT_EQ(p.warm_pass_allocations, 0) << "operator new calls over 12 warm cases";
  EXPECT_EQ(p.warm_rows, p.fresh_rows);
}

TEST(SweepAllocations, APatchedCaseAllocatesNothingOnceTheWorkspaceIsWarm) {
  // Patches are applied to the worker's document in place and undone (not a copy of the whole
  // document per case).
  const Sweep sweep = beamfea::read_sweep(chain_patch_sweep(), BEAMFEA_SOURCE_DIR);
  ASSERT_EQ(sweep.size(), 3u);
  const Passes p = run_twice(sweep);
  EXPECT_EQ(p.warm_pass_allocations, 0) << "operator new calls over 3 warm cases";
  EXPECT_EQ(p.warm_rows, p.fresh_rows);
}

TEST(SweepAllocations, AFiveBarPoseCaseAllocatesNothingOnceTheWorkspaceIsWarm) {
  // A closed loop: the DofMap's elimination of the loop-closing joint is rebuilt for every pose.
  for (const char* model : {"beam.json", "lumped.json"}) {
    const Sweep sweep = beamfea::read_sweep(five_bar_sweep(model), BEAMFEA_SOURCE_DIR);
    ASSERT_EQ(sweep.size(), 12u);
    const Passes p = run_twice(sweep);
    EXPECT_EQ(p.warm_pass_allocations, 0) << model << ": operator new calls over 12 warm cases";
    EXPECT_EQ(p.warm_rows, p.fresh_rows) << model;
    // The rigid body model is over-constrained out of its plane: three redundant rows of the loop,
    // named in each row (the beams' loop has none).
    const bool lumped = std::string(model) == "lumped.json";
    for (const std::string& row : p.warm_rows)
      EXPECT_EQ(row.find("joint 'pE'") != std::string::npos, lumped) << model << ": " << row;
  }
}

}  // namespace sweep_allocations_test
