#include "core/assembly.hpp"

#include <algorithm>

#include "core/errors.hpp"
#include "core/huge_pages.hpp"

namespace beamfea {

void SystemAssembler::reset(const DofMap& map) {
  map_ = &map;
  built_ = false;
  planned_ = false;
  tff_.clear();
  tfp_.clear();
  pos_ff_.clear();
  pos_fp_.clear();
}

void SystemAssembler::begin() {
  kff_ = kfp_ = 0;
  if (built_) {
    std::fill(Kff_.valuePtr(), Kff_.valuePtr() + Kff_.nonZeros(), 0.0);
    std::fill(Kfp_.valuePtr(), Kfp_.valuePtr() + Kfp_.nonZeros(), 0.0);
  } else {
    if (planned_) std::fill(Kff_.valuePtr(), Kff_.valuePtr() + Kff_.nonZeros(), 0.0);
    tff_.clear();
    tfp_.clear();
  }
}

void SystemAssembler::expect(std::size_t entries) {
  if (built_ || !tff_.empty() || entries <= tff_.capacity()) return;
  tff_.reserve(entries);
  advise_huge_pages(tff_.data(), tff_.capacity() * sizeof(Triplet));
}

void SystemAssembler::put(std::vector<Triplet>& trip, std::vector<int>& pos, std::size_t& k, SparseMatrix& A,
                          int r, int c, double v) {
  if (!built_) {
    trip.push_back({r, c, v});
    return;
  }
  if (k >= pos.size()) throw Error("assembly: call sequence differs from the first pass");
  A.valuePtr()[pos[k++]] += v;
}

void SystemAssembler::plan(SparseMatrix pattern) {
  if (!one_pass_) throw Error("assembly: a planned pattern is for a single pass (Passes::One)");
  if (pattern.rows() != map_->free_size() || pattern.cols() != map_->free_size() || !pattern.isCompressed())
    throw Error("assembly: the planned pattern does not fit the DOF map");
  Kff_ = std::move(pattern);
  planned_ = true;
  built_ = false;
}

void SystemAssembler::add_planned(int n, const Eigen::Ref<const Eigen::MatrixXd>& K) {
  const int* outer = Kff_.outerIndexPtr();
  const int* inner = Kff_.innerIndexPtr();
  double* value = Kff_.valuePtr();
  // Column j of the element's entries, its rows in the element's order: a node's free DOFs are
  // consecutive rows of the column too, so most entries sit just after the last one found.
  for (int b = 0; b < n; ++b)
    for (int jb = start_f_[b]; jb < start_f_[b + 1]; ++jb) {
      const auto [j, cj] = terms_f_[jb];
      if (!owned_.contains(j)) continue;
      const int* first = inner + outer[j];
      const int* last = inner + outer[j + 1];
      const int* at = last;
      for (int a = 0; a < n; ++a)
        for (int ia = start_f_[a]; ia < start_f_[a + 1]; ++ia) {
          const auto [i, ci] = terms_f_[ia];
          if (at + 1 < last && at[1] == i) {
            ++at;
          } else {
            at = std::lower_bound(first, last, i);
            if (at == last || *at != i) throw Error("assembly: an entry outside the planned pattern");
          }
          value[at - inner] += ci * K(a, b) * cj;  // the arithmetic of the triplets' path
        }
    }
}

void SystemAssembler::add(std::span<const int> raw, const Eigen::Ref<const Eigen::MatrixXd>& K) {
  const auto& Tf = map_->T_free();
  const auto& Tp = map_->T_prescribed();
  const int n = static_cast<int>(raw.size());
  terms_f_.clear();
  start_f_.assign(n + 1, 0);
  terms_p_.clear();
  start_p_.assign(n + 1, 0);
  for (int a = 0; a < n; ++a) {
    for (SparseRowMatrix::InnerIterator it(Tf, raw[a]); it; ++it) terms_f_.emplace_back(static_cast<int>(it.col()), it.value());
    start_f_[a + 1] = static_cast<int>(terms_f_.size());
    if (Tp.cols() > 0)
      for (SparseRowMatrix::InnerIterator it(Tp, raw[a]); it; ++it) terms_p_.emplace_back(static_cast<int>(it.col()), it.value());
    start_p_[a + 1] = static_cast<int>(terms_p_.size());
  }
  if (planned_) {  // K_ff's values straight into the plan; K_fp's triplets below
    add_planned(n, K);
    if (terms_p_.empty()) return;
  }
  for (int a = 0; a < n; ++a)
    for (int ia = start_f_[a]; ia < start_f_[a + 1]; ++ia) {
      const auto [i, ci] = terms_f_[ia];
      const bool owned_row = owned_.contains(i);
      for (int b = 0; b < n; ++b) {
        const double kab = ci * K(a, b);
        if (!planned_)
          for (int jb = start_f_[b]; jb < start_f_[b + 1]; ++jb)
            if (owned_.contains(terms_f_[jb].first))
              put(tff_, pos_ff_, kff_, Kff_, i, terms_f_[jb].first, kab * terms_f_[jb].second);
        if (owned_row)
          for (int jb = start_p_[b]; jb < start_p_[b + 1]; ++jb)
            put(tfp_, pos_fp_, kfp_, Kfp_, i, terms_p_[jb].first, kab * terms_p_[jb].second);
      }
    }
}

bool SystemAssembler::reaches_owned(std::span<const int> raw) const {
  if (owned_.all()) return true;
  for (const int r : raw)
    for (SparseRowMatrix::InnerIterator it(map_->T_free(), r); it; ++it)
      if (owned_.contains(static_cast<int>(it.col()))) return true;
  return false;
}

void SystemAssembler::build(SparseMatrix& A, int rows, int cols, const std::vector<Triplet>& trip, std::vector<int>* pos_out) {
  A.resize(rows, cols);
  A.setFromTriplets(trip.begin(), trip.end());
  A.makeCompressed();
  if (!pos_out) return;
  std::vector<int>& pos = *pos_out;
  pos.resize(trip.size());
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  for (std::size_t k = 0; k < trip.size(); ++k) {
    const int* first = inner + outer[trip[k].c];
    const int* last = inner + outer[trip[k].c + 1];
    pos[k] = static_cast<int>(std::lower_bound(first, last, trip[k].r) - inner);
  }
}

void SystemAssembler::end() {
  if (built_) {
    if (kff_ != pos_ff_.size() || kfp_ != pos_fp_.size()) throw Error("assembly: call sequence differs from the first pass");
    return;
  }
  if (planned_) {  // K_ff's values are in place; K_fp from its triplets
    build(Kfp_, map_->free_size(), map_->prescribed_size(), tfp_, nullptr);
    tfp_.clear();
    tfp_.shrink_to_fit();
    return;
  }
  build(Kff_, map_->free_size(), map_->free_size(), tff_, one_pass_ ? nullptr : &pos_ff_);
  build(Kfp_, map_->free_size(), map_->prescribed_size(), tfp_, one_pass_ ? nullptr : &pos_fp_);
  tff_.clear();
  tff_.shrink_to_fit();
  tfp_.clear();
  tfp_.shrink_to_fit();
  built_ = !one_pass_;  // one pass: no positions, so a later pass collects triplets again
}

SparseMatrix planned_pattern(const DofMap& map, const AssemblyBlocks& blocks) { return planned_pattern(map, blocks, {}); }

SparseMatrix planned_pattern(const DofMap& map, const AssemblyBlocks& blocks, OwnedColumns owned) {
  const SparseRowMatrix& Tf = map.T_free();
  const int n = map.free_size();
  const std::size_t nb = blocks.size();
  // The free DOFs each block reaches, sorted, once each; none for a block that reaches no owned
  // column (it adds nothing to them).
  std::vector<int> fstart(nb + 1, 0), free;
  free.reserve(owned.all() ? blocks.raw.size() : blocks.raw.size() / 2);
  for (std::size_t b = 0; b < nb; ++b) {
    const auto first = static_cast<std::ptrdiff_t>(free.size());
    for (const int r : blocks.block(b))
      for (SparseRowMatrix::InnerIterator it(Tf, r); it; ++it) free.push_back(static_cast<int>(it.col()));
    std::sort(free.begin() + first, free.end());
    free.erase(std::unique(free.begin() + first, free.end()), free.end());
    if (!owned.all() && std::none_of(free.begin() + first, free.end(), [&](int j) { return owned.contains(j); }))
      free.resize(static_cast<std::size_t>(first));
    fstart[b + 1] = static_cast<int>(free.size());
  }
  // The blocks of each free DOF, in block order.
  std::vector<int> istart(static_cast<std::size_t>(n) + 1, 0), incident(free.size());
  for (const int f : free) ++istart[f + 1];
  for (int j = 0; j < n; ++j) istart[j + 1] += istart[j];
  {
    std::vector<int> next(istart.begin(), istart.end() - 1);
    for (std::size_t b = 0; b < nb; ++b)
      for (int q = fstart[b]; q < fstart[b + 1]; ++q) incident[next[free[q]]++] = static_cast<int>(b);
  }
  // Column j: the union of its blocks' free DOFs. The DOFs of a node meet the same blocks and so
  // have the same rows: a column whose blocks are the last column's copies its rows.
  std::vector<int> outer(static_cast<std::size_t>(n) + 1, 0), rows, mark(static_cast<std::size_t>(n), -1);
  rows.reserve(free.size() * 4);
  for (int j = 0; j < n; ++j) {
    const int* inc = incident.data() + istart[j];
    const int count = owned.contains(j) ? istart[j + 1] - istart[j] : 0;
    const std::size_t at = rows.size();
    if (j > 0 && count > 0 && owned.contains(j - 1) && count == istart[j] - istart[j - 1] &&
        std::equal(inc, inc + count, incident.data() + istart[j - 1])) {
      const std::size_t from = outer[j - 1], len = at - from;
      rows.resize(at + len);
      std::copy(rows.begin() + static_cast<std::ptrdiff_t>(from), rows.begin() + static_cast<std::ptrdiff_t>(at),
                rows.begin() + static_cast<std::ptrdiff_t>(at));
    } else {
      for (int k = 0; k < count; ++k)
        for (int q = fstart[inc[k]]; q < fstart[inc[k] + 1]; ++q)
          if (mark[free[q]] != j) {
            mark[free[q]] = j;
            rows.push_back(free[q]);
          }
      std::sort(rows.begin() + static_cast<std::ptrdiff_t>(at), rows.end());
    }
    outer[j + 1] = static_cast<int>(rows.size());
  }
  SparseMatrix K(n, n);
  K.resizeNonZeros(static_cast<Eigen::Index>(rows.size()));
  std::copy(outer.begin(), outer.end(), K.outerIndexPtr());
  std::copy(rows.begin(), rows.end(), K.innerIndexPtr());
  std::fill(K.valuePtr(), K.valuePtr() + rows.size(), 0.0);
  return K;
}

}  // namespace beamfea
