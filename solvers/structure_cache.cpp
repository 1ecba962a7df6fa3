#include "solvers/structure_cache.hpp"

#include <bit>
#include <cstdint>

namespace beamfea {

namespace {

// Doubles are equal when their bits are: 0.0 and -0.0 can give results whose zeros differ in sign
// (and a NaN, which no checked model holds, equals itself here and gives the same NaNs again).
bool same(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }
bool same(const Vec3& a, const Vec3& b) { return same(a[0], b[0]) && same(a[1], b[1]) && same(a[2], b[2]); }

bool same(const Node& a, const Node& b) { return a.id == b.id && same(a.x, b.x) && a.member == b.member; }
bool same(const Element& a, const Element& b) {
  return a.id == b.id && a.type == b.type && a.nodes == b.nodes && a.material == b.material && a.section == b.section &&
         same(a.orientation, b.orientation) && a.theory == b.theory && a.member == b.member;
}
bool same(const Material& a, const Material& b) {
  return a.id == b.id && same(a.E, b.E) && same(a.G, b.G) && same(a.density, b.density);
}
bool same(const Section& a, const Section& b) {
  return a.id == b.id && same(a.A, b.A) && same(a.Iy, b.Iy) && same(a.Iz, b.Iz) && same(a.J, b.J) && same(a.ky, b.ky) &&
         same(a.kz, b.kz);
}
// Everything but the springs (stiffness, stiffness_matrix): LinearStructure::assemble reads those
// from the bound model at each call, and the DofMap never does.
bool same(const Joint& a, const Joint& b) {
  if (!(a.id == b.id && a.type == b.type && a.nodes == b.nodes && a.translations == b.translations &&
        a.axes.size() == b.axes.size()))
    return false;
  for (std::size_t i = 0; i < a.axes.size(); ++i)
    if (!same(a.axes[i], b.axes[i])) return false;
  return true;
}
bool same(const Support& a, const Support& b) { return a.node == b.node && a.fixed == b.fixed; }
bool same(const Prescribed& a, const Prescribed& b) { return a.dof == b.dof && same(a.value, b.value); }

template <class T>
bool same(const std::vector<T>& a, const std::vector<T>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!same(a[i], b[i])) return false;
  return true;
}

}  // namespace

bool LinearStructureCache::keeps(const Model& model) {
  long raw = 6 * static_cast<long>(model.nodes.size());
  for (const auto& j : model.joints) raw += j.coordinates();
  return raw <= kMaxRawDofs;
}

bool LinearStructureCache::matches(const Key& key, const Model& model) {
  return same(key.nodes, model.nodes) && same(key.elements, model.elements) && same(key.materials, model.materials) &&
         same(key.sections, model.sections) && same(key.joints, model.joints) && same(key.supports, model.supports) &&
         same(key.prescribed, model.prescribed);
}

void LinearStructureCache::assign_key(Key& key, const Model& model) {
  // Copy-assigned: the vectors and the ids keep the storage of the last key (a sweep whose
  // geometry changes every case copies its key every case).
  key.nodes = model.nodes;
  key.elements = model.elements;
  key.materials = model.materials;
  key.sections = model.sections;
  key.joints = model.joints;
  key.supports = model.supports;
  key.prescribed = model.prescribed;
  for (auto& j : key.joints) {  // not part of the key: no need to hold them
    j.stiffness.clear();
    j.stiffness_matrix.resize(0, 0);
  }
}

const LinearStructureCache::Parts& LinearStructureCache::get(const Model& model) {
  last_hit_ = key_ && parts_ && matches(*key_, model);
  if (last_hit_) {
    parts_->map.rebind(model);
    parts_->structure.rebind(model);
    return *parts_;
  }
  // A throwing constructor leaves no pair behind (and a key without a pair matches nothing); the
  // key's storage is kept for the next one.
  parts_.reset();
  parts_.emplace(Parts{DofMap(model), LinearStructure(model)});
  if (keeps(model)) {
    if (!key_) key_.emplace();
    assign_key(*key_, model);
  } else {
    key_.reset();
  }
  return *parts_;
}

LinearStructureCache& thread_structure_cache() {
  thread_local LinearStructureCache cache;
  return cache;
}

}  // namespace beamfea
