#pragma once
// URDF import: a robot description (URDF, read by liburdfdom) and an optional side-car (JSON: what
// URDF lacks, joint stiffnesses and flexible links) become a beamfea model document (docs/urdf.md).
//
// Mapping, at the zero joint values (the model's reference geometry):
//   - every link frame is a node named after the link; the root link's node is supported (all);
//   - a joint's origin (xyz, rpy: R = Rz(yaw) Ry(pitch) Rx(roll), URDF's convention) places its
//     child link's frame; a revolute, continuous or prismatic joint becomes a beamfea joint (id: the
//     URDF joint's name) between the parent's joint-location node "<parent>@<joint>" (the link frame
//     node itself where the origin's xyz is zero) and the child's link-frame node, coincident, its
//     axis turned into global components; revolute and prismatic limits become "limits";
//   - a fixed joint welds the child link to its parent (a rigid link, or a tie of all six DOFs
//     where the two frames coincide);
//   - a link is rigid between its frame and its children's joint locations (rigid links), unless
//     the side-car gives it a flexible beam "from" -> "to" (points in the link frame): the link
//     frame is then welded to the beam's "from" end and the joint locations to its "to" end;
//   - an inertial becomes a point mass with its inertia (rotated into global axes) at the link's
//     centre of mass, a node "<link>@com" rigidly attached to the link frame (the frame node itself
//     where they coincide); side-car "inertials": false leaves them out.
// Errors (InputError, exit 2): the URDF parser's message naming the element (a joint whose parent
// or child link does not exist, a malformed attribute), a joint type beamfea has no equivalent for
// (floating, planar), and side-car fields at their JSON pointer (unknown keys with the nearest one
// suggested, unknown joint or link names).
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace beamfea {

// The model document of the URDF text `urdf` (named `source` in messages) with the side-car
// `sidecar` (none: rigid links, passive joints, masses from the inertials).
nlohmann::ordered_json urdf_to_model(const std::string& urdf, const std::string& source,
                                     const std::optional<nlohmann::json>& sidecar, const std::string& sidecar_source);

// The same, the URDF read from a file.
nlohmann::ordered_json urdf_file_to_model(const std::string& urdf_path, const std::optional<nlohmann::json>& sidecar,
                                          const std::string& sidecar_source);

}  // namespace beamfea
