// bench_iterative_solve: the direct solver against PETSc's conjugate gradients on the generated
// cube frames of bench_frame_solve (benchmarks/frame_models.hpp), for docs/analyses/solver.md:
//   direct      LinearSystem with "solver": {"type": "direct"}: assembly, CHOLMOD's factorisation,
//               one solve (the whole linear_static solve, results aside)
//   gamg        the same with "iterative" (GAMG given the six rigid-body modes of the nodes, and
//               the matrix's block size 6 where the free DOFs are whole nodes: it aggregates nodes)
//   gamg-dofs   PETSc's GAMG on the same K_ff with the rigid-body modes but no block size (it
//               aggregates single DOFs), set up and solved alone
//   gamg-bare   the same without the rigid-body modes (its default near null space, the constant
//               vector)
//   hypre       "iterative" with "preconditioner": "hypre"
// Each row: free DOFs, wall seconds of each and the CG iterations to rtol 1e-8 (the issue's
// large-model tolerance). Wall time on this machine, one process.
//
// Usage: bench_iterative_solve [--sizes 3000,30000,...]  (element targets, cube frames)
//                              [--rtol 1e-8] [--skip direct,gamg-dofs,gamg-bare,hypre]
#include <fmt/format.h>

#include <chrono>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "core/assembly.hpp"
#include "frame_models.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/near_null_space.hpp"
#include "solvers/petsc_solver.hpp"
#include "solvers/structure.hpp"

using namespace beamfea;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct Run {
  double seconds = 0.0;
  int iterations = 0;
  double residual = 0.0;
};

Run linear_static(Model m, SolverChoice::Type type, SolverChoice::Preconditioner pc, double rtol) {
  m.solver.type = type;
  m.solver.preconditioner = pc;
  m.solver.rtol = rtol;
  const auto t0 = std::chrono::steady_clock::now();
  const LinearSystem system(m);
  const LinearStaticResult r = system.solve(m.default_loads());
  Run out{seconds_since(t0), r.solver.iterations, r.solver.residual};
  if (r.status != SolveStatus::Succeeded) fmt::print(stderr, "  failed: {}\n", r.message);
  return out;
}

// GAMG on K_ff alone, with or without the rigid-body modes, without a block size (the assembly
// is not timed).
Run gamg_alone(const Model& m, double rtol, bool with_modes, const char* what) {
  const DofMap map(m);
  const LinearStructure structure(m);
  SystemAssembler assembler(map);
  structure.assemble_stiffness(map, assembler);
  const Eigen::VectorXd f = map.reduce(external_force(m, map));
  const auto t0 = std::chrono::steady_clock::now();
  PetscSolver cg(IterativeOptions{.rtol = rtol});
  if (with_modes) cg.set_near_null_space(rigid_body_modes(m, map));
  cg.compute(assembler.K_ff());
  Eigen::VectorXd u(f.size());
  cg.solve(f, u);
  if (!cg.last_solve().converged()) fmt::print(stderr, "  {}: {}\n", what, cg.last_solve().reason);
  Run out{seconds_since(t0), cg.last_solve().iterations, 0.0};
  Eigen::VectorXd r = f - assembler.K_ff() * u;
  out.residual = r.norm() / f.norm();
  return out;
}

std::vector<long> parse_list(const char* s) {
  std::vector<long> v;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) v.push_back(std::stol(item));
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<long> sizes{3'000, 30'000};
  double rtol = 1e-8;
  std::string skip;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--sizes")) sizes = parse_list(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--rtol")) rtol = std::stod(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--skip")) skip = argv[i + 1];
    else {
      fmt::print(stderr, "unknown option {}\n", argv[i]);
      return 2;
    }
  }
  const auto skipped = [&](const char* what) { return skip.find(what) != std::string::npos; };
  fmt::print("| frame | free DOFs | direct s | GAMG, nodes + modes s (its.) | GAMG, DOFs + modes s (its.) | "
             "GAMG bare s (its.) | hypre s (its.) |\n");
  fmt::print("|---|---:|---:|---:|---:|---:|---:|\n");
  for (const long target : sizes) {
    const bench::Dims d = bench::choose_dims(target);
    const Model m = bench::make_frame(d);
    const DofMap map(m);
    const int free_dofs = map.free_size();
    fmt::print(stderr, "{}x{}x{}: {} free DOFs, block size {}\n", d.nx, d.ny, d.nz, free_dofs, node_block_size(map));
    using T = SolverChoice::Type;
    using P = SolverChoice::Preconditioner;
    const Run direct = skipped("direct") ? Run{} : linear_static(m, T::Direct, P::Gamg, rtol);
    const Run gamg = linear_static(m, T::Iterative, P::Gamg, rtol);
    const Run dofs = skipped("gamg-dofs") ? Run{} : gamg_alone(m, rtol, true, "gamg-dofs");
    const Run bare = skipped("gamg-bare") ? Run{} : gamg_alone(m, rtol, false, "gamg-bare");
    const Run hypre = skipped("hypre") ? Run{} : linear_static(m, T::Iterative, P::Hypre, rtol);
    fmt::print("| {}x{}x{} | {} | {:.2f} | {:.2f} ({}) | {:.2f} ({}) | {:.2f} ({}) | {:.2f} ({}) |\n", d.nx, d.ny,
               d.nz, free_dofs, direct.seconds, gamg.seconds, gamg.iterations, dofs.seconds, dofs.iterations,
               bare.seconds, bare.iterations, hypre.seconds, hypre.iterations);
    std::fflush(stdout);
  }
  finalize_petsc();
  return 0;
}
