#include "io/stiffness_indices_output.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"
#include "io/json_util.hpp"
#include "solvers/stiffness_indices.hpp"

namespace beamfea {

namespace {

void set_optional(ojson& v, const std::optional<double>& x) {
  if (x) v = *x;
  else v = nullptr;
}

void set_directions(ojson& v, const std::array<Vec3, 3>& d, int count) {
  auto& items = set_array(v, static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) set_numbers(items[static_cast<std::size_t>(i)], d[static_cast<std::size_t>(i)].data(), 3);
}

// {min, max, directions [d_min, d_max] (empty when every direction is blocked), blocked, free}.
void set_block(ojson& v, const BlockIndices& b) {
  ObjectFiller o(v, 5);
  set_optional(o.slot("min"), b.min);
  set_optional(o.slot("max"), b.max);
  const int extremes = b.min ? 2 : 0;
  set_directions(o.slot("directions"), {b.direction_min, b.direction_max, Vec3::Zero()}, extremes);
  set_directions(o.slot("blocked"), b.blocked, b.blocked_count);
  set_directions(o.slot("free"), b.free, b.free_count);
  o.finish();
}

}  // namespace

IndicesRequest read_indices_request(const nlohmann::json& spec, const json_in::Pointer& p) {
  IndicesRequest r;
  if (const nlohmann::json* d = json_in::field(spec, "directions")) {
    const json_in::Pointer pd = json_in::child(p, "directions");
    const nlohmann::json& list = json_in::array(*d, pd, "stiffness directions");
    if (list.size() > kMaxIndexDirections)
      throw InputError(pd, fmt::format("stiffness: at most {} directions", kMaxIndexDirections));
    for (std::size_t i = 0; i < list.size(); ++i) {
      const json_in::Pointer pi = json_in::child(pd, i);
      const Vec3 x = json_in::vec3(list[i], pi, "stiffness direction");
      if (!(x.norm() > 0.0)) throw InputError(pi, "stiffness direction: must not be zero");
      r.directions.push_back(x);
    }
  }
  if (const nlohmann::json* w = json_in::field(spec, "reference_wrench")) {
    const json_in::Pointer pw = json_in::child(p, "reference_wrench");
    if (!w->is_array() || w->size() != 6)
      throw InputError(pw, "stiffness reference_wrench: expected an array of 6 numbers [fx fy fz mx my mz]");
    Vec6 x;
    for (int i = 0; i < 6; ++i) x[i] = json_in::number((*w)[static_cast<std::size_t>(i)], json_in::child(pw, static_cast<std::size_t>(i)), "stiffness reference_wrench");
    r.reference_wrench = x;
  }
  return r;
}

void set_indices(ojson& v, const CondensedStiffness& k, double L, const IndicesRequest& request) {
  const StiffnessIndices ix = stiffness_indices(k.compliance, k.unbounded_directions(), L);
  ObjectFiller o(v, 8);
  set_block(o.slot("translational"), ix.translational);
  set_block(o.slot("rotational"), ix.rotational);
  set_optional(o.slot("condition_translational"), ix.translational.condition);
  set_optional(o.slot("condition_rotational"), ix.rotational.condition);
  if (!request.directions.empty()) {
    auto& along = set_array(o.slot("along"), request.directions.size());
    for (std::size_t i = 0; i < request.directions.size(); ++i)
      set_optional(along[i], stiffness_along(k.compliance, k.unbounded_directions(), L, request.directions[i]));
  }
  if (request.reference_wrench) {
    const std::optional<Vec6> u = deflection_under(k.compliance, k.unbounded_directions(), L, *request.reference_wrench);
    if (u) {
      set_numbers(o.slot("deflection"), u->data(), 6);
      o.slot("deflection_norm") = u->head<3>().norm();
    } else {
      o.slot("deflection") = nullptr;
      o.slot("deflection_norm") = nullptr;
    }
  }
  o.finish();
}

}  // namespace beamfea
