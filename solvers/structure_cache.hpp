#pragma once
// A cache of a small model's DofMap (reference configuration) and LinearStructure, for the
// stiffness analysis of a sweep: a sweep over actuator stiffnesses, loads or anything else the
// numbering, the constraint rows and the beams' matrices do not depend on rebuilds the same map
// and the same element matrices case after case (about a sixth of a three-link chain's case).
//
// Never stale by construction: the cache keeps a copy of every model field that the DofMap and
// LinearStructure constructors read (nodes, elements, materials, sections, joints but their
// springs, supports, prescribed values), and reuses its pair only when the asked model equals
// that copy field by field, doubles compared by their bits (so -0.0 and 0.0 differ, as they may
// in what is computed from them). A hit rebinds the pair to the asked model, so its later reads
// (the joint springs in `assemble`, ids in messages) come from that model. A field added to
// those structs that either constructor reads must be added to the key (structure_cache.cpp).
#include <optional>
#include <vector>

#include "core/dof_map.hpp"
#include "core/model.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

class LinearStructureCache {
 public:
  // Models up to this many raw DOFs are kept (the cache's memory stays small: at most the map
  // and element matrices of a 160-node frame).
  static constexpr int kMaxRawDofs = 960;

  struct Parts {
    DofMap map;
    LinearStructure structure;
  };
  // `model`'s DofMap in its reference configuration and its LinearStructure, bound to `model`:
  // the kept pair when `model` equals the key, else a new pair (reused by later calls only when
  // `keeps(model)`). Valid while `model` lives and until the next call. Throws what the
  // constructors throw (nothing is kept then).
  const Parts& get(const Model& model);

  // Whether `get` keeps this model's pair (at most kMaxRawDofs raw DOFs). A caller with a larger
  // model builds its own pair, so that a thread does not hold a large model's map after the call.
  static bool keeps(const Model& model);

  // Whether the last `get` reused the kept pair (tests).
  bool last_was_hit() const { return last_hit_; }

 private:
  // The fields the constructors read (joints without their springs).
  struct Key {
    std::vector<Node> nodes;
    std::vector<Element> elements;
    std::vector<Material> materials;
    std::vector<Section> sections;
    std::vector<Joint> joints;
    std::vector<Support> supports;
    std::vector<Prescribed> prescribed;
  };
  static bool matches(const Key& key, const Model& model);
  static void assign_key(Key& key, const Model& model);

  std::optional<Key> key_;
  std::optional<Parts> parts_;
  bool last_hit_ = false;
};

// The calling thread's cache (linear_node_stiffness uses it: a sweep worker is one thread).
LinearStructureCache& thread_structure_cache();

}  // namespace beamfea
