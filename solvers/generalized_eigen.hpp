#pragma once
// The lowest eigenpairs of the symmetric pencil K phi = lambda M phi, M positive semi-definite
// (massless DOFs allowed: their eigenvalues are infinite and never returned), K symmetric
// (positive semi-definite for free vibration; indefinite beyond buckling under a preload).
//
// Method: shift-invert Lanczos (Spectra's SymGEigsShiftSolver, GEigsMode::ShiftInvert; Ericsson &
// Ruhe 1980, "The spectral transformation Lanczos method", Math. Comp. 35, 1251-1268) on
// (K - sigma M)^{-1} M, with K - sigma M factorised once by CHOLMOD (supernodal LL^T; a sparse
// LU when it is indefinite). Eigenvalues nearest sigma come first; with sigma below the spectrum
// they are the lowest. Each eigenvector is "purified" by one more application of the operator
// (phi <- (lambda - sigma)(K - sigma M)^{-1} M phi), which removes any component in the null
// space of M (Ericsson & Ruhe, sec. 4), and then M-normalised: phi^T M phi = 1.
// Systems of at most kDenseLimit DOFs are solved densely: Cholesky of K - sigma M = L L^T and the
// symmetric eigenproblem of L^{-1} M L^{-T} (eigenvalues 1/(lambda - sigma)).
#include <string>

#include "core/dof_map.hpp"

namespace beamfea {

struct GeneralizedEigenPairs {
  Eigen::VectorXd values;   // ascending, finite
  Eigen::MatrixXd vectors;  // columns, phi^T M phi = 1
  bool converged = false;
  std::string message;      // why not, when not converged
};

inline constexpr int kDenseLimit = 600;  // dense below: about 0.2 s, and robust for any M

// The `count` eigenvalues nearest `sigma` (not an eigenvalue) and their vectors. Fewer are
// returned when M has fewer than `count` finite modes (its rank).
GeneralizedEigenPairs nearest_generalized_eigenpairs(const SparseMatrix& K, const SparseMatrix& M, int count,
                                                     double sigma);

}  // namespace beamfea
