#include "core/dense_assembly.hpp"

namespace beamfea {

void DenseAssembler::begin() { Kff_.setZero(map_->free_size(), map_->free_size()); }

void DenseAssembler::add(std::span<const int> raw, const Eigen::Ref<const Eigen::MatrixXd>& K) {
  const auto& Tf = map_->T_free();
  const int n = static_cast<int>(raw.size());
  terms_.clear();
  start_.assign(n + 1, 0);
  bool direct = true;  // every raw DOF is one free DOF with coefficient 1 (no constraint rows)
  for (int a = 0; a < n; ++a) {
    for (SparseRowMatrix::InnerIterator it(Tf, raw[a]); it; ++it)
      if (it.value() != 0.0) terms_.emplace_back(static_cast<int>(it.col()), it.value());
    start_[a + 1] = static_cast<int>(terms_.size());
    direct = direct && start_[a + 1] - start_[a] == 1 && terms_.back().second == 1.0;
  }
  double* k = Kff_.data();
  const Eigen::Index ld = Kff_.rows();
  if (direct) {
    for (int b = 0; b < n; ++b) {
      double* col = k + ld * terms_[b].first;
      for (int a = 0; a < n; ++a) col[terms_[a].first] += K(a, b);
    }
    return;
  }
  for (int b = 0; b < n; ++b)
    for (int jb = start_[b]; jb < start_[b + 1]; ++jb) {
      const auto [j, cj] = terms_[jb];
      double* col = k + ld * j;
      for (int a = 0; a < n; ++a) {
        const double kab = K(a, b) * cj;
        if (kab == 0.0) continue;
        for (int ia = start_[a]; ia < start_[a + 1]; ++ia) col[terms_[ia].first] += terms_[ia].second * kab;
      }
    }
}

}  // namespace beamfea
