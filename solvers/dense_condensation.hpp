#pragma once
// The dense small-model path of the stiffness condensation (issue 15): a Cholesky factor that
// skips the zeros of a small stiffness matrix, and the Schur complement onto constraint rows.
//
// Below kDenseMaxDofs (solvers/sparse_factor.hpp) the matrix is stored dense but is still sparse:
// a right-looking column Cholesky that skips zero multipliers and stops each column at its last
// nonzero costs about sum_k b_k^2 (b_k the extent of column k of L) instead of n^3/3, and no
// sparse structure, ordering or supernode bookkeeping is set up. On a chain (a banded matrix) the
// factor is several times faster than Eigen's blocked LLT at 40 DOFs (docs/performance.md,
// "Small models").
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <vector>

#include "solvers/sparse_factor.hpp"

namespace beamfea {

// L L^T = A for the symmetric positive definite A, whose lower triangle is read; L overwrites it
// (the strict upper triangle is left as it was). last[k] is the last row of column k of L that
// is not zero. False when a pivot is not positive (or not finite): the matrix is not positive
// definite, A is left part-way.
bool cholesky_in_place(Eigen::MatrixXd& A, std::vector<int>& last);

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
};

// As condense_dense (solvers/sparse_factor.hpp) for a dense K (n x n, lower triangle read): Kz =
// (A K^-1 A^T)^-1, false when K is larger than options.dense_max_dofs, not positive definite, or
// either factor's reciprocal condition estimate is below options.singular_rcond.
bool condense_dense(const Eigen::MatrixXd& K, const Eigen::MatrixXd& A, Eigen::MatrixXd& Kz,
                    const FactorOptions& options = {}, DenseCondensationWorkspace* workspace = nullptr);

}  // namespace beamfea
