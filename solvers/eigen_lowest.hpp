#pragma once
// Lowest eigenpairs of a sparse symmetric matrix by shift-invert Lanczos (Spectra), with the
// shifted matrix factorised by CHOLMOD. Small matrices are solved densely.
#include <Eigen/Core>

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

}  // namespace beamfea
