#pragma once
// A beam element with rigid arms: its flexible part (the held element) lies between two points
// that are rigidly attached to its nodes, at the vectors o1, o2 (global components at the
// reference) from node 1 and node 2. It states eccentric connections (a member whose axis misses
// the node) and rigid end zones (joint panel zones, Frame3DD's finite node radii: o along the
// member's axis). A wrapper of the element contract (elements/frame_element.hpp) around any
// FrameElement whose reference nodes are the flexible ends.
//
// Formulation: exact rigid arms (McGuire, Gallagher & Ziemian, Matrix Structural Analysis, 2nd
// ed. (2000), section 13.3 "rigid end offsets"; OpenSees' joint offsets of its coordinate
// transformations). The flexible end a follows node a as one rigid body:
//   linear arms (small rotations, around a LinearBeam):  x'_a = x_a + o_a + theta_a x o_a,
//   finite arms (co-rotational):                          x'_a = x_a + R_a o_a,
// with the end's rotation R'_a = R_a. The increments of the flexible ends are d' = B d, per end
// B_a = [I  -[a]x; 0  I], a = o_a (linear) or R_a o_a (finite), so that
//   force   f = B^T f',          mass M = B^T M' B  (the arms carry no mass),
//   tangent K = B^T K' B + sum_a ( a f'_a^T - (a . f'_a) I ) on node a's rotations   (finite arms:
//            the arm turning under the flexible end's force f'_a; not symmetric, as the
//            co-rotational tangent is not),
//   geometric stiffness B^T Kg' B + sum_a ( sym(F_a o_a^T) - (F_a . o_a) I ) on node a's
//            rotations, F_a the force on the element at its flexible end (global): the symmetric
//            second-order work of the end force on the turning arm, the arm's share of the loaded
//            stiffness at the reference (buckling; modal about a loaded state).
// Reported: local axes, length, end forces, section forces, member loads' fixed-end forces and the
// drawn shape are the flexible part's, at its ends (the section forces at a node are those at the
// flexible end, carried to the node by statics through the arm). Equivalent nodal loads and
// thermal loads act on the nodes: B^T of the flexible part's (local components).
// Member loads: on the flexible part, positions s in [0, length()] along it.
#include <array>
#include <memory>

#include "elements/frame_element.hpp"

namespace beamfea {

enum class ArmKinematics { Linear, Finite };

class OffsetElement final : public FrameElement {
 public:
  // `flexible`: the element between the flexible ends; `offsets`: o1, o2 (global) from the nodes to
  // them at the reference.
  OffsetElement(std::unique_ptr<FrameElement> flexible, const std::array<Vec3, 2>& offsets, ArmKinematics arms);

  double length() const override { return flexible_->length(); }
  const Mat3& axes() const override { return flexible_->axes(); }
  NodalPoses reference_poses() const override;
  Mat3 axes_at(const NodalPoses& p) const override { return flexible_->axes_at(flexible_poses(p)); }

  Mat12 stiffness() const override { return K_; }
  Vec12 local_end_forces(const Vec12& u) const override { return flexible_->local_end_forces(B0_ * u); }
  ElementResponse respond(const NodalPoses& p, Evaluate what) const override;
  NodalPoses advance(const NodalPoses& p, const Vec12& d) const override { return flexible_->advance(p, d); }

  using FrameElement::geometric_stiffness;
  Mat12 geometric_stiffness(const Vec12& local_end_forces, GeometricStiffness kind) const override;
  Mat12 mass(MassKind kind, double density) const override;
  Mat12 mass_at(const NodalPoses& p, MassKind kind, double density) const override;
  Vec12 equivalent_loads(const ElementLoads& loads) const override;
  Vec12 fixed_end_forces_at(const NodalPoses& p, const ElementLoads& loads) const override {
    return flexible_->fixed_end_forces_at(flexible_poses(p), loads);
  }
  Vec12 thermal_loads(const Temperature& t) const override;
  Vec6 section_forces(double s, const Vec12& end_forces, const ElementLoads& loads, CutSide side) const override {
    return flexible_->section_forces(s, end_forces, loads, side);
  }
  // The flexible part's point at xi (its ends at xi = 0, 1 are the flexible ends, not the nodes).
  Vec3 displacement_at(const NodalPoses& p, double xi) const override {
    return flexible_->displacement_at(flexible_poses(p), xi);
  }

  // The flexible ends' poses at the nodes' poses p.
  NodalPoses flexible_poses(const NodalPoses& p) const;
  const std::array<Vec3, 2>& offsets() const { return o_; }

 private:
  // B at the arms a1, a2 (global).
  static Mat12 arm_map(const Vec3& a1, const Vec3& a2);
  // B^T (local A, global components through T of the flexible axes) B, for local-axis vectors.
  Vec12 to_nodes(const Vec12& local) const;

  std::unique_ptr<FrameElement> flexible_;
  std::array<Vec3, 2> o_;
  ArmKinematics arms_;
  Mat12 B0_;  // B at the reference
  Mat12 K_;   // B0^T K' B0
};

}  // namespace beamfea
