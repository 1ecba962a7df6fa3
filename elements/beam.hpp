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
// P L^3 / (3 E I) + P L / (G As). Not supported: warping, offsets, member loads.
//
// An element answers three questions and never touches the global system: internal force,
// tangent stiffness, strain energy, for given nodal kinematics.
#include <Eigen/Core>

#include "core/model.hpp"

namespace beamfea {

using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat12 = Eigen::Matrix<double, 12, 12>;

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

// The linear beam in global axes: kinematics are the 12 global nodal displacements/rotations.
class LinearBeam {
 public:
  LinearBeam(const BeamSection& section, const Vec3& x1, const Vec3& x2, const Vec3& orientation);

  const Mat12& stiffness() const { return K_; }                      // global tangent
  Vec12 internal_force(const Vec12& u) const { return K_ * u; }      // global
  double strain_energy(const Vec12& u) const { return 0.5 * u.dot(K_ * u); }
  // Forces exerted on the element at its ends, local axes: [N1 Vy1 Vz1 T1 My1 Mz1 N2 ... Mz2].
  Vec12 local_end_forces(const Vec12& u) const { return kl_ * (T_ * u); }

  double length() const { return L_; }
  const Mat3& axes() const { return R_; }
  const Mat12& local_stiffness() const { return kl_; }
  const Mat12& transformation() const { return T_; }

 private:
  double L_;
  Mat3 R_;
  Mat12 T_;
  Mat12 kl_;
  Mat12 K_;
};

// Cubic (Hermite) interpolation of a beam's displacement at xi in [0, 1], in global axes,
// from the 12 global end displacements: used to draw the deformed shape (Euler-Bernoulli shape
// functions also for a Timoshenko beam: a drawing, not a result).
Vec3 beam_displacement_at(const Mat3& R, double L, const Vec12& u_global, double xi);

}  // namespace beamfea
