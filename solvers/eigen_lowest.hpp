#pragma once
// Lowest eigenpairs of a sparse symmetric matrix by shift-invert Lanczos (Spectra), with the
// shifted matrix factorised by CHOLMOD. Small matrices are solved densely.
#include <Eigen/Core>
#include <functional>

#include "core/dof_map.hpp"

namespace beamfea {

struct EigenPairs {
  Eigen::VectorXd values;   // ascending
  Eigen::MatrixXd vectors;  // columns, unit norm
  bool converged = true;
};

// The `count` eigenvalues of A nearest to `shift` from above; `shift` must lie below the
// spectrum part of interest so that A - shift*I is positive definite when A is semi-definite.
EigenPairs lowest_eigenpairs(const SparseMatrix& A, int count, double shift);

// y = A^-1 x for an n x n matrix A (x and y of length n).
using InverseOp = std::function<void(const double* x, double* y)>;

// The `count` lowest eigenpairs of a symmetric POSITIVE DEFINITE A (n x n) given only y = A^-1 x (a
// factorisation the caller already has): Lanczos on A^-1, whose largest eigenvalues 1/lambda are
// those of the lowest lambda (shift-invert with shift zero; Saad 2011, "Numerical Methods for Large
// Eigenvalue Problems", sec. 8.3). `start`, when given (length n), starts the Krylov space: the
// previous eigenvector of a slowly changing A converges in the first Lanczos cycle. Throws Error
// when Spectra fails; `converged` false when the iterations ran out.
EigenPairs lowest_eigenpairs_of_inverse(Eigen::Index n, const InverseOp& inverse, int count,
                                        const Eigen::VectorXd* start = nullptr);

}  // namespace beamfea
