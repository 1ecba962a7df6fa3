#include "elements/offset_element.hpp"

#include "elements/beam.hpp"

namespace beamfea {

OffsetElement::OffsetElement(std::unique_ptr<FrameElement> flexible, const std::array<Vec3, 2>& offsets, ArmKinematics arms)
    : flexible_(std::move(flexible)), o_(offsets), arms_(arms), B0_(arm_map(offsets[0], offsets[1])),
      K_(B0_.transpose() * flexible_->stiffness() * B0_) {}

Mat12 OffsetElement::arm_map(const Vec3& a1, const Vec3& a2) {
  Mat12 B = Mat12::Identity();
  B.block<3, 3>(0, 3) = -skew(a1);  // x' = x + w x a: d x' = dx - [a]x dw
  B.block<3, 3>(6, 9) = -skew(a2);
  return B;
}

NodalPoses OffsetElement::reference_poses() const {
  const NodalPoses f = flexible_->reference_poses();
  return {f.x1 - o_[0], f.x2 - o_[1], Mat3::Identity(), Mat3::Identity()};
}

NodalPoses OffsetElement::flexible_poses(const NodalPoses& p) const {
  if (arms_ == ArmKinematics::Linear)
    return {p.x1 + o_[0] + log_so3(p.R1).cross(o_[0]), p.x2 + o_[1] + log_so3(p.R2).cross(o_[1]), p.R1, p.R2};
  return {p.x1 + p.R1 * o_[0], p.x2 + p.R2 * o_[1], p.R1, p.R2};
}

ElementResponse OffsetElement::respond(const NodalPoses& p, Evaluate what) const {
  ElementResponse r = flexible_->respond(flexible_poses(p), what);
  const bool finite = arms_ == ArmKinematics::Finite;
  const Vec3 a[2] = {finite ? Vec3(p.R1 * o_[0]) : o_[0], finite ? Vec3(p.R2 * o_[1]) : o_[1]};
  const Mat12 B = finite ? arm_map(a[0], a[1]) : B0_;
  const Vec12 f = r.force;  // the flexible ends' forces
  r.force = B.transpose() * f;
  if (what == Evaluate::ForceAndTangent) {
    r.tangent = B.transpose() * r.tangent * B;
    if (finite)  // the arm a = R o turning: d(a x f) = (dw x a) x f = (a f^T - (a . f) I) dw
      for (int e = 0; e < 2; ++e) {
        const Vec3 fe = f.segment<3>(6 * e);
        r.tangent.block<3, 3>(6 * e + 3, 6 * e + 3) += a[e] * fe.transpose() - a[e].dot(fe) * Mat3::Identity();
      }
  }
  return r;
}

Mat12 OffsetElement::geometric_stiffness(const Vec12& f, GeometricStiffness kind) const {
  Mat12 kg = B0_.transpose() * flexible_->geometric_stiffness(f, kind) * B0_;
  // The arms' part, whichever kind the flexible part's: the second-order work of the end force F on the arm turned by theta:
  // F . (theta x (theta x o)) / 2 = theta^T (sym(F o^T) - (F . o) I) theta / 2.
  const Mat3& E = flexible_->axes();
  for (int e = 0; e < 2; ++e) {
    const Vec3 F = E.transpose() * f.segment<3>(6 * e);
    const Mat3 Fo = F * o_[e].transpose();
    kg.block<3, 3>(6 * e + 3, 6 * e + 3) += 0.5 * (Fo + Fo.transpose()) - F.dot(o_[e]) * Mat3::Identity();
  }
  return kg;
}

Mat12 OffsetElement::mass(MassKind kind, double density) const {
  return B0_.transpose() * flexible_->mass(kind, density) * B0_;
}

Mat12 OffsetElement::mass_at(const NodalPoses& p, MassKind kind, double density) const {
  if (arms_ == ArmKinematics::Linear) return mass(kind, density);
  const Mat12 B = arm_map(p.R1 * o_[0], p.R2 * o_[1]);
  return B.transpose() * flexible_->mass_at(flexible_poses(p), kind, density) * B;
}

Vec12 OffsetElement::to_nodes(const Vec12& local) const {
  const Mat12 T = beam_transformation(flexible_->axes());
  return T * (B0_.transpose() * (T.transpose() * local));
}

Vec12 OffsetElement::equivalent_loads(const ElementLoads& loads) const { return to_nodes(flexible_->equivalent_loads(loads)); }

Vec12 OffsetElement::thermal_loads(const Temperature& t) const { return to_nodes(flexible_->thermal_loads(t)); }

}  // namespace beamfea
