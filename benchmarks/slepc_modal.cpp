// bench_slepc_modal: the lowest modes of a cube lattice frame (`"generate": {"lattice"}`, aluminium
// rods of 2 mm on a 10 mm pitch, the bottom face clamped) by modal on the direct solver (CHOLMOD's
// shift-invert Lanczos, solvers/generalized_eigen.hpp) and on SLEPc (Krylov-Schur, shift-and-invert
// with CG + GAMG and the rigid-body near null space, solvers/slepc_eigen.hpp), each the whole
// solve_modal call, in one process.
//
// Usage: bench_slepc_modal [--cells 10,20,30] [--modes 10] [--direct-max-dofs N] [--rtol 1e-8]
//   the direct solver runs up to N free DOFs (default 400000: its factor's memory).
// Output: a Markdown table on stdout (wall and process CPU seconds, their ratio, the largest
// relative difference of the frequencies, SLEPc's outer and inner iterations and residual).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench_timing.hpp"
#include "io/model_reader.hpp"
#include "solvers/modal.hpp"

namespace {

using beamfea::bench::Stopwatch;
using json = nlohmann::json;

beamfea::Model lattice(int cells) {
  json d;
  d["materials"] = json::array({{{"id", "al"}, {"E", 70e9}, {"G", 26e9}, {"density", 2700}}});
  d["sections"] = json::array({{{"id", "rod"}, {"shape", "circle"}, {"d", 0.002}}});
  d["generate"] = {{"lattice", {{"cells", {cells, cells, cells}}, {"pitch", 0.01}, {"section", "rod"}, {"material", "al"}}}};
  d["supports"] = json::array();
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) d["supports"].push_back({{"node", fmt::format("{}_{}_0", i, j)}, {"fix", "all"}});
  return beamfea::read_model(d);
}

std::vector<int> parse_list(const char* s) {
  std::vector<int> v;
  for (const char* p = s; *p;) {
    char* end = nullptr;
    v.push_back(static_cast<int>(std::strtol(p, &end, 10)));
    p = *end ? end + 1 : end;
  }
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> cells = {10, 20, 30};
  int modes = 10;
  long direct_max = 400000;
  double rtol = 1e-8;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--cells") == 0) cells = parse_list(argv[i + 1]);
    else if (std::strcmp(argv[i], "--modes") == 0) modes = std::atoi(argv[i + 1]);
    else if (std::strcmp(argv[i], "--direct-max-dofs") == 0) direct_max = std::atol(argv[i + 1]);
    else if (std::strcmp(argv[i], "--rtol") == 0) rtol = std::atof(argv[i + 1]);
  }
  fmt::print("| cells | free DOFs | direct wall s | direct CPU s | SLEPc wall s | SLEPc CPU s | SLEPc/direct (CPU) | max rel. freq. diff | outer its | linear its | SLEPc residual |\n");
  fmt::print("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const int c : cells) {
    beamfea::Model m = lattice(c);
    beamfea::ModalOptions o;
    o.modes = modes;
    m.solver.rtol = rtol;
    m.solver.type = beamfea::SolverChoice::Type::Iterative;
    Stopwatch ti;
    const beamfea::ModalResult it = beamfea::solve_modal(m, o);
    const double it_wall = ti.wall(), it_cpu = ti.cpu();
    if (it.status != beamfea::ModalStatus::Succeeded) fmt::print(stderr, "SLEPc: {}\n", it.message);
    double d_wall = NAN, d_cpu = NAN, diff = NAN;
    if (it.free_dofs <= direct_max) {
      m.solver.type = beamfea::SolverChoice::Type::Direct;
      Stopwatch td;
      const beamfea::ModalResult d = beamfea::solve_modal(m, o);
      d_wall = td.wall();
      d_cpu = td.cpu();
      diff = 0.0;
      for (Eigen::Index k = 0; k < std::min(d.frequencies.size(), it.frequencies.size()); ++k)
        diff = std::max(diff, std::abs(it.frequencies[k] - d.frequencies[k]) / d.frequencies[k]);
    }
    fmt::print("| {} | {} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {:.1e} | {} | {} | {:.1e} |\n", c, it.free_dofs, d_wall,
               d_cpu, it_wall, it_cpu, it_cpu / d_cpu, diff, it.solver.iterations, it.solver.linear_iterations,
               it.solver.residual);
    std::fflush(stdout);
  }
  return 0;
}
