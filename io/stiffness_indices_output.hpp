#pragma once
// The "indices" of a node stiffness result (stiffness analyses, path steps with stiffness_node):
// the options of a stiffness spec that ask for more of them, and their JSON
// (docs/analyses/stiffness.md; the numerics in solvers/stiffness_indices.hpp).
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "io/analysis.hpp"
#include "io/json_pointer.hpp"
#include "solvers/condensed_stiffness.hpp"

namespace beamfea {

// The documented bound of a stiffness spec's "directions".
inline constexpr std::size_t kMaxIndexDirections = 1000;

struct IndicesRequest {
  std::vector<Vec3> directions;           // "directions": [[dx, dy, dz], ...] (nonzero): "along"
  std::optional<Vec6> reference_wrench;   // "reference_wrench": [fx fy fz mx my mz]: "deflection"
};

// Reads "directions" and "reference_wrench" of a stiffness spec (absent: none); InputError at the
// field's pointer (a zero direction at its own).
IndicesRequest read_indices_request(const nlohmann::json& spec, const json_in::Pointer& p);

// The indices of the node stiffness `k` (ok) about a model of length scale L, written over `v`:
// translational and rotational {min, max, directions [d_min, d_max], blocked, free},
// condition_translational, condition_rotational, and along / deflection, deflection_norm when
// `request` asks for them. Unbounded or undefined values are null.
void set_indices(ojson& v, const CondensedStiffness& k, double L, const IndicesRequest& request = {});

}  // namespace beamfea
