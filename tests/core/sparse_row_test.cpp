// core/sparse_row.hpp: the flat rows that replaced std::map expressions and setFromTriplets in
// DofMap. They must give the same numbers bit for bit (same terms, same summation order), so each
// is checked against what it replaced on random sequences of operations.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <vector>

#include "core/sparse_row.hpp"

namespace beamfea::sparse_row_test {
namespace {

void expect_same(const SparseRow& row, const std::map<int, double>& ref) {
  ASSERT_EQ(row.size(), ref.size());
  auto it = ref.begin();
  for (const auto& [k, v] : row) {
    EXPECT_EQ(k, it->first);
    EXPECT_EQ(v, it->second);  // bitwise: the same additions in the same order
    ++it;
  }
}

TEST(SparseRow, BehavesAsTheMapItReplaced) {
  std::mt19937 gen(7);
  std::uniform_int_distribution<int> key(-20, 40), op(0, 9);
  std::uniform_real_distribution<double> val(-3.0, 3.0);
  SparseRow row, other;
  std::map<int, double> ref, other_ref;
  for (int step = 0; step < 5000; ++step) {
    const int k = key(gen);
    const double v = val(gen);
    switch (op(gen)) {
      case 0: {  // erase through find
        auto it = row.find(k);
        auto rit = ref.find(k);
        ASSERT_EQ(it == row.end(), rit == ref.end());
        if (rit != ref.end()) {
          EXPECT_EQ(it->second, rit->second);
          row.erase(it);
          ref.erase(rit);
        }
        break;
      }
      case 1:  // dst += f * src
        add_scaled(row, other, v);
        for (const auto& [ok, ov] : other_ref) ref[ok] += v * ov;
        break;
      case 2:
        other[k] += v;
        other_ref[k] += v;
        break;
      case 3:
        if (step % 50 == 0) {
          row.clear();
          ref.clear();
        }
        break;
      default:
        row[k] += v;
        ref[k] += v;
    }
    expect_same(row, ref);
  }
  // A zero factor adds nothing, not even zero entries.
  SparseRow empty;
  add_scaled(empty, other, 0.0);
  EXPECT_TRUE(empty.empty());
  const SparseRow& c = row;
  EXPECT_EQ(c.find(1000), c.end());
}

TEST(SparseRow, RowStoreKeepsEachRowAsStored) {
  RowStore store;
  store.reset(3, 1);  // fewer terms reserved than stored: the store grows
  SparseRow a, b;
  a[5] = 1.5;
  a[2] = -1.0;
  b[0] = 4.0;
  store.set(2, a);
  store.set(0, b);
  a[9] = 7.0;  // later changes to the source row do not reach the stored one
  std::vector<std::pair<int, double>> r2(store[2].begin(), store[2].end()), r0(store[0].begin(), store[0].end());
  EXPECT_EQ(r2, (std::vector<std::pair<int, double>>{{2, -1.0}, {5, 1.5}}));
  EXPECT_EQ(r0, (std::vector<std::pair<int, double>>{{0, 4.0}}));
  EXPECT_EQ(store[1].begin(), store[1].end());  // never set: empty
}

TEST(SparseRow, AppendRowMatchesSetFromTripletsAndPrune) {
  // Random rows with repeated columns, exact cancellations and explicit zeros, against Eigen's
  // setFromTriplets (duplicates summed in triplet order) followed by prune(0.0).
  using RowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  std::mt19937 gen(11);
  std::uniform_int_distribution<int> col(0, 9), count(0, 8), pick(0, 4);
  std::uniform_real_distribution<double> val(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const int rows = 1 + trial % 7, cols = 10;
    std::vector<Eigen::Triplet<double>> triplets;
    RowMatrix M(rows, cols);
    std::vector<SparseRow::Term> terms;
    for (int r = 0; r < rows; ++r) {
      const int n = count(gen);
      for (int t = 0; t < n; ++t) {
        const int c = col(gen);
        double v = val(gen);
        const int kind = pick(gen);
        if (kind == 0) v = 0.0;
        terms.emplace_back(c, v);
        triplets.emplace_back(r, c, v);
        if (kind == 1) {  // the same column again, cancelling exactly
          terms.emplace_back(c, -v);
          triplets.emplace_back(r, c, -v);
        }
      }
      append_row(M, r, terms);
      EXPECT_TRUE(terms.empty());
    }
    M.finalize();
    RowMatrix ref(rows, cols);
    ref.setFromTriplets(triplets.begin(), triplets.end());
    ref.prune(0.0);
    ASSERT_EQ(M.nonZeros(), ref.nonZeros()) << trial;
    for (int r = 0; r < rows; ++r) {
      RowMatrix::InnerIterator a(M, r), b(ref, r);
      for (; a && b; ++a, ++b) {
        EXPECT_EQ(a.col(), b.col());
        EXPECT_EQ(a.value(), b.value());
      }
      EXPECT_FALSE(a);
      EXPECT_FALSE(b);
    }
  }
}

}  // namespace
}  // namespace beamfea::sparse_row_test
