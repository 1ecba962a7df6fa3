#pragma once
// analyses.<id>.solver of the eigen-analyses (modal, buckling): which eigen-solver ran.
//   {"type": "direct" | "iterative", "iterations": n, "linear_iterations": m (iterative only),
//    "residual": r}
// iterations: 1 for the direct solver; SLEPc's outer (Krylov-Schur) iterations for the iterative
// one, whose inner linear iterations add up to linear_iterations (0 where PETSc factorised the
// shifted matrix). residual: the largest relative eigen-residual over the returned pairs,
// computed from the vectors (solvers/slepc_eigen.hpp, relative_eigen_residual).
#include "io/analysis.hpp"
#include "solvers/slepc_eigen.hpp"

namespace beamfea {

ojson eigen_solver_json(const EigenSolverReport& report);

}  // namespace beamfea
