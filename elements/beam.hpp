#pragma once
// 3-D beam, 12 DOF, Euler-Bernoulli or shear-deformable (Timoshenko): the linear-elastic basic
// element.
//
// DOF order (global and local): [u1 v1 w1 rx1 ry1 rz1  u2 v2 w2 rx2 ry2 rz2], node 1 then node 2.
// Local axes: x from node 1 to node 2; `orientation` is a vector in the local x-z plane;
//   y = orientation x x (normalised), z = x x y  (OpenSees' vecxz convention).
// Iz governs bending in the local x-y plane (v, rz); Iy bending in the local x-z plane (w, ry).
// Stiffness: the exact matrix of Przemieniecki, Theory of Matrix Structural Analysis (1968),
// eq. 5.116: with the shear parameters Phi_y = 12 E Iz / (G Asy L^2) (bending in x-y, shear
// along y) and Phi_z = 12 E Iy / (G Asz L^2), Asy = A/ky, Asz = A/kz the shear areas, e.g.
//   k(v1,v1) = 12 E Iz / (L^3 (1 + Phi_y)),  k(rz1,rz1) = (4 + Phi_y) E Iz / (L (1 + Phi_y)),
//   k(rz1,rz2) = (2 - Phi_y) E Iz / (L (1 + Phi_y)).
// Phi = 0 (no shear areas given: BeamSection::shear_deformable() false) is the Euler-Bernoulli
// matrix (McGuire, Gallagher & Ziemian, Matrix Structural Analysis, 2nd ed., eq. 4.34). The
// Timoshenko matrix is exact for a prismatic member without span loads: it is the stiffness of
// the "interdependent interpolation" shape functions (elements/beam_mass.hpp), which solve the
// homogeneous Timoshenko equations, so one element gives the exact cantilever tip deflection
// P L^3 / (3 E I) + P L / (G As). Not supported: warping (end releases and offsets are wrappers:
// elements/frame_element.hpp).
//
// The element contract it fulfils: elements/frame_element.hpp.
#include <memory>
#include <Eigen/Core>

#include "core/model.hpp"
#include "elements/frame_element.hpp"

namespace beamfea {

struct BeamSection {
  double E = 0, G = 0, A = 0, Iy = 0, Iz = 0, J = 0;
  // Shear areas A/ky (shear along local y) and A/kz (along local z) of a Timoshenko beam;
  // 0 means rigid in shear (Euler-Bernoulli).
  double Asy = 0, Asz = 0;
  bool shear_deformable() const { return Asy > 0.0 || Asz > 0.0; }
  // Phi_y = 12 E Iz / (G Asy L^2) and Phi_z = 12 E Iy / (G Asz L^2) for a member of length L
  // (0 for Euler-Bernoulli): the ratio of shear to bending flexibility.
  double phi_y(double L) const { return Asy > 0.0 ? 12.0 * E * Iz / (G * Asy * L * L) : 0.0; }
  double phi_z(double L) const { return Asz > 0.0 ? 12.0 * E * Iy / (G * Asz * L * L) : 0.0; }
};

// Equivalent nodal loads (local) of a temperature change on a beam of this section: those of
// FrameElement::thermal_loads (an axial pair E A alpha dT and an end-moment pair per plane,
// E I alpha dT/dy and E I alpha dT/dz; the same for Timoshenko beams: a uniform curvature shears
// nothing). Independent of the length.
Vec12 beam_thermal_loads(const BeamSection& section, const Temperature& t);

// Rows are the local axes (x, y, z) in global components: v_local = R * v_global.
// Throws ModelError if the orientation is parallel to the member or the length is zero.
Mat3 beam_local_axes(const Vec3& x1, const Vec3& x2, const Vec3& orientation);

// 12x12 block-diagonal transformation diag(R, R, R, R).
Mat12 beam_transformation(const Mat3& R);

// Local elastic stiffness of a member of length L (Timoshenko when s.shear_deformable()).
Mat12 beam_local_stiffness(const BeamSection& s, double L);

// Stiffness of the tip (end 2) of a cantilever of length L clamped at end 1, in the beam's local
// axes (6x6, x along the beam): the end-2 block of the local matrix. Pashkevich, Klimchik &
// Chablat (2010) eq. 39 (a virtual spring's stiffness "from a beam").
Mat6 cantilever_tip_stiffness(const BeamSection& s, double L);

// What every beam kind shares: the section, the reference geometry, the linear local element and
// the answers that do not depend on the geometric transformation (linear stiffness, geometric
// stiffness, mass, member and thermal loads, section forces). LinearBeam and CorotationalBeam
// add the kinematics (elements/frame_element.hpp).
class BeamElement : public FrameElement {
 public:
  BeamElement(const BeamSection& section, const Vec3& x1, const Vec3& x2, const Vec3& orientation);

  double length() const override { return L_; }
  const Mat3& axes() const override { return R_; }
  NodalPoses reference_poses() const override { return {X1_, X2_, Mat3::Identity(), Mat3::Identity()}; }
  Mat12 stiffness() const override;
  Vec12 local_end_forces(const Vec12& u) const override;  // kl T u
  // T^T kg T, kg of elements/geometric_stiffness.hpp: Full, McGuire's (its Euler-Bernoulli
  // coefficients also for a Timoshenko beam); Axial, with the shear-deformable coefficients.
  using FrameElement::geometric_stiffness;
  Mat12 geometric_stiffness(const Vec12& local_end_forces, GeometricStiffness kind) const override;
  // T^T m T, m of elements/beam_mass.hpp.
  Mat12 mass(MassKind kind, double density) const override;
  Vec12 equivalent_loads(const ElementLoads& loads) const override;
  Vec12 thermal_loads(const Temperature& t) const override;
  Vec6 section_forces(double s, const Vec12& end_forces, const ElementLoads& loads, CutSide side) const override;

  const BeamSection& section() const { return section_; }
  // The local element k: beam_local_stiffness(section, L), or C^T k C after condense_local.
  // Made on demand, as are T and K = T^T k T: a beam keeps its section, its geometry and R
  // (about 230 bytes; a million-member lattice keeps 2.4 GB less than with k, T and K stored).
  Mat12 local_stiffness() const;
  // Replaces the local element k by C^T k C: a static condensation (elements/released_element.hpp)
  // that every answer built on k follows (stiffness, local end forces, response at a state).
  void condense_local(const Mat12& C);
  // T = diag(R, R, R, R).
  Mat12 transformation() const { return beam_transformation(R_); }

 protected:
  Vec12 to_local(const Vec12& u) const;  // T u: the end vectors in the local axes

  BeamSection section_;
  Vec3 X1_, X2_;
  double L_;
  Mat3 R_;
  std::shared_ptr<const Mat12> condensed_;  // C^T k C of a released beam; null otherwise
};

// The linear beam: small displacements and rotations. At a state, its displacements are
// u = [x1 - X1, log R1, x2 - X2, log R2]; force K u, tangent K, energy u^T K u / 2.
class LinearBeam final : public BeamElement {
 public:
  using BeamElement::BeamElement;

  Vec12 internal_force(const Vec12& u) const { return stiffness() * u; }  // global
  double strain_energy(const Vec12& u) const { return 0.5 * u.dot(internal_force(u)); }
  // The small displacements u of a state (rotation vectors log R).
  Vec12 displacements(const NodalPoses& p) const;

  Mat3 axes_at(const NodalPoses&) const override { return R_; }
  ElementResponse respond(const NodalPoses& p, Evaluate what) const override;
  NodalPoses advance(const NodalPoses& p, const Vec12& d) const override;
  Mat12 mass_at(const NodalPoses&, MassKind kind, double density) const override { return mass(kind, density); }
  // Small displacements: the loads keep their reference local components.
  Vec12 fixed_end_forces_at(const NodalPoses& p, const ElementLoads& loads) const override;
  Vec3 displacement_at(const NodalPoses& p, double xi) const override;
};

// Cubic (Hermite) interpolation of a beam's displacement at xi in [0, 1], in global axes,
// from the 12 global end displacements: used to draw the deformed shape (Euler-Bernoulli shape
// functions also for a Timoshenko beam: a drawing, not a result).
Vec3 beam_displacement_at(const Mat3& R, double L, const Vec12& u_global, double xi);

}  // namespace beamfea
