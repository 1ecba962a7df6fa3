#include "solvers/element_factory.hpp"

#include "core/errors.hpp"
#include "elements/corotational_beam.hpp"
#include "elements/offset_element.hpp"
#include "elements/released_element.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

bool is_transformed(const Element& el) { return el.type == MemberType::Beam && (el.has_releases() || el.has_offsets()); }

std::unique_ptr<FrameElement> make_frame_element(const Model& model, int e, Kinematics kinematics) {
  const Element& el = model.elements[e];
  try {
    const BeamSection s = beam_section(model, el);
    // The beam between the flexible ends, its releases condensed, seen at the nodes through the
    // rigid arms.
    const Vec3 x1 = flexible_end(model, el, 0), x2 = flexible_end(model, el, 1);
    std::unique_ptr<BeamElement> beam;
    if (kinematics == Kinematics::Linear) beam = std::make_unique<LinearBeam>(s, x1, x2, el.orientation);
    else beam = std::make_unique<CorotationalBeam>(s, x1, x2, el.orientation);
    std::unique_ptr<FrameElement> out;
    if (el.has_releases()) out = std::make_unique<ReleasedElement>(std::move(beam), el.released);
    else out = std::move(beam);
    if (el.has_offsets())
      out = std::make_unique<OffsetElement>(std::move(out), el.offsets,
                                            kinematics == Kinematics::Linear ? ArmKinematics::Linear : ArmKinematics::Finite);
    return out;
  } catch (const ModelError&) {
    throw;
  } catch (const Error& err) {  // the element's own error, named here
    throw ModelError("element '" + el.id + "'", err.what());
  }
}

}  // namespace beamfea
