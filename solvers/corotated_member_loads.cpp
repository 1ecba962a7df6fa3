#include "solvers/corotated_member_loads.hpp"

#include "elements/corotational_beam.hpp"
#include "elements/member_loads.hpp"
#include "solvers/member_loading.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

std::vector<Vec12> corotated_fixed_end_forces(const Model& model, const LoadSet& loads, const std::vector<Vec3>& x,
                                              const std::vector<Mat3>& R, double factor) {
  std::vector<Vec12> out(model.elements.size(), Vec12::Zero());
  if (factor == 0.0) return out;
  // The loads between the nodes, in each element's reference local axes.
  const std::vector<ElementLoads> ref = element_loads(model, loads);
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const auto& el = model.elements[e];
    if (el.type != MemberType::Beam || ref[e].empty()) continue;
    const int a = el.nodes[0], b = el.nodes[1];
    const CorotationalBeam beam(beam_section(model, el), model.nodes[a].x, model.nodes[b].x, el.orientation);
    const Mat3 Rr = beam.kinematics(x[a], R[a], x[b], R[b]).Rr;
    // Reference local -> global (E0, columns the reference axes) -> current local (Rr^T): the load
    // keeps its direction in space.
    const Mat3 Q = Rr.transpose() * beam.reference_axes();
    ElementLoads now;
    for (const auto& d : ref[e].distributed) now.distributed.push_back({d.a, d.b, Q * d.q_a, Q * d.q_b});
    for (const auto& p : ref[e].points) now.points.push_back({p.a, Q * p.force, Q * p.moment});
    out[e] = factor * fixed_end_forces(beam.reference_length(), now);
  }
  return out;
}

}  // namespace beamfea
