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

#include "bench_blas.hpp"
#include "bench_timing.hpp"
#include "frame_models.hpp"
#include "core/model.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/modal.hpp"

namespace {

using beamfea::bench::Stopwatch;

double load_average() {
  std::ifstream in("/proc/loadavg");
  double one = 0.0;
  in >> one;
  return one;
}

// The frame of bench_frame_solve (benchmarks/frame_models.hpp) with steel's density.
using beamfea::bench::choose_dims;
using beamfea::bench::Dims;
constexpr double kSteelDensity = 7850.0;

}  // namespace

int main(int argc, char** argv) {
  fmt::print(stderr, "BLAS: {}\n", beamfea::bench::choose_libraries_as_the_program());  // as `beamfea` runs
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
    const beamfea::Model m = beamfea::bench::make_frame(d, kSteelDensity);
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
