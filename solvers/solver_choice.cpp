#include "solvers/solver_choice.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

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

namespace {
// relative_residual of a K that holds only this process's columns `rows` (symmetric: they are its
// rows), f right in those rows: the squared norms of those rows summed over the processes.
double distributed_relative_residual(const SparseMatrix& K, const Eigen::VectorXd& f, const Eigen::VectorXd& u,
                                     ProcessRows rows, Eigen::VectorXd& r) {
  r = f.segment(rows.first, rows.count);
  r.noalias() -= K.middleCols(rows.first, rows.count).transpose() * u;
  const double ff = sum_over_petsc_processes(f.segment(rows.first, rows.count).squaredNorm());
  const double rr = sum_over_petsc_processes(r.squaredNorm());
  return ff > 0.0 ? std::sqrt(rr / ff) : 0.0;
}
}  // namespace

SolverReport solve_to_rtol(const PetscSolver& cg, const SparseMatrix& K, const Eigen::VectorXd& f, Eigen::VectorXd& u,
                           Eigen::VectorXd& r) {
  const auto residual = [&] {
    return cg.owned_columns_only() ? distributed_relative_residual(K, f, u, cg.process_rows(), r)
                                   : relative_residual(K, f, u, r);
  };
  u.resize(f.size());
  cg.solve(f, u);
  SolverReport report{.iterative = true, .iterations = cg.last_solve().iterations, .residual = residual()};
  for (int k = 0; k < kMaxRestarts && cg.last_solve().converged() && report.residual > cg.options().rtol; ++k) {
    cg.refine(f, u);
    report.iterations += cg.last_solve().iterations;
    report.residual = residual();
  }
  return report;
}

std::string describe_iterative(const IterativeOptions& options) {
  return fmt::format("CG with {} (rtol {:g})",
                     options.preconditioner == IterativeOptions::Preconditioner::Hypre ? "hypre's BoomerAMG" : "GAMG",
                     options.rtol);
}

}  // namespace beamfea
