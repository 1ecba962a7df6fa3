#include "solvers/solver_choice.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace beamfea {

bool solves_iteratively(const SolverChoice& choice, int free_dofs) {
  if (free_dofs == 0) return false;  // nothing to iterate on
  switch (choice.type) {
    case SolverChoice::Type::Direct: return false;
    case SolverChoice::Type::Iterative: return true;
    case SolverChoice::Type::Auto: return petsc_available() && free_dofs >= kAutoIterativeMinDofs;
  }
  return false;
}

SolverChoice::Preconditioner resolve_preconditioner(SolverChoice::Preconditioner p) {
  if (p != SolverChoice::Preconditioner::Default) return p;
  return petsc_available() && petsc_has_hypre() ? SolverChoice::Preconditioner::Hypre : SolverChoice::Preconditioner::Gamg;
}

IterativeOptions iterative_options(const SolverChoice& choice) {
  IterativeOptions o;
  o.rtol = choice.rtol;
  o.max_iterations = choice.max_iterations;
  o.preconditioner = resolve_preconditioner(choice.preconditioner) == SolverChoice::Preconditioner::Hypre
                         ? IterativeOptions::Preconditioner::Hypre
                         : IterativeOptions::Preconditioner::Gamg;
  return o;
}

void SolverReport::add(const SolverReport& other) {
  iterative = iterative || other.iterative;
  iterations = std::max(iterations, other.iterations);
  residual = std::max(residual, other.residual);
}

double relative_residual(const SparseMatrix& K, const Eigen::VectorXd& f, const Eigen::VectorXd& u, Eigen::VectorXd& r) {
  const double fn = f.norm();
  if (!(fn > 0.0)) return 0.0;
  r = f;
  r.noalias() -= K * u;
  return r.norm() / fn;
}

SolverReport solve_to_rtol(const PetscSolver& cg, const SparseMatrix& K, const Eigen::VectorXd& f, Eigen::VectorXd& u,
                           Eigen::VectorXd& r) {
  u.resize(f.size());
  cg.solve(f, u);
  SolverReport report{.iterative = true, .iterations = cg.last_solve().iterations, .residual = relative_residual(K, f, u, r)};
  for (int k = 0; k < kMaxRestarts && cg.last_solve().converged() && report.residual > cg.options().rtol; ++k) {
    cg.refine(f, u);
    report.iterations += cg.last_solve().iterations;
    report.residual = relative_residual(K, f, u, r);
  }
  return report;
}

std::string describe_iterative(const IterativeOptions& options) {
  return fmt::format("CG with {} (rtol {:g})",
                     options.preconditioner == IterativeOptions::Preconditioner::Hypre ? "hypre's BoomerAMG" : "GAMG",
                     options.rtol);
}

}  // namespace beamfea
