#include "core/assembly.hpp"

#include <algorithm>

#include "core/errors.hpp"
#include "core/huge_pages.hpp"

namespace beamfea {

void SystemAssembler::reset(const DofMap& map) {
  map_ = &map;
  built_ = false;
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
  for (int a = 0; a < n; ++a)
    for (int ia = start_f_[a]; ia < start_f_[a + 1]; ++ia) {
      const auto [i, ci] = terms_f_[ia];
      for (int b = 0; b < n; ++b) {
        const double kab = ci * K(a, b);
        for (int jb = start_f_[b]; jb < start_f_[b + 1]; ++jb)
          put(tff_, pos_ff_, kff_, Kff_, i, terms_f_[jb].first, kab * terms_f_[jb].second);
        for (int jb = start_p_[b]; jb < start_p_[b + 1]; ++jb)
          put(tfp_, pos_fp_, kfp_, Kfp_, i, terms_p_[jb].first, kab * terms_p_[jb].second);
      }
    }
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
  build(Kff_, map_->free_size(), map_->free_size(), tff_, one_pass_ ? nullptr : &pos_ff_);
  build(Kfp_, map_->free_size(), map_->prescribed_size(), tfp_, one_pass_ ? nullptr : &pos_fp_);
  tff_.clear();
  tff_.shrink_to_fit();
  tfp_.clear();
  tfp_.shrink_to_fit();
  built_ = !one_pass_;  // one pass: no positions, so a later pass collects triplets again
}

}  // namespace beamfea
