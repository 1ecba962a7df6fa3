#pragma once
// Sparse linear expressions of DofMap's constraint elimination (core/dof_map.cpp), without a heap
// node per term (std::map rows would be most of a small model's DofMap allocations).
//
// SparseRow: sum_k c_k x_k as terms sorted by k, each k once; the interface of the
// std::map<int, double> it replaces (operator[] inserts a zero, iteration in increasing k), so the
// sums are formed in the same order and give the same bits.
// RowStore: finished rows, appended once each into one array (rows are read, never changed, after
// they are stored).
// append_row: a row of a row-major Eigen matrix built in place, as setFromTriplets would form it.
#include <Eigen/SparseCore>
#include <algorithm>
#include <utility>
#include <vector>

namespace beamfea {

class SparseRow {
 public:
  using Term = std::pair<int, double>;
  using iterator = std::vector<Term>::iterator;
  using const_iterator = std::vector<Term>::const_iterator;

  double& operator[](int k) {
    auto it = lower(k);
    if (it == terms_.end() || it->first != k) it = terms_.insert(it, Term{k, 0.0});
    return it->second;
  }
  iterator find(int k) {
    auto it = lower(k);
    return it != terms_.end() && it->first == k ? it : terms_.end();
  }
  const_iterator find(int k) const {
    auto it = std::lower_bound(terms_.begin(), terms_.end(), k, [](const Term& t, int key) { return t.first < key; });
    return it != terms_.end() && it->first == k ? it : terms_.end();
  }
  iterator erase(iterator it) { return terms_.erase(it); }
  void clear() { terms_.clear(); }  // keeps the capacity: a reused row allocates no more
  void reserve(std::size_t n) { terms_.reserve(n); }
  bool empty() const { return terms_.empty(); }
  std::size_t size() const { return terms_.size(); }
  iterator begin() { return terms_.begin(); }
  iterator end() { return terms_.end(); }
  const_iterator begin() const { return terms_.begin(); }
  const_iterator end() const { return terms_.end(); }

 private:
  iterator lower(int k) {
    return std::lower_bound(terms_.begin(), terms_.end(), k, [](const Term& t, int key) { return t.first < key; });
  }
  std::vector<Term> terms_;
};

// dst += f * src (nothing when f is 0), term by term in increasing index.
template <class Terms>
void add_scaled(SparseRow& dst, const Terms& src, double f) {
  if (f == 0.0) return;
  for (const auto& [k, v] : src) dst[k] += f * v;
}

class RowStore {
 public:
  struct View {
    const SparseRow::Term* first = nullptr;
    const SparseRow::Term* last = nullptr;
    const SparseRow::Term* begin() const { return first; }
    const SparseRow::Term* end() const { return last; }
  };
  // Sizes the slots (every slot empty until set) and reserves room for about `terms` terms.
  void reset(int slots, std::size_t terms) {
    range_.assign(slots, {0, 0});
    terms_.clear();
    terms_.reserve(terms);
  }
  // Stores `row` as slot `slot` (once per slot).
  void set(int slot, const SparseRow& row) {
    const std::size_t b = terms_.size();
    terms_.insert(terms_.end(), row.begin(), row.end());
    range_[slot] = {b, terms_.size()};
  }
  View operator[](int slot) const {
    const auto& r = range_[slot];
    return {terms_.data() + r.first, terms_.data() + r.second};
  }

 private:
  std::vector<SparseRow::Term> terms_;
  std::vector<std::pair<std::size_t, std::size_t>> range_;
};

// Appends row `r` to the row-major matrix M being filled row by row (M.startVec for each row in
// turn; M.finalize() after the last), from terms (column, value) in the order they were produced:
// a column's terms summed in that order and exact zeros dropped, the entries of setFromTriplets
// followed by prune(0.0) on the same triplets. Clears `terms` (sorted in place first).
inline void append_row(Eigen::SparseMatrix<double, Eigen::RowMajor>& M, int r, std::vector<SparseRow::Term>& terms) {
  // A stable insertion sort: rows are short and nearly always sorted already (std::stable_sort
  // would allocate a buffer on every call).
  for (std::size_t i = 1; i < terms.size(); ++i) {
    const SparseRow::Term t = terms[i];
    std::size_t j = i;
    for (; j > 0 && terms[j - 1].first > t.first; --j) terms[j] = terms[j - 1];
    terms[j] = t;
  }
  M.startVec(r);
  for (std::size_t i = 0; i < terms.size();) {
    const int c = terms[i].first;
    double v = terms[i].second;
    for (++i; i < terms.size() && terms[i].first == c; ++i) v += terms[i].second;
    if (v != 0.0) M.insertBack(r, c) = v;
  }
  terms.clear();
}

}  // namespace beamfea
