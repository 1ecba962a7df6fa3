#pragma once
// Assembly of the reduced stiffness into a dense matrix, for small models.
//
// The same map as SystemAssembler (core/assembly.hpp), K_ff += T_f,e^T K_e T_f,e, written straight
// into an n x n column-major array: no triplets, no sparse pattern, no allocation once the array
// and the scratch have their size. Below a few hundred free DOFs the dense factorisations
// (solvers/sparse_factor.hpp, kDenseMaxDofs) are the faster ones, and building a CSC matrix only to
// copy it into a dense one cost more than the factorisation itself (docs/performance.md, "Small
// models"). Only K_ff: the stiffness condensation needs no K_fp.
#include <Eigen/Core>
#include <span>
#include <utility>
#include <vector>

#include "core/dof_map.hpp"

namespace beamfea {

class DenseAssembler {
 public:
  explicit DenseAssembler(const DofMap& map) : map_(&map) {}

  // Starts an assembly pass: K_ff = 0 (free x free), storage kept.
  void begin();
  // Adds a matrix over raw DOFs (symmetric or not).
  void add(std::span<const int> raw, const Eigen::Ref<const Eigen::MatrixXd>& K);
  void end() {}

  const Eigen::MatrixXd& K_ff() const { return Kff_; }
  // For another map of the same model (a new configuration); the storage is kept.
  void reset(const DofMap& map) { map_ = &map; }

 private:
  const DofMap* map_;
  Eigen::MatrixXd Kff_;
  // Scratch for one call, reused between calls: the free terms of each raw DOF of the element.
  std::vector<std::pair<int, double>> terms_;
  std::vector<int> start_;
};

}  // namespace beamfea
