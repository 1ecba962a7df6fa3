// The ordering of large matrices by supervariables (solvers/fill_ordering.hpp) and its use by
// SparseFactor from kOrderedMinDofs up.
#include <gtest/gtest.h>

#include <Eigen/CholmodSupport>
#include <algorithm>
#include <numeric>
#include <string>

#include "solvers/fill_ordering.hpp"
#include "solvers/sparse_factor.hpp"
#include "support/matrices.hpp"

namespace fill_ordering_test {

using namespace beamfea;

namespace {

constexpr int kDofsPerNode = 6;

// A frame-like matrix: the 7-point grid Laplacian of m^3 nodes (tests/support/matrices.hpp) with
// every node carrying six DOFs coupled by the SPD block B = 6 I + ones (K = L (x) B, SPD as both
// factors are). When `released` >= 0, DOF 5 of that node keeps only its diagonal, as a released
// DOF with a spring to ground would: its pattern then differs from its node's other five.
SparseMatrix node_grid(int m, int released = -1) {
  const SparseMatrix L = test::grid_laplacian(m);
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < L.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(L, j); it; ++it)
      for (int a = 0; a < kDofsPerNode; ++a)
        for (int b = 0; b < kDofsPerNode; ++b) {
          const int r = static_cast<int>(it.row()) * kDofsPerNode + a, c = j * kDofsPerNode + b;
          const bool cut = (it.row() == released && a == 5) || (j == released && b == 5);
          if (cut && r != c) continue;
          t.emplace_back(r, c, cut ? 1.0 : it.value() * ((a == b ? 6.0 : 0.0) + 1.0));
        }
  SparseMatrix K(L.rows() * kDofsPerNode, L.cols() * kDofsPerNode);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

SparseMatrix lower(const SparseMatrix& K) {
  SparseMatrix A = K.triangularView<Eigen::Lower>();
  A.makeCompressed();
  return A;
}

}  // namespace

TEST(FillOrdering, SupervariablesAreTheNodesAndAReleasedDofStandsAlone) {
  const int m = 4, nodes = m * m * m;
  const std::vector<int> plain = supervariable_starts(lower(node_grid(m)));
  ASSERT_EQ(static_cast<int>(plain.size()), nodes + 1);
  for (int g = 0; g <= nodes; ++g) EXPECT_EQ(plain[g], g * kDofsPerNode);

  const int released = 21;
  const std::vector<int> split = supervariable_starts(lower(node_grid(m, released)));
  ASSERT_EQ(static_cast<int>(split.size()), nodes + 2);
  // Node 21's DOFs 0-4 stay one run, DOF 5 is a run of its own; its neighbours' runs are whole.
  EXPECT_EQ(split[released], released * kDofsPerNode);
  EXPECT_EQ(split[released + 1], released * kDofsPerNode + 5);
  EXPECT_EQ(split[released + 2], (released + 1) * kDofsPerNode);
  EXPECT_EQ(split.back(), nodes * kDofsPerNode);
}

namespace {
// `perm` orders all the columns of A, each run of a node's DOFs expanded in place: a node's first
// DOF is followed by its next ones (the released node's DOF 5 is a run of its own and may stand
// anywhere).
void expect_permutation_keeping_runs(const std::vector<int>& perm, std::size_t columns, int released) {
  ASSERT_EQ(perm.size(), columns);
  std::vector<int> sorted = perm;
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> identity(perm.size());
  std::iota(identity.begin(), identity.end(), 0);
  EXPECT_EQ(sorted, identity);
  for (std::size_t k = 0; k < perm.size(); ++k) {
    const int node = perm[k] / kDofsPerNode, dof = perm[k] % kDofsPerNode;
    const int run_end = node == released ? 4 : kDofsPerNode - 1;
    if (dof < run_end) {
      ASSERT_LT(k + 1, perm.size());
      EXPECT_EQ(perm[k + 1], perm[k] + 1) << "position " << k;
    }
  }
}
}  // namespace

TEST(FillOrdering, NestedDissectionIsAPermutationKeepingEachNodesDofsTogetherAndInOrder) {
  const int m = 6, released = 100;
  const SparseMatrix A = lower(node_grid(m, released));
  cholmod_common c;
  cholmod_start(&c);
  const std::vector<int> perm = nested_dissection_by_supervariables(A, c);
  EXPECT_EQ(c.status, CHOLMOD_OK);
  const SupervariableOrderings both = orderings_by_supervariables(A, c);
  EXPECT_EQ(c.status, CHOLMOD_OK);
  cholmod_finish(&c);
  expect_permutation_keeping_runs(perm, static_cast<std::size_t>(A.cols()), released);
  expect_permutation_keeping_runs(both.nesdis, static_cast<std::size_t>(A.cols()), released);
  expect_permutation_keeping_runs(both.metis, static_cast<std::size_t>(A.cols()), released);
  EXPECT_EQ(both.nesdis, perm);  // the same NESDIS from the same compressed graph
}

// CHOLMOD's count of the factor's nonzeros (Common->lnz) for the analysis of `perm` given.
double cholmod_lnz(const SparseMatrix& lower_triangle, std::vector<int> perm, cholmod_common& c) {
  cholmod_sparse a = Eigen::viewAsCholmod(lower_triangle.selfadjointView<Eigen::Lower>());
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_GIVEN;
  cholmod_factor* L = cholmod_analyze_p(&a, perm.data(), nullptr, 0, &c);
  EXPECT_NE(L, nullptr);
  const double lnz = c.lnz;
  cholmod_free_factor(&L, &c);
  return lnz;
}

TEST(FillOrdering, TheFactorsNonzerosCountedOnTheCompressedGraphAreCholmodsCount) {
  // The count decides between the candidates without CHOLMOD's analysis of each: it must be
  // CHOLMOD's own (Common->lnz), exactly, for either ordering, with runs of six columns, a run of
  // five beside a lone released DOF, and on a matrix whose runs are all single columns (the grid
  // Laplacian itself, where the count is that of the ordinary symbolic factorisation).
  cholmod_common c;
  cholmod_start(&c);
  for (const SparseMatrix& K : {node_grid(7), node_grid(9, 200), test::grid_laplacian(12)}) {
    const SparseMatrix A = lower(K);
    const SupervariableOrderings both = orderings_by_supervariables(A, c);
    ASSERT_FALSE(both.nesdis.empty());
    ASSERT_FALSE(both.metis.empty());
    EXPECT_EQ(both.lnz_nesdis, cholmod_lnz(A, both.nesdis, c)) << K.rows() << " DOFs";
    EXPECT_EQ(both.lnz_metis, cholmod_lnz(A, both.metis, c)) << K.rows() << " DOFs";
    // And not a count that any ordering would give: the natural order fills far more.
    std::vector<int> natural(static_cast<std::size_t>(A.cols()));
    std::iota(natural.begin(), natural.end(), 0);
    EXPECT_GT(cholmod_lnz(A, natural, c), 1.2 * std::max(both.lnz_nesdis, both.lnz_metis)) << K.rows() << " DOFs";
  }
  cholmod_finish(&c);
}

TEST(FillOrdering, SparseFactorFromTheThresholdSolvesAndNamesTheOrderingItKept) {
  // 15^3 nodes x 6 = 20,250 DOFs >= kOrderedMinDofs.
  const SparseMatrix K = node_grid(15, 7);
  ASSERT_GE(K.rows(), kOrderedMinDofs);
  SparseFactor f;
  ASSERT_EQ(f.factorize(K), FactorStatus::Succeeded);
  const std::string ordering = f.ordering();
  EXPECT_TRUE(ordering.rfind("NESDIS (", 0) == 0 || ordering.rfind("METIS (", 0) == 0) << ordering;
  // The kept ordering is the one of fewer nonzeros: "<kept> (nnz(L): NESDIS of supervariables
  // <a>, METIS of supervariables <b>)".
  const auto n_at = ordering.find("NESDIS of supervariables "), m_at = ordering.find("METIS of supervariables ");
  ASSERT_NE(n_at, std::string::npos) << ordering;
  ASSERT_NE(m_at, std::string::npos) << ordering;
  const double lnz_nesdis = std::stod(ordering.substr(n_at + 25)), lnz_metis = std::stod(ordering.substr(m_at + 24));
  EXPECT_GT(lnz_nesdis, 0.0);
  EXPECT_GT(lnz_metis, 0.0);
  EXPECT_EQ(ordering.rfind("NESDIS (", 0) == 0, lnz_nesdis <= lnz_metis) << ordering;
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(K.rows(), -1.0, 2.0);
  const Eigen::VectorXd x = f.solve(b);
  // Backward stable Cholesky of a matrix of condition ~1e2: the residual is rounding.
  EXPECT_LT((K * x - b).norm() / b.norm(), 1e-13);

  // Below the threshold CHOLMOD's own choice.
  SparseFactor small;
  ASSERT_EQ(small.factorize(node_grid(8)), FactorStatus::Succeeded);
  EXPECT_EQ(small.ordering(), "CHOLMOD's choice");
}

}  // namespace fill_ordering_test
