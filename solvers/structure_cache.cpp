#include "solvers/structure_cache.hpp"

#include <bit>
#include <cstdint>

namespace beamfea {

namespace {
// Options compared by their bits, as the key's doubles (solvers/structure_key.hpp).
bool same_option(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }
}  // namespace

bool structure_cache_keeps(const Model& model) {
  long raw = 6 * static_cast<long>(model.nodes.size());
  for (const auto& j : model.joints) raw += j.coordinates();
  return raw <= kMaxCachedRawDofs;
}

const LinearStructureCache::Parts& LinearStructureCache::get(const Model& model) {
  last_hit_ = parts_ && key_.matches(model);
  if (last_hit_) {
    parts_->map.rebind(model);
    parts_->structure.rebind(model);
    return *parts_;
  }
  // A miss rebuilds the pair over the last one's storage (a sweep whose geometry changes every case
  // then allocates nothing once warm). The key is cleared first: a throwing rebuild leaves a pair
  // that no model matches, rebuilt again by the next call. The key's storage is kept too.
  key_.clear();
  reference_configuration(model, reference_);
  if (parts_) parts_->rebuild(model, reference_);
  else parts_.emplace(model, reference_);
  if (keeps(model)) key_.assign(model);
  return *parts_;
}

LinearStructureCache& thread_structure_cache() {
  thread_local LinearStructureCache cache;
  return cache;
}

std::shared_ptr<const LinearSystem> LinearSystemCache::get(const Model& model, const LinearStaticOptions& options) {
  last_hit_ = system_ && same_option(options.singular_rcond, options_.singular_rcond) &&
              same_option(options.zero_energy_tolerance, options_.zero_energy_tolerance) && key_.matches(model);
  if (last_hit_) {
    system_->rebind(model);
    return system_;
  }
  system_.reset();
  key_.clear();
  auto system = std::make_shared<LinearSystem>(model, options);
  if (structure_cache_keeps(model) && system->factorizations() == 1) {
    key_.assign(model);
    options_ = options;
    system_ = system;
  }
  return system;
}

}  // namespace beamfea
