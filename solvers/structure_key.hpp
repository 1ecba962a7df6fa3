#pragma once
// A copy of the model fields that a small model's structure is built from, for the caches of
// solvers/structure_cache.hpp: a cache reuses what it built for the last model only when the asked
// model equals this copy field by field, doubles compared by their bits (so -0.0 and 0.0 differ, as
// they may in what is computed from them). Never stale by construction, as long as every field that
// the cached constructors read is here: the DofMap and LinearStructure constructors read nodes,
// elements, materials, sections, joints but their springs, supports, prescribed values, ties and
// linear constraints; the assembled stiffness (LinearSystem) reads the joint springs and the solver
// choice too. A field
// added to those structs that a constructor reads must be added here (structure_key.cpp).
#include <vector>

#include "core/model.hpp"

namespace beamfea {

class StructureKey {
 public:
  // Whether the joints' springs (stiffness, stiffness_matrix) are part of the key.
  enum class Springs { Excluded, Included };
  explicit StructureKey(Springs springs) : springs_(springs) {}

  // False until `assign` (and after `clear`).
  bool matches(const Model& model) const;
  // Copy-assigned: the vectors and ids keep the storage of the last key (a sweep whose geometry
  // changes every case copies its key every case).
  void assign(const Model& model);
  void clear() { set_ = false; }

 private:
  Springs springs_;
  bool set_ = false;
  std::vector<Node> nodes_;
  std::vector<Element> elements_;
  std::vector<Material> materials_;
  std::vector<Section> sections_;
  std::vector<Joint> joints_;
  std::vector<Support> supports_;
  std::vector<Prescribed> prescribed_;
  std::vector<Tie> ties_;
  std::vector<LinearConstraint> constraints_;
  SolverChoice solver_;  // the top-level "solver" (LinearSystem's direct or iterative back end)
};

}  // namespace beamfea
