#pragma once
// The solver contract: factor an operator once, solve many right-hand sides, give its inertia
// when asked (Eigen's compute()/solve(), PETSc's KSP with its operators set once, Trilinos
// Amesos2's symbolic/numeric/solve).
//
//   analyze(A)   the symbolic analysis (ordering, elimination tree) of A's pattern alone; optional:
//                compute() makes it when the pattern is new, and reuses the last one otherwise
//   compute(A)   the numeric factorisation (after the symbolic one where the pattern changed);
//                returns the outcome as a FactorStatus, never throws for a singular or indefinite
//                matrix (bad input, e.g. a non-square matrix, throws)
//   solve(b, x)  x = A^-1 b for one right-hand side (x sized like b, written over); solve(B, X)
//                for many at once. Only when usable().
//   inertia()    the numbers of negative, zero and positive eigenvalues of the (symmetric) matrix,
//                where the back end can tell them (Sylvester's law of inertia on its factor):
//                  DenseLdlt, SimplicialLdlt: always after a factorisation (signs of D; a pivot
//                    below kZeroPivotRelative of the largest counts as zero);
//                  Automatic, Cholmod, DenseLlt: only when the LL^T succeeded (positive
//                    definite: 0, 0, n); none otherwise;
//                  Umfpack, DenseLu: none (an LU does not preserve symmetry).
//
// Back ends (SolverOptions::backend, made by make_linear_solver):
//   Automatic       SparseFactor (solvers/sparse_factor.hpp): Jacobi-scaled; a dense Cholesky that
//                   skips zeros up to dense_max_dofs DOFs, CHOLMOD's supernodal LL^T with its
//                   ordering trial above, UMFPACK's LU when the LL^T fails (allow_lu). What the
//                   linear analyses use.
//   Cholmod         CHOLMOD's supernodal LL^T (unscaled, CHOLMOD's orderings), then UMFPACK's LU
//                   when it fails and allow_lu (the shift-invert operators of the eigensolvers).
//   Umfpack         UMFPACK's LU.
//   SimplicialLdlt  Eigen's simplicial LDL^T (AMD ordering): the inertia of a sparse matrix.
//   DenseLlt, DenseLdlt, DenseLu   Eigen's LLT, LDLT (inertia) and PartialPivLU of a dense copy.
// Every sparse back end keeps its symbolic analysis while the pattern stays (solvers/
// pattern_factor.hpp's PatternFactor for the plain Eigen wrappers).
//
// Adding a back end. An iterative one (PETSc's KSP with a preconditioner, say) is a class deriving
// from LinearSolver whose analyze() sets up the preconditioner's structure, compute() its values
// and solve() iterates (FactorStatus then reports a failure to converge as Singular, or a new
// enumerator), plus one SolverBackend enumerator and its case in make_linear_solver: callers that
// hold a LinearSolver& are unchanged. A complex-valued one (frequency response: K + i omega C -
// omega^2 M) derives from BasicLinearSolver<std::complex<double>>: the contract is a template on
// the scalar type, LinearSolver being its real instance, and a factory for that scalar would sit
// beside make_linear_solver.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <complex>
#include <memory>
#include <optional>

#include "core/dof_map.hpp"

namespace beamfea {

enum class FactorStatus {
  Succeeded,           // factorised; solves are meaningful
  NotPositiveDefinite, // Cholesky failed: singular or indefinite (LU may still have succeeded)
  Singular,            // no factorisation could be made, or one with a zero pivot
  TooLarge,            // the symbolic analysis failed: the factor exceeds CHOLMOD's int interface or memory
};
const char* to_string(FactorStatus s);

// Up to this many DOFs a dense Cholesky replaces CHOLMOD (same scaling, same reciprocal
// condition estimate; the factor skips the zeros of the matrix, solvers/dense_condensation.hpp).
// Measured (bench_small_models, docs/performance.md "Small models"): dense is at least 2.2x faster
// than CHOLMOD up to 160 DOFs on every model tried; the crossover is near 290 DOFs for 3-D fill
// and above 360 for a banded matrix. Not raised: beyond 160 the dense factor's (unpermuted)
// condition estimate would decide singularity for models CHOLMOD decides today.
inline constexpr int kDenseMaxDofs = 160;

// A pivot of an LDL^T whose magnitude is below this fraction of the largest counts as a zero
// eigenvalue in the inertia (rounding of an exactly singular matrix's pivot: n eps relative).
inline constexpr double kZeroPivotRelative = 1e-12;

enum class SolverBackend { Automatic, Cholmod, Umfpack, SimplicialLdlt, DenseLlt, DenseLdlt, DenseLu };
const char* to_string(SolverBackend b);

struct SolverOptions {
  SolverBackend backend = SolverBackend::Automatic;
  double singular_rcond = 1e-13;  // below this (scaled) reciprocal condition the matrix is singular
  bool allow_lu = true;           // Automatic, Cholmod: fall back to LU for indefinite matrices
  int dense_max_dofs = kDenseMaxDofs;  // Automatic: dense Cholesky up to this size (0: always sparse)
  void validate() const;
};
// The name the factorisation options have always had.
using FactorOptions = SolverOptions;

// Sylvester's inertia of a symmetric matrix.
struct Inertia {
  int negative = 0, zero = 0, positive = 0;
  bool operator==(const Inertia&) const = default;
};
// The inertia of the pivots d of an LDL^T: a pivot below kZeroPivotRelative of the largest is zero.
Inertia count_inertia(const Eigen::VectorXd& d);

template <class Scalar>
class BasicLinearSolver {
 public:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Sparse = Eigen::SparseMatrix<Scalar, Eigen::ColMajor, int>;

  virtual ~BasicLinearSolver() = default;
  // The symbolic analysis of A's pattern (A's values are not read).
  virtual void analyze(const Sparse& A) = 0;
  // The factorisation of A (square; symmetric for the LL^T and LDL^T back ends, which read its
  // lower triangle), reusing the symbolic analysis while the pattern is unchanged.
  virtual FactorStatus compute(const Sparse& A) = 0;
  // The outcome of the last compute(); Singular before any.
  virtual FactorStatus status() const = 0;
  // Whether solve() may be called (a factor exists, possibly of a matrix that is not positive
  // definite or is ill-conditioned: status() says).
  virtual bool usable() const = 0;
  // x = A^-1 b, x of b's size (written over; may not alias b).
  virtual void solve(Eigen::Ref<const Vector> b, Eigen::Ref<Vector> x) const = 0;
  // X = A^-1 B (X resized).
  virtual void solve(const Matrix& B, Matrix& X) const = 0;
  // Numbers of negative, zero and positive eigenvalues, where the back end can tell (see above).
  virtual std::optional<Inertia> inertia() const = 0;
  virtual Eigen::Index rows() const = 0;

  Vector solve(const Vector& b) const {
    Vector x(b.size());
    solve(b, x);
    return x;
  }
  Matrix solve(const Matrix& B) const {
    Matrix X;
    solve(B, X);
    return X;
  }
};
using LinearSolver = BasicLinearSolver<double>;

// A back end for the options (validated).
std::unique_ptr<LinearSolver> make_linear_solver(const SolverOptions& options = {});

}  // namespace beamfea
