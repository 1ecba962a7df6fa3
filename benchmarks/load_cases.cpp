// Many load cases on one model: N cases solved against one factorisation (LinearSystem) against
// N separate runs (solve_linear_static: assemble, factorise, solve, each time).
//
//   OPENBLAS_NUM_THREADS=1 bench_load_cases [--cube n] [--cases N1,N2,...]
// (one BLAS thread: on a shared, oversubscribed machine OpenBLAS's threads spin against other
// processes and make the triangular solves erratic)
// Model: an n x n x n frame of 6 m bays and 3.5 m storeys (steel columns and beams, divisions 1,
// base fixed); case k: self-weight times (1 + k/10), a uniform load on every beam and a
// horizontal force at every floor node, both varying with k. Prints one markdown table row per N.
#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_blas.hpp"
#include "solvers/linear_static.hpp"

using namespace beamfea;
using Clock = std::chrono::steady_clock;

namespace {

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

Model make_frame(int n) {
  Model m;
  Material steel;
  steel.id = "steel";
  steel.E = 2.1e11;
  steel.G = 8.1e10;
  steel.density = 7850.0;
  m.materials.push_back(steel);
  m.sections.push_back({"column", 1.49e-2, 2.517e-4, 0.8563e-4, 1.85e-6, 0.0, 0.0});
  m.sections.push_back({"beam", 8.45e-3, 2.313e-4, 1.318e-5, 5.1e-7, 0.0, 0.0});
  auto node = [&](int i, int j, int k) { return i + (n + 1) * (j + (n + 1) * k); };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        m.nodes.push_back({std::to_string(m.nodes.size()), Vec3(6.0 * i, 6.0 * j, 3.5 * k), -1});
  auto member = [&](int a, int b, int section, const Vec3& o) {
    Member mem;
    mem.id = std::to_string(m.members.size());
    mem.nodes = {a, b};
    mem.material = 0;
    mem.section = section;
    mem.orientation = o;
    mem.elements = {static_cast<int>(m.elements.size())};
    Element e;
    e.id = mem.id;
    e.nodes = {a, b};
    e.material = 0;
    e.section = section;
    e.orientation = o;
    e.member = static_cast<int>(m.members.size());
    m.members.push_back(mem);
    m.elements.push_back(e);
  };
  for (int k = 1; k <= n; ++k) {
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) member(node(i, j, k - 1), node(i, j, k), 0, Vec3::UnitX());
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i < n; ++i) member(node(i, j, k), node(i + 1, j, k), 1, Vec3::UnitZ());
    for (int j = 0; j < n; ++j)
      for (int i = 0; i <= n; ++i) member(node(i, j, k), node(i, j + 1, k), 1, Vec3::UnitZ());
  }
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      Support s;
      s.node = node(i, j, 0);
      s.fixed.fill(true);
      m.supports.push_back(s);
    }
  return m;
}

LoadSet load_case(const Model& m, int k) {
  LoadSet s;
  s.gravity = Vec3(0, 0, -9.81 * (1.0 + 0.1 * k));
  for (std::size_t b = 0; b < m.members.size(); ++b) {
    const Vec3 d = m.nodes[m.members[b].nodes[1]].x - m.nodes[m.members[b].nodes[0]].x;
    if (std::abs(d.z()) > 0.0) continue;  // beams only
    MemberLoad l;
    l.member = static_cast<int>(b);
    l.q_from = l.q_to = Vec3(0, 0, -5e3 * (1.0 + 0.05 * k));
    s.member.push_back(l);
  }
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    if (m.nodes[i].x.z() > 0.0) s.nodal.push_back({static_cast<int>(i), Vec3(1e3 * (k % 3), 1e3 * ((k + 1) % 3), 0), Vec3::Zero()});
  return s;
}

std::string load_average() {
  std::ifstream f("/proc/loadavg");
  std::string a;
  f >> a;
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  fmt::print(stderr, "BLAS: {}\n", beamfea::bench::choose_libraries_as_the_program());  // as `beamfea` runs
  int cube = 10;
  std::vector<int> counts{1, 4, 16};
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--cube") cube = std::atoi(v.c_str());
    else if (k == "--cases") {
      counts.clear();
      std::stringstream ss(v);
      std::string t;
      while (std::getline(ss, t, ',')) counts.push_back(std::atoi(t.c_str()));
    }
  }
  const Model m = make_frame(cube);
  fmt::print("cube {}: {} nodes, {} elements, load average {}\n\n", cube, m.nodes.size(), m.elements.size(), load_average());
  fmt::print("| free DOFs | cases N | N separate runs (s) | one factorisation + N solves (s) | of which assembly + factorisation (s) | ratio |\n|---|---|---|---|---|---|\n");
  for (int N : counts) {
    std::vector<LoadSet> cases;
    for (int k = 0; k < N; ++k) cases.push_back(load_case(m, k));
    double check = 0.0;
    auto t0 = Clock::now();
    int free = 0;
    for (int k = 0; k < N; ++k) {
      Model mk = m;
      mk.set_default_loads(cases[k]);
      const auto r = solve_linear_static(mk);
      free = r.free_dofs;
      check += r.u.cwiseAbs().maxCoeff();
    }
    const double separate = since(t0);
    t0 = Clock::now();
    const LinearSystem sys(m);
    const double factor = since(t0);
    for (int k = 0; k < N; ++k) check -= sys.solve(cases[k]).u.cwiseAbs().maxCoeff();
    const double shared = since(t0);
    if (std::abs(check) > 1e-9) fmt::print("warning: results differ ({:.3g})\n", check);
    fmt::print("| {} | {} | {:.3f} | {:.3f} | {:.3f} | {:.2f} |\n", free, N, separate, shared, factor, separate / shared);
    std::fflush(stdout);
  }
  return 0;
}
