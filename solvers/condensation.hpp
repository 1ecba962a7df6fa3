#pragma once
// The condensation: the stiffness K_z that a structure of stiffness K (n x n, symmetric) offers
// to r independent rows A (r x n) of its coordinates,
//   1/2 z^T K_z z = min { 1/2 u^T K u : A u = z },   K_z = (A K^-1 A^T)^-1 when K is regular,
// in general minus the multiplier block M of the saddle point
//   [ K  A^T ] [ X ]   [ 0 ]
//   [ A  0   ] [ M ] = [ I ],     K_z = -M,
// which stays regular when K itself is singular, as long as holding the rows leaves the structure
// stable (a chain ending in a spherical joint).
//
// One function over the solver contract (solvers/linear_solver.hpp); dense and sparse are back-end
// choices of SolverOptions::backend:
//   Dense*     a dense, Jacobi-scaled Cholesky of K (solvers/dense_condensation.hpp): where each row
//              picks one coordinate of its own (at most six: a node whose DOFs are free DOFs of
//              their own) the static condensation onto those coordinates (Guyan 1965), else the
//              Schur complement of the rows. Mechanism when K is not positive definite or either
//              factor's reciprocal condition estimate is below singular_rcond: the dense route
//              does not see past a singular K.
//   sparse     (Cholmod, Umfpack, SimplicialLdlt) the saddle point factorised by the Umfpack back
//              end (it is indefinite), with a residual test for near singularity.
//   Automatic  the dense route for K of at most dense_max_dofs coordinates, the saddle point where
//              K is larger or the dense route declines: the arithmetic of every caller so far.
//   iterative  (condense_iteratively, the model's "solver" choosing it) X = K^-1 A^T column by
//              column by PETSc's conjugate gradients (solvers/petsc_solver.hpp) with the multigrid
//              set up once, then K_z = (A X)^-1: K must be positive definite (a K that only the
//              rows make regular is a mechanism there).
// Outcomes: Succeeded; HeldDof where a row is zero (the coordinate cannot move: its stiffness is
// unbounded); Mechanism where holding the rows still leaves a mechanism or the rows are not
// independent of the constraints. Bad input (sizes) throws.
#include <Eigen/Core>
#include <span>

#include "core/dof_map.hpp"
#include "solvers/dense_condensation.hpp"
#include "solvers/linear_solver.hpp"
#include "solvers/solver_choice.hpp"

namespace beamfea {

struct Condensation {
  enum class Outcome { Succeeded, HeldDof, Mechanism, NotConverged /* an iterative solve stopped above rtol */ };
  Outcome outcome = Outcome::Mechanism;
  Eigen::MatrixXd K;  // r x r, symmetric (Succeeded)
  int held = -1;      // HeldDof: the index of a zero row
};
// The name of the condensation onto raw DOFs so far.
using RawCondensation = Condensation;

// Scratch of the dense route, kept by a caller that condenses many times (a sweep's analyses), so
// that no allocation remains once the sizes are known.
using CondensationWorkspace = DenseCondensationWorkspace;

// K_z of K (sparse, or dense as a small model's dense assembly gives it: only its lower triangle
// is read on the dense route) for the rows A, written over Kz (its storage kept). `residual`, when
// given: the computed relative residual ||F - K X|| / ||F|| of the route's own linear solve (the
// saddle point's, or the dense factor's for the condensed DOFs' response to the rows).
template <class Matrix>
Condensation::Outcome condense(const Matrix& K, const Eigen::MatrixXd& A, Eigen::MatrixXd& Kz,
                               const SolverOptions& options = {}, CondensationWorkspace* workspace = nullptr,
                               double* residual = nullptr);

// K_z of K for the rows A by the iterative solver `cg` (its compute(K) done): Mechanism when CG
// breaks down or A X is not positive definite (K singular), NotConverged when a solve stops above
// rtol; `report` says how the solves went (the most iterations and the largest computed residual
// ||a_k - K x_k|| / ||a_k|| over the rows).
Condensation::Outcome condense_iteratively(const PetscSolver& cg, const SparseMatrix& K, const Eigen::MatrixXd& A,
                                           Eigen::MatrixXd& Kz, SolverReport& report);

// The same for the rows of T_free of the raw DOFs `raw` of `map` (K free x free).
Condensation condense(const DofMap& map, const SparseMatrix& K, std::span<const int> raw,
                      const SolverOptions& options = {});

}  // namespace beamfea
