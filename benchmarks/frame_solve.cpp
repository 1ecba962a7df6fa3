// bench_frame_solve: timing and peak memory of beamfea's linear static pipeline on a regular
// 3-D space frame, with baselines in the same process.
//
// The frame: nx x ny x nz bays (6 m x 6 m x 3.5 m), a column on every grid point of every
// storey, beams along x and y at every floor, all base nodes fixed in 6 DOF, every other node
// loaded by (1, 0.5, -10) kN. nx = ny = nz by default (a cube: the hardest shape for a direct
// solver, since nested-dissection separators grow as n^2); `--stories S` fixes nz = S instead
// (a building), which makes the fill nearly two-dimensional.
//
// Stages timed, in the order the library runs them (solvers/linear_static.cpp):
//   model      generating the Model (not part of the library; for scale)
//   dofmap     DofMap construction (numbering, constraint elimination: none here)
//   elements   LinearStructure construction (12x12 global stiffness of every beam)
//   asm1       first SystemAssembler pass: triplets, CSC pattern, positions
//   asm2       second pass over the same calls: values written through the stored positions
//   symbolic   CHOLMOD analysis (ordering + supernodal symbolic factorisation)
//   numeric    CHOLMOD supernodal numeric factorisation
//   solve      forward/back substitution for one right-hand side
// The factorisation is that of solvers/sparse_factor.cpp: CholmodSupernodalLLT (Eigen's
// defaults) on the Jacobi-scaled S K S, timed stage by stage. The library's SparseFactor is then
// run too (analysis and factorisation in one call, plus its scaling and condition estimate) where
// the numeric stage took less than `--library-path-max-s`, and its solution is the one checked:
// relative residual |K u - f| / |f| and |sum of base reactions + sum of loads| / |sum of loads|,
// the reactions obtained as the library does (DofMap::constraint_forces).
//
// Baselines in the same process: Eigen's setFromTriplets assembly (direct raw -> free indices,
// valid here since the frame has no constraints) against the pattern-reusing pass; Eigen's
// SimplicialLDLT (AMD ordering) against CHOLMOD, for sizes where CHOLMOD's flop count says it
// is affordable (`--max-simplicial-gflop`).
//
// Peak memory per size: each size runs in a fresh child process (the program re-executes
// itself with --single N); the child reports VmHWM after assembly and after the library path
// (before the baselines), the parent the child's ru_maxrss from wait4 (whole run, baselines
// included).
//
// Usage: bench_frame_solve [--sizes 1000,10000,100000,1000000] [--stories S] [--repeat R]
//                          [--max-gflop G] [--max-simplicial-gflop G] [--mem-margin-gb M]
//                          [--library-path-max-s T] [--ordering default|amd|metis|nesdis|metis+nesdis]
//                          [--settle-s S]  (pause before each of the two compared timings, default 3)
// Output: Markdown tables on stdout, progress on stderr.
//
// The child's stages are frame_solve_stages.hpp, the parent's runs and tables frame_solve_report.hpp.
#include <fmt/format.h>

#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "bench_blas.hpp"
#include "frame_solve_report.hpp"
#include "frame_solve_stages.hpp"

namespace {

using beamfea::bench::frame_solve::Options;
using beamfea::bench::frame_solve::run_all;
using beamfea::bench::frame_solve::run_single;

std::vector<long> parse_sizes(const std::string& s) {
  std::vector<long> v;
  std::istringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) v.push_back(static_cast<long>(std::atof(item.c_str())));
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string kernels = beamfea::bench::choose_libraries_as_the_program();  // as `beamfea` runs
  Options o;
  long single = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        fmt::print(stderr, "{} needs a value\n", a);
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--single") single = static_cast<long>(std::atof(next().c_str()));
    else if (a == "--sizes") o.sizes = parse_sizes(next());
    else if (a == "--stories") o.stories = std::atoi(next().c_str());
    else if (a == "--repeat") o.repeat = std::atoi(next().c_str());
    else if (a == "--max-gflop") o.max_gflop = std::atof(next().c_str());
    else if (a == "--max-simplicial-gflop") o.max_simplicial_gflop = std::atof(next().c_str());
    else if (a == "--mem-margin-gb") o.mem_margin_gb = std::atof(next().c_str());
    else if (a == "--library-path-max-s") o.library_path_max_s = std::atof(next().c_str());
    else if (a == "--settle-s") o.settle_s = std::atof(next().c_str());
    else if (a == "--ordering") {
      o.ordering = next();
      if (o.ordering != "default" && o.ordering != "amd" && o.ordering != "metis" && o.ordering != "nesdis" &&
          o.ordering != "metis+nesdis") {
        fmt::print(stderr, "--ordering: default, amd, metis, nesdis or metis+nesdis\n");
        return 2;
      }
    }
    else if (a == "--nrelax") o.nrelax = next();
    else if (a == "--zrelax") o.zrelax = next();
    else {
      fmt::print(stderr,
                 "usage: {} [--nrelax a,b,c] [--zrelax x,y,z] [--sizes N1,N2,...] [--stories S] [--repeat R] [--max-gflop G] "
                 "[--max-simplicial-gflop G] [--mem-margin-gb M] [--library-path-max-s T] [--ordering O] [--settle-s S] [--single N]\n",
                 argv[0]);
      return a == "--help" || a == "-h" ? 0 : 2;
    }
  }
  try {
    return single > 0 ? run_single(single, o) : run_all(argv[0], o, kernels);
  } catch (const std::exception& e) {
    fmt::print(stderr, "bench_frame_solve: {}\n", e.what());
    return 1;
  }
}
