#pragma once
// Where the analyses get their beam elements (the element contract, elements/frame_element.hpp):
// the beam of the element's section and theory in the analysis's kinematics, wrapped by the
// behaviours that transform it (end releases: elements/released_element.hpp; rigid arms of
// offsets and rigid end zones: elements/offset_element.hpp, around the released beam, which lies
// between the flexible ends). An analysis asks here and never branches on the wrappers.
#include <memory>

#include "core/model.hpp"
#include "elements/frame_element.hpp"

namespace beamfea {

// Small displacements (LinearBeam) or finite rotations (CorotationalBeam).
enum class Kinematics { Linear, Corotational };

// Whether beam element `el` is a wrapped element (a plain LinearBeam or CorotationalBeam when not).
bool is_transformed(const Element& el);

// The element of beam element `e` of `model`. Throws ModelError naming the element (a zero length,
// an orientation along the member, releases that leave it a mechanism).
std::unique_ptr<FrameElement> make_frame_element(const Model& model, int e, Kinematics kinematics);

}  // namespace beamfea
