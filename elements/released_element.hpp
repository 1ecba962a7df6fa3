#pragma once
// A beam element with end releases: some of its local end DOFs (ux uy uz rx ry rz at node 1
// and/or node 2, in the member's local axes) do not follow the node: a pinned end (ry, rz), a
// sliding end (uy), a torsion release (rx). A wrapper of the element contract
// (elements/frame_element.hpp) around a beam (LinearBeam or CorotationalBeam).
//
// Formulation: exact static condensation of the released DOFs inside the element, no extra nodes
// (Przemieniecki, Theory of Matrix Structural Analysis (1968), section 11.3; McGuire, Gallagher &
// Ziemian, Matrix Structural Analysis, 2nd ed. (2000), section 4.8 "condensation"). With r the
// retained and c the released local DOFs of the local element k, the released displacements take
// the values that leave their forces zero, u_c = -k_cc^{-1} k_cr u_r, i.e. u = C u with
//   C = [I 0; -k_cc^{-1} k_cr 0]  (rows and columns in the local DOF order, released columns zero),
// and the element's local stiffness is k* = C^T k C (its released rows and columns zero).
//   - Stiffness, local end forces and the response at a state: the held beam's local element is
//     replaced by k* (BeamElement::condense_local), so the linear beam is exact and the
//     co-rotational beam condenses its local element at every state (the released DOFs are
//     relative motions in the co-rotated frame: exact within its moderate local deformations).
//   - Member and thermal loads: their local equivalent loads through the same C, f* = C^T f (the
//     fixed-end forces of the released element: zero at the released DOFs).
//   - Mass and geometric stiffness: C^T m C and C^T kg C in the local axes (the released end's
//     motion interpolated by the condensed, statically exact shape; for modes and buckling this is
//     the consistent Rayleigh-Ritz choice, exact as the member is divided further).
//   - Section forces: by statics from the end forces (zero at the released DOFs).
//   - Drawn shape: the held beam's, its released end rotations and translations relaxed by C.
// A set of releases that leaves k_cc singular (rx at both ends, ux at both ends, uy at both ends,
// every rotation at both ends, ...) lets the element move without strain while holding nothing:
// the constructor throws Error naming the releases (the caller names the element).
#include <array>
#include <memory>

#include "elements/beam.hpp"

namespace beamfea {

// released[k]: local DOF k (the contract's DOF order) released.
using Releases = std::array<bool, 12>;

// The condensation map C above for the local stiffness k. Throws Error when the released DOFs
// can move without strain (k_cc singular).
Mat12 release_condensation(const Mat12& k, const Releases& released);

// "start: ry, rz; end: uy" for the message of a release set.
std::string describe_releases(const Releases& released);

class ReleasedElement final : public FrameElement {
 public:
  ReleasedElement(std::unique_ptr<BeamElement> beam, const Releases& released);

  double length() const override { return beam_->length(); }
  const Mat3& axes() const override { return beam_->axes(); }
  NodalPoses reference_poses() const override { return beam_->reference_poses(); }
  Mat3 axes_at(const NodalPoses& p) const override { return beam_->axes_at(p); }

  Mat12 stiffness() const override { return beam_->stiffness(); }
  Vec12 local_end_forces(const Vec12& u) const override { return beam_->local_end_forces(u); }
  ElementResponse respond(const NodalPoses& p, Evaluate what) const override { return beam_->respond(p, what); }
  NodalPoses advance(const NodalPoses& p, const Vec12& d) const override { return beam_->advance(p, d); }

  using FrameElement::geometric_stiffness;
  Mat12 geometric_stiffness(const Vec12& local_end_forces, GeometricStiffness kind) const override;
  Mat12 mass(MassKind kind, double density) const override;
  Mat12 mass_at(const NodalPoses& p, MassKind kind, double density) const override;
  Vec12 equivalent_loads(const ElementLoads& loads) const override { return C_.transpose() * beam_->equivalent_loads(loads); }
  Vec12 fixed_end_forces_at(const NodalPoses& p, const ElementLoads& loads) const override {
    return C_.transpose() * beam_->fixed_end_forces_at(p, loads);
  }
  Vec12 thermal_loads(const Temperature& t) const override { return C_.transpose() * beam_->thermal_loads(t); }
  Vec6 section_forces(double s, const Vec12& end_forces, const ElementLoads& loads, CutSide side) const override {
    return beam_->section_forces(s, end_forces, loads, side);
  }
  Vec3 displacement_at(const NodalPoses& p, double xi) const override;

  const Releases& released() const { return released_; }
  // The map C from the retained to all local DOFs (local axes).
  const Mat12& condensation() const { return C_; }

 private:
  // C^T (T A T^T) C in global axes, T the transformation of the local axes `axes`.
  Mat12 condensed(const Mat12& A, const Mat3& axes) const;

  std::unique_ptr<BeamElement> beam_;
  Releases released_;
  Mat12 C_;
};

}  // namespace beamfea
