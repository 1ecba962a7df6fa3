#pragma once
// The kernels of the dense back end of the solver contract and of the condensation: a Cholesky
// factor that skips the zeros of a small stiffness matrix (SparseFactor's small-model path), and
// the Schur complement onto constraint rows. Callers condense through solvers/condensation.hpp,
// which chooses between these and the saddle point.
//
// Below kDenseMaxDofs (solvers/sparse_factor.hpp) the matrix is stored dense but is still sparse:
// a right-looking column Cholesky that skips zero multipliers and stops each column at its last
// nonzero costs about sum_k b_k^2 (b_k the extent of column k of L) instead of n^3/3, and no
// sparse structure, ordering or supernode bookkeeping is set up. On a chain (a banded matrix) the
// factor is several times faster than Eigen's blocked LLT at 40 DOFs (docs/performance.md,
// "Small models").
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <span>
#include <vector>

#include "solvers/linear_solver.hpp"

namespace beamfea {

// L L^T = A for the symmetric positive definite A, whose lower triangle is read; L overwrites it
// (the strict upper triangle is left as it was). last[k] is the last row of column k of L that
// is not zero. False when a pivot is not positive (or not finite): the matrix is not positive
// definite, A is left part-way.
bool cholesky_in_place(Eigen::MatrixXd& A, std::vector<int>& last);
// The first `columns` columns of that factor only: the trailing block then holds the Schur
// complement A_22 - A_21 A_11^-1 A_12 of the leading columns' block (lower triangle).
bool cholesky_in_place(Eigen::MatrixXd& A, std::vector<int>& last, int columns);

// x = (L L^T)^-1 x for the factor of cholesky_in_place (forward and back substitution within each
// column's extent).
void cholesky_solve_in_place(const Eigen::MatrixXd& L, const std::vector<int>& last, Eigen::Ref<Eigen::VectorXd> x);

// CHOLMOD's reciprocal condition estimate of L L^T (cholmod_rcond): (min L_ii / max L_ii)^2.
double cholesky_rcond(const Eigen::MatrixXd& L);

// Scratch of the dense condensation, kept by a caller that condenses many times (a sweep's
// analyses), so that no allocation remains once the sizes are known.
struct DenseCondensationWorkspace {
  Eigen::MatrixXd L, W, C;
  Eigen::VectorXd s;
  std::vector<int> last;
  Eigen::LLT<Eigen::MatrixXd> llt;  // of C
  std::vector<int> order;           // dense_static_condensation's DOF order
  Eigen::MatrixXd X, F;             // the solve's answer and right-hand side (condense's residual)
};

// Condensation onto constraint rows: for K (n x n, symmetric positive definite, lower triangle
// read) and dense rows A (r x n), Kz = (A K^-1 A^T)^-1, which is minus the multiplier block M of
// the saddle point [K A^T; A 0][X; M] = [0; I] (Schur complement), by the Cholesky of K and of the
// r x r complement. False when K is larger than options.dense_max_dofs, not positive definite, or
// either factor's reciprocal condition estimate is below options.singular_rcond.
bool dense_schur_condensation(const Eigen::MatrixXd& K, const Eigen::MatrixXd& A, Eigen::MatrixXd& Kz,
                              const FactorOptions& options = {}, DenseCondensationWorkspace* workspace = nullptr);

// The same for rows A = diag(a) E that pick columns `cols` of K (distinct; a node whose DOFs are
// free DOFs of their own), by static condensation: the picked DOFs ordered last, a Cholesky factor
// of the other DOFs' block K_11 alone, and K_z = D^-1 (K_22 - K_21 K_11^-1 K_12) D^-1, D = diag(a)
// (Guyan 1965; A K^-1 A^T = D (K^-1)_22 D and (K^-1)_22 is the inverse of that Schur complement).
// No inverse of the compliance is formed. At most six picked columns. False when K is larger
// than options.dense_max_dofs, not positive definite, or its factor's reciprocal condition
// estimate is below options.singular_rcond (a mechanism, an ill-posed condensation: the caller
// falls back to dense_schur_condensation and the saddle point).
bool dense_static_condensation(const Eigen::MatrixXd& K, std::span<const int> cols, std::span<const double> a,
                               Eigen::MatrixXd& Kz, const FactorOptions& options = {},
                               DenseCondensationWorkspace* workspace = nullptr);

}  // namespace beamfea
