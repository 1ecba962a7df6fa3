#pragma once
// Model-level validation that no single entry shows (contradictions are errors):
// a model without elements; a support and a prescribed value on one DOF that disagree; supports
// and prescribed values on one rigid body (rigid links, locked joint directions) that disagree;
// end releases that leave a member a mechanism.
// Each is an InputError naming both sides. Called by load_and_check after read_model.
#include <nlohmann/json.hpp>
#include <string>

#include "core/dof_map.hpp"
#include "core/model.hpp"

namespace beamfea {

void check_model(const Model& model, const nlohmann::json& document);

// Why a raw node DOF cannot move in the reference configuration, in the user's words
// ("is supported (/supports/0)", "is prescribed (/prescribed/2)", "is held by rigid link 'r1'
// to a supported node"...), or "" when it is free to move.
std::string why_held(const Model& model, const DofMap& map, int node, int comp);

}  // namespace beamfea
