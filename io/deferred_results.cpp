#include "io/deferred_results.hpp"

#include <iterator>
#include <utility>

namespace beamfea {

using ojson = nlohmann::ordered_json;

void DeferredParts::defer(ojson& slot, DeferredMembers part) {
  slot = ojson::binary({}, parts_.size());
  parts_.push_back(std::move(part));
}

const DeferredMembers* DeferredParts::find(const ojson& v) const {
  if (!v.is_binary()) return nullptr;
  const auto& b = v.get_binary();
  return b.has_subtype() && b.subtype() < parts_.size() ? &parts_[b.subtype()] : nullptr;
}

void DeferredParts::erase_placeholders(ojson& v) const {
  if (v.is_object()) {
    auto& items = v.get_ref<ojson::object_t&>();
    // ordered_map's own erase: its (const key, value) pairs cannot be move-assigned (std::erase_if).
    for (auto it = items.begin(); it != items.end();) it = find(it->second) ? items.erase(it) : std::next(it);
    for (auto& [key, x] : items) erase_placeholders(x);
  } else if (v.is_array()) {
    for (auto& x : v.get_ref<ojson::array_t&>()) erase_placeholders(x);
  }
}

}  // namespace beamfea
