// bench_closed_loop_step: cost of a path step on a closed-loop lumped model against the same model
// opened at one joint (the aim: within 1.5x).
//
// The model: a planar arch of two chains of n rigid links each, from the ground pivots A = (0, 0, 0)
// and B = (2, 0, 0) up to the crown C = (1, 1, 0), with a revolute spring about z (k = 100) at every
// joint between links and at both pivots (3-D model, parallel axes). Closed: the two chains are joined
// at the crown by a passive revolute joint; the loop closes there (a joint closure, six rows of which
// three are redundant). Opened: that joint is removed (two cantilevered chains, same coordinates, no
// closure). A load (0.5, -1, 0) at the crown node of the first chain, load control to 1 in `steps`
// equal increments with stability (inertia and lowest eigenvalue) at every step. Reported: the free
// coordinates, closure rows kept, mean time per step of follow_path and Newton iterations per step,
// the best of `reps` runs, and the ratio closed / opened.
// Usage: bench_closed_loop_step [--sizes 10,20,40,80] [--steps 5] [--reps 3] [--load 1] (a factor on the load)
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "bench_blas.hpp"
#include "solvers/path_following.hpp"

using namespace beamfea;

namespace {

Model arch(int n, bool closed, double load) {
  Model m;
  const Vec3 A(0, 0, 0), B(2, 0, 0), C(1, 1, 0);
  auto node = [&](const std::string& id, const Vec3& x) {
    m.nodes.push_back({id, x, -1});
    return static_cast<int>(m.nodes.size()) - 1;
  };
  auto joint = [&](const std::string& id, int a, int b, double k) {
    Joint j;
    j.id = id;
    j.type = JointType::Revolute;
    j.nodes = {a, b};
    j.axes = {Vec3::UnitZ()};
    j.stiffness = {k};
    m.joints.push_back(j);
  };
  auto rigid = [&](const std::string& id, int a, int b) {
    Element e;
    e.id = id;
    e.type = MemberType::Rigid;
    e.nodes = {a, b};
    m.elements.push_back(e);
  };
  std::vector<int> tips;
  for (int c = 0; c < 2; ++c) {
    const Vec3 from = c == 0 ? A : B;
    int prev = node(fmt::format("g{}", c), from);
    Support s;
    s.node = prev;
    s.fixed.fill(true);
    m.supports.push_back(s);
    for (int i = 0; i < n; ++i) {
      const Vec3 x0 = from + (C - from) * (double(i) / n), x1 = from + (C - from) * (double(i + 1) / n);
      const int a = node(fmt::format("c{}_{}a", c, i), x0);
      joint(fmt::format("j{}_{}", c, i), prev, a, 100.0);
      prev = node(fmt::format("c{}_{}", c, i + 1), x1);
      rigid(fmt::format("l{}_{}", c, i), a, prev);
    }
    tips.push_back(prev);
  }
  if (closed) joint("crown", tips[0], tips[1], 0.0);
  m.default_case.nodal.push_back({tips[0], load * Vec3(0.5, -1.0, 0.0), Vec3::Zero()});
  return m;
}

struct Run {
  double ms_per_step = 0.0, iterations = 0.0;
  int free = 0;
  bool ok = false;
};

bool verbose = false;

Run run(const Model& m, int steps, int reps) {
  Run best;
  best.ms_per_step = 1e300;
  for (int r = 0; r < reps; ++r) {
    PathOptions o;
    o.target = 1.0;
    o.increments = steps;
    if (verbose) o.progress = [](const std::string& s) { fmt::print(stderr, "  {}\n", s); };
    const auto t0 = std::chrono::steady_clock::now();
    const PathResult res = follow_path(m, o);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const int n = static_cast<int>(res.steps.size()) - 1;
    if (!res.completed || n <= 0) return best;
    long it = 0;
    for (const auto& s : res.steps) it += s.iterations;
    if (ms / n < best.ms_per_step) {
      best.ms_per_step = ms / n;
      best.iterations = double(it) / n;
    }
    best.free = res.free_dofs;
    best.ok = true;
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  fmt::print(stderr, "BLAS: {}\n", beamfea::bench::choose_libraries_as_the_program());  // as `beamfea` runs
  std::vector<int> sizes{10, 20, 40, 80};
  int steps = 5, reps = 3;
  double load = 1.0;
  for (int i = 1; i + 1 < argc; ++i) {
    if (!std::strcmp(argv[i], "--sizes")) {
      sizes.clear();
      std::stringstream ss(argv[++i]);
      std::string t;
      while (std::getline(ss, t, ',')) sizes.push_back(std::stoi(t));
    } else if (!std::strcmp(argv[i], "--steps")) {
      steps = std::stoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--load")) {
      load = std::stod(argv[++i]);
    } else if (!std::strcmp(argv[i], "--verbose")) {
      verbose = std::stoi(argv[++i]) != 0;
    } else if (!std::strcmp(argv[i], "--reps")) {
      reps = std::stoi(argv[++i]);
    }
  }
  fmt::print("| links per chain | free coordinates | closed [ms/step] | it./step | opened [ms/step] | it./step | closed / opened |\n");
  fmt::print("|---|---|---|---|---|---|---|\n");
  for (int n : sizes) {
    const Run c = run(arch(n, true, load), steps, reps), o = run(arch(n, false, load), steps, reps);
    if (!c.ok || !o.ok) {
      fmt::print("| {} | failed: closed {} opened {} | | | | | |\n", n, c.ok, o.ok);
      continue;
    }
    fmt::print("| {} | {} | {:.2f} | {:.1f} | {:.2f} | {:.1f} | {:.2f} |\n", n, c.free, c.ms_per_step, c.iterations, o.ms_per_step,
               o.iterations, c.ms_per_step / o.ms_per_step);
  }
  return 0;
}
