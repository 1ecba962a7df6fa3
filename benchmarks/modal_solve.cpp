// bench_modal_solve: the lowest modes of the regular 3-D space frames of bench_frame_solve
// (benchmarks/frame_solve.cpp: 6 m x 6 m x 3.5 m bays, HEB 300-like columns, IPE 400-like beams,
// base fixed, nx = ny = nz), now with steel's density (7850 kg/m^3), against one linear static
// solve of the same frame in the same process.
//
// Timed (wall and process CPU), each the whole library call as an analysis runs it:
//   linear   solve_linear_static (DofMap, assembly, CHOLMOD analysis + factorisation, solve,
//            reactions and end forces)
//   modal    solve_modal with `--modes` modes (DofMap, K and M assembly, CHOLMOD factorisation of
//            K - sigma M, shift-invert Lanczos, purification, participation factors)
//
// Usage: bench_modal_solve [--sizes 10000,30000] [--modes 10]   (sizes: element targets)
// Output: a Markdown table on stdout, progress on stderr.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/model.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/modal.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

struct Stopwatch {
  Clock::time_point wall0 = Clock::now();
  double cpu0 = cpu_seconds();
  double wall() const { return std::chrono::duration<double>(Clock::now() - wall0).count(); }
  double cpu() const { return cpu_seconds() - cpu0; }
};

double load_average() {
  std::ifstream in("/proc/loadavg");
  double one = 0.0;
  in >> one;
  return one;
}

// The frame of bench_frame_solve (same dimensions, sections, supports and loads).
struct Dims {
  int nx = 1, ny = 1, nz = 1;
  long elements() const { return long(nz) * (long(nx + 1) * (ny + 1) + long(nx) * (ny + 1) + long(nx + 1) * ny); }
};

Dims choose_dims(long target) {
  Dims best;
  long best_err = -1;
  for (int nx = 1; nx <= 4000; ++nx)
    for (int dy = 0; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        Dims d{nx, nx + dy, nx + dz};
        if (d.nz < 1) continue;
        const long err = std::labs(d.elements() - target);
        if (best_err < 0 || err < best_err) {
          best_err = err;
          best = d;
        }
      }
  return best;
}

beamfea::Model make_frame(const Dims& d) {
  using namespace beamfea;
  Model m;
  m.materials.push_back({"steel", 2.1e11, 8.1e10, 7850.0});
  m.sections.push_back({"column", 1.49e-2, 2.517e-4, 0.8563e-4, 1.85e-6, 0.0, 0.0});
  m.sections.push_back({"beam", 8.45e-3, 2.313e-4, 1.318e-5, 5.1e-7, 0.0, 0.0});
  auto node = [&](int i, int j, int k) { return i + (d.nx + 1) * (j + (d.ny + 1) * k); };
  for (int k = 0; k <= d.nz; ++k)
    for (int j = 0; j <= d.ny; ++j)
      for (int i = 0; i <= d.nx; ++i)
        m.nodes.push_back({std::to_string(m.nodes.size()), Vec3(6.0 * i, 6.0 * j, 3.5 * k), -1});
  auto element = [&](int a, int b, int section, const Vec3& orientation) {
    Element e;
    e.id = std::to_string(m.elements.size());
    e.type = MemberType::Beam;
    e.nodes = {a, b};
    e.material = 0;
    e.section = section;
    e.orientation = orientation;
    m.elements.push_back(std::move(e));
  };
  for (int k = 1; k <= d.nz; ++k) {
    for (int j = 0; j <= d.ny; ++j)
      for (int i = 0; i <= d.nx; ++i) element(node(i, j, k - 1), node(i, j, k), 0, Vec3::UnitX());
    for (int j = 0; j <= d.ny; ++j)
      for (int i = 0; i < d.nx; ++i) element(node(i, j, k), node(i + 1, j, k), 1, Vec3::UnitZ());
    for (int j = 0; j < d.ny; ++j)
      for (int i = 0; i <= d.nx; ++i) element(node(i, j, k), node(i, j + 1, k), 1, Vec3::UnitZ());
  }
  for (int j = 0; j <= d.ny; ++j)
    for (int i = 0; i <= d.nx; ++i) {
      Support s;
      s.node = node(i, j, 0);
      s.fixed.fill(true);
      m.supports.push_back(s);
    }
  for (int n = (d.nx + 1) * (d.ny + 1); n < static_cast<int>(m.nodes.size()); ++n)
    m.loads.push_back({n, Vec3(1e3, 0.5e3, -10e3), Vec3::Zero()});
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<long> sizes{10000, 30000};
  int modes = 10;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc) {
      sizes.clear();
      std::stringstream ss(argv[++i]);
      std::string s;
      while (std::getline(ss, s, ',')) sizes.push_back(std::atol(s.c_str()));
    } else if (!std::strcmp(argv[i], "--modes") && i + 1 < argc) {
      modes = std::atoi(argv[++i]);
    } else {
      fmt::print(stderr, "usage: bench_modal_solve [--sizes 10000,30000] [--modes 10]\n");
      return 2;
    }
  }
  fmt::print("| bays | elements | free DOFs | linear solve s (CPU s) | {} modes s (CPU s) | modal / linear (wall) | f1 Hz | f{} Hz | load avg |\n", modes, modes);
  fmt::print("|---|---|---|---|---|---|---|---|---|\n");
  for (long target : sizes) {
    const Dims d = choose_dims(target);
    const beamfea::Model m = make_frame(d);
    fmt::print(stderr, "{}x{}x{} bays, {} elements: linear...\n", d.nx, d.ny, d.nz, m.elements.size());
    Stopwatch sl;
    const beamfea::LinearStaticResult lin = beamfea::solve_linear_static(m);
    const double lw = sl.wall(), lc = sl.cpu();
    fmt::print(stderr, "  {} ({:.2f} s); modal...\n", lin.message, lw);
    beamfea::ModalOptions o;
    o.modes = modes;
    Stopwatch sm;
    const beamfea::ModalResult r = beamfea::solve_modal(m, o);
    const double mw = sm.wall(), mc = sm.cpu();
    fmt::print(stderr, "  {} ({:.2f} s)\n", r.message, mw);
    const auto nf = r.frequencies.size();
    fmt::print("| {}x{}x{} | {} | {} | {:.2f} ({:.2f}) | {:.2f} ({:.2f}) | {:.1f} | {:.4g} | {:.4g} | {:.1f} |\n", d.nx, d.ny,
               d.nz, m.elements.size(), lin.free_dofs, lw, lc, mw, mc, mw / lw, nf ? r.frequencies[0] : 0.0,
               nf ? r.frequencies[nf - 1] : 0.0, load_average());
    std::fflush(stdout);
  }
  return 0;
}
