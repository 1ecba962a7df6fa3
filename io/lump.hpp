#pragma once
// Lumped (VJM) models generated from beam models (docs/analyses/superelement.md, "Generated lumped
// models"): `beamfea lump model.json --links links.json -o lumped.json` and beamfea.lump().
//
// links: {"links": [{"id": "L1", "elements": ["e1", ...], "base": "O", "tip": "J1a"}, ...]}: each
// link is the sub-structure of its elements (members of the beam model; beams, rigid links, and the
// joints whose two nodes are both nodes of those elements), clamped at `base`, seen at `tip`.
// The lumped model is the beam model with each link replaced by
//   a node "<link>_spring" at the tip's position,
//   a rigid link "<link>_rigid" from the base to it,
//   a virtual spring "<link>_spring" from it to the tip, whose 6x6 stiffness (global axes, the
//   spring's default frame) is the link's condensed tip stiffness (the FEA-based VJM,
//   docs/analyses/superelement.md eq. 8: solvers/condensed_stiffness.hpp on the link clamped at
//   its base).
// Every other node, element, joint (actuators included), support, load, mass and analysis is kept
// with its id. A link's other nodes disappear with it: a support, load, point mass, prescribed DOF,
// tie, constraint, element or joint outside the link that names one is bad input, as is a member
// load on a link's element.
//
// The linear statics of the lumped model are the beam model's (to rounding), closed loops included:
// a link meets the rest only at its base and tip, and such a link's linear stiffness is its tip
// spring carried rigidly from its base. Under load (path, buckling, loaded stiffness) the models
// differ: the springs keep the reference pose's stiffness; that difference is what the comparison
// of lumped and beam models shows.
#include <nlohmann/json.hpp>

namespace beamfea {

// The lumped model of the beam model `model_doc` for the links of `links_doc` (a valid model,
// checked as `beamfea check` would). Bad input: InputError, the pointer into the links document
// ("/links/<i>/...") or the model's.
nlohmann::json lump_model(const nlohmann::json& model_doc, const nlohmann::json& links_doc);

}  // namespace beamfea
