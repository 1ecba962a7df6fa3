#pragma once
// Matrices shared by the tests of factorisations.
#include <Eigen/Sparse>
#include <vector>

#include "core/dof_map.hpp"

namespace beamfea::test {

// The 7-point Laplacian of an m x m x m grid plus the identity (diagonal 7, -1 to each neighbour):
// m^3 unknowns, symmetric positive definite with eigenvalues in [1, 13] (well conditioned), and
// for m >= 12 above the dense threshold with supernodes large enough for BLAS-3 calls.
inline SparseMatrix grid_laplacian(int m) {
  const int n = m * m * m;
  std::vector<Eigen::Triplet<double>> t;
  auto id = [m](int i, int j, int k) { return (k * m + j) * m + i; };
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const int r = id(i, j, k);
        t.emplace_back(r, r, 7.0);
        const int nb[3][3] = {{i + 1, j, k}, {i, j + 1, k}, {i, j, k + 1}};
        for (const auto& q : nb)
          if (q[0] < m && q[1] < m && q[2] < m) {
            const int c = id(q[0], q[1], q[2]);
            t.emplace_back(r, c, -1.0);
            t.emplace_back(c, r, -1.0);
          }
      }
  SparseMatrix K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

}  // namespace beamfea::test
