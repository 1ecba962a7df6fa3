#pragma once
// Caches of a small model's structure, for sweeps: a sweep over actuator stiffnesses, loads or
// anything else that the numbering, the constraint rows and the beams' matrices do not depend on
// rebuilds the same map and the same element matrices case after case (about a sixth of a
// three-link chain's stiffness case), and a load sweep the same assembled and factorised system.
//
// Never stale by construction: each cache keeps a copy of every model field that its constructors
// read (solvers/structure_key.hpp) and reuses what it built only when the asked model equals that
// copy field by field, doubles compared by their bits. A hit rebinds what it reuses to the asked
// model, so that its later reads (the joint springs in `assemble`, loads, ids in messages) come from
// that model.
#include <memory>
#include <optional>

#include "core/dof_map.hpp"
#include "core/model.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/structure.hpp"
#include "solvers/structure_key.hpp"

namespace beamfea {

// Models up to this many raw DOFs are kept (a cache's memory stays small: at most the map, element
// matrices and factor of a 160-node frame).
inline constexpr int kMaxCachedRawDofs = 960;

// Whether the caches keep this model's structure (at most kMaxCachedRawDofs raw DOFs). A caller
// with a larger model builds its own, so that a thread does not hold a large model's map after it.
bool structure_cache_keeps(const Model& model);

// The DofMap (reference configuration) and LinearStructure of the stiffness analysis; the key
// leaves out the joint springs, which `LinearStructure::assemble` reads from the bound model.
class LinearStructureCache {
 public:
  static constexpr int kMaxRawDofs = kMaxCachedRawDofs;

  struct Parts {
    // Built in place: moving a DofMap copies its sparse matrices (Eigen's SparseMatrix has no move
    // constructor), three allocations each.
    explicit Parts(const Model& model) : map(model), structure(model) {}
    Parts(const Model& model, const Configuration& reference) : map(model, reference), structure(model) {}
    // Both built over the last pair's storage (the same values as a new pair's).
    void rebuild(const Model& model, const Configuration& reference) {
      map.rebuild(model, reference);
      structure.rebuild(model);
    }
    DofMap map;
    LinearStructure structure;
  };
  // `model`'s DofMap in its reference configuration and its LinearStructure, bound to `model`:
  // the kept pair when `model` equals the key, else a pair rebuilt over the kept one's storage
  // (reused by later calls only when `keeps(model)`). Valid while `model` lives and until the next
  // call. Throws what the constructors throw (nothing reusable is kept then).
  const Parts& get(const Model& model);

  static bool keeps(const Model& model) { return structure_cache_keeps(model); }

  // Whether the last `get` reused the kept pair (tests).
  bool last_was_hit() const { return last_hit_; }

 private:
  StructureKey key_{StructureKey::Springs::Excluded};
  Configuration reference_;  // the last missed model's reference configuration (storage kept)
  std::optional<Parts> parts_;
  bool last_hit_ = false;
};

// The calling thread's cache (linear_node_stiffness uses it: a sweep worker is one thread).
LinearStructureCache& thread_structure_cache();

// The LinearSystem (map, assembled stiffness, factorisation) of linear_static, for a worker that
// solves case after case (io's RunReport keeps one): the key includes the joint springs, and the
// loads are not in it (a load sweep reuses the factorisation). A system whose stiffness could not
// be factorised is not kept.
class LinearSystemCache {
 public:
  // `model`'s system bound to `model`: the kept one when `model` and `options` equal the key's,
  // else a new one (kept when `structure_cache_keeps(model)` and it factorised). Throws what the
  // constructor throws (nothing is kept then).
  std::shared_ptr<const LinearSystem> get(const Model& model, const LinearStaticOptions& options = {});

  // Whether the last `get` reused the kept system (tests).
  bool last_was_hit() const { return last_hit_; }

 private:
  StructureKey key_{StructureKey::Springs::Included};
  LinearStaticOptions options_;
  std::shared_ptr<LinearSystem> system_;
  bool last_hit_ = false;
};

}  // namespace beamfea
