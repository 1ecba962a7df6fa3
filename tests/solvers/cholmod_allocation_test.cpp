// CHOLMOD allocates its factor through core/huge_pages.hpp's functions once a SparseFactor exists
// (solvers/sparse_factor.cpp: SuiteSparse's process-wide allocation functions), and frees with
// std::free; a factorisation through them still solves (a 1-D Laplacian, exact).
#include <gtest/gtest.h>

#include <SuiteSparse_config.h>

#include <cmath>
#include <cstdlib>
#include <vector>

#include "core/huge_pages.hpp"
#include "solvers/sparse_factor.hpp"

namespace cholmod_allocation_test {

using namespace beamfea;

TEST(CholmodAllocation, ThroughTheAdvisedFunctionsOnceASparseFactorExists) {
  SparseFactor factor;
  EXPECT_EQ(SuiteSparse_config.malloc_func, &malloc_advised);
  EXPECT_EQ(SuiteSparse_config.calloc_func, &calloc_advised);
  EXPECT_EQ(SuiteSparse_config.realloc_func, &realloc_advised);
  EXPECT_EQ(SuiteSparse_config.free_func, &std::free);
}

TEST(CholmodAllocation, AFactorisationThroughThemSolves) {
  // K = tridiag(-1, 2, -1) of order n (a 1-D Laplacian, condition ~ 4 n^2 / pi^2), b = K x for a
  // known x: CHOLMOD's LL' (dense path off) must return x to rounding, 1e-8 here for n = 2000
  // (error ~ condition x 1e-16 = 2e-10).
  const int n = 2000;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0);
    if (i + 1 < n) t.emplace_back(i + 1, i, -1.0), t.emplace_back(i, i + 1, -1.0);
  }
  SparseMatrix K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  Eigen::VectorXd x(n);
  for (int i = 0; i < n; ++i) x[i] = std::sin(0.01 * i) + 1.0;
  SparseFactor factor;
  FactorOptions sparse;
  sparse.dense_max_dofs = 0;
  ASSERT_EQ(factor.factorize(K, sparse), FactorStatus::Succeeded);
  const Eigen::VectorXd b = K * x;
  const Eigen::VectorXd solved = factor.solve(b);
  EXPECT_LT((solved - x).lpNorm<Eigen::Infinity>(), 1e-8);
}

}  // namespace cholmod_allocation_test
