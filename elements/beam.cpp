#include "elements/beam.hpp"

#include <cmath>

#include "core/errors.hpp"
#include "elements/beam_mass.hpp"
#include "elements/geometric_stiffness.hpp"
#include "elements/span_loads.hpp"

namespace beamfea {

Mat3 beam_local_axes(const Vec3& x1, const Vec3& x2, const Vec3& orientation) {
  const Vec3 d = x2 - x1;
  const double L = d.norm();
  if (!(L > 0.0)) throw Error("zero-length member");
  const Vec3 ex = d / L;
  const double on = orientation.norm();
  if (!(on > 0.0)) throw Error("orientation vector is zero");
  Vec3 ey = (orientation / on).cross(ex);
  if (ey.norm() < 1e-8) throw Error("orientation vector is parallel to the member");
  ey.normalize();
  const Vec3 ez = ex.cross(ey);
  Mat3 R;
  R.row(0) = ex;
  R.row(1) = ey;
  R.row(2) = ez;
  return R;
}

Mat12 beam_transformation(const Mat3& R) {
  Mat12 T = Mat12::Zero();
  for (int b = 0; b < 4; ++b) T.block<3, 3>(3 * b, 3 * b) = R;
  return T;
}

Mat12 beam_local_stiffness(const BeamSection& s, double L) {
  Mat12 k = Mat12::Zero();
  const double L2 = L * L, L3 = L2 * L;
  const double EA = s.E * s.A / L, GJ = s.G * s.J / L;
  // axial and torsion
  k(0, 0) = k(6, 6) = EA;
  k(0, 6) = k(6, 0) = -EA;
  k(3, 3) = k(9, 9) = GJ;
  k(3, 9) = k(9, 3) = -GJ;
  // bending in x-y: v (1, 7), rz (5, 11), Iz; Przemieniecki (1968) eq. 5.116 with Phi_y
  const double py = s.phi_y(L), cy = s.E * s.Iz / (1.0 + py);
  const double a = 12 * cy / L3, b = 6 * cy / L2, c = (4 + py) * cy / L, d = (2 - py) * cy / L;
  k(1, 1) = k(7, 7) = a;
  k(1, 7) = k(7, 1) = -a;
  k(1, 5) = k(5, 1) = k(1, 11) = k(11, 1) = b;
  k(7, 5) = k(5, 7) = k(7, 11) = k(11, 7) = -b;
  k(5, 5) = k(11, 11) = c;
  k(5, 11) = k(11, 5) = d;
  // bending in x-z: w (2, 8), ry (4, 10), Iy, Phi_z; note the sign change (w' = -ry)
  const double pz = s.phi_z(L), cz = s.E * s.Iy / (1.0 + pz);
  const double e = 12 * cz / L3, f = 6 * cz / L2, g = (4 + pz) * cz / L, h = (2 - pz) * cz / L;
  k(2, 2) = k(8, 8) = e;
  k(2, 8) = k(8, 2) = -e;
  k(2, 4) = k(4, 2) = k(2, 10) = k(10, 2) = -f;
  k(8, 4) = k(4, 8) = k(8, 10) = k(10, 8) = f;
  k(4, 4) = k(10, 10) = g;
  k(4, 10) = k(10, 4) = h;
  return k;
}

namespace {

// T^T k T for T = diag(R, R, R, R): block by block, R^T k_ij R (16 products of 3x3 matrices
// instead of two 12x12 ones; the element matrices of a small model's every analysis).
Mat12 to_global(const Mat12& k, const Mat3& R) {
  Mat12 K;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) K.block<3, 3>(3 * i, 3 * j).noalias() = R.transpose() * (k.block<3, 3>(3 * i, 3 * j) * R);
  return K;
}

}  // namespace

BeamElement::BeamElement(const BeamSection& section, const Vec3& x1, const Vec3& x2, const Vec3& orientation)
    : section_(section), X1_(x1), X2_(x2), L_((x2 - x1).norm()), R_(beam_local_axes(x1, x2, orientation)) {}

Mat12 BeamElement::local_stiffness() const { return condensed_ ? *condensed_ : beam_local_stiffness(section_, L_); }

Mat12 BeamElement::stiffness() const { return to_global(local_stiffness(), R_); }

Vec12 BeamElement::to_local(const Vec12& u) const {
  Vec12 local;
  for (int i = 0; i < 4; ++i) local.segment<3>(3 * i).noalias() = R_ * u.segment<3>(3 * i);
  return local;
}

Vec12 BeamElement::local_end_forces(const Vec12& u) const { return local_stiffness() * to_local(u); }

void BeamElement::condense_local(const Mat12& C) {
  condensed_ = std::make_shared<const Mat12>(C.transpose() * local_stiffness() * C);
}

Mat12 BeamElement::geometric_stiffness(const Vec12& f, GeometricStiffness kind) const {
  const Mat12 kg = kind == GeometricStiffness::Full ? beam_local_geometric_stiffness(L_, section_.A, section_.Iy, section_.Iz, f)
                                                    : beam_local_axial_geometric_stiffness(section_, L_, f);
  return to_global(kg, R_);
}

Mat12 BeamElement::mass(MassKind kind, double density) const {
  return to_global(beam_local_mass(section_, density, L_, kind), R_);
}

Vec12 BeamElement::equivalent_loads(const ElementLoads& loads) const {
  Vec12 f = equivalent_nodal_loads(L_, loads);
  if (loads.has_temperature()) f += thermal_loads(loads.temperature);
  return f;
}

Vec12 BeamElement::thermal_loads(const Temperature& t) const { return beam_thermal_loads(section_, t); }

Vec12 beam_thermal_loads(const BeamSection& section_, const Temperature& t) {
  // The restrained thermal strain and curvatures, eps = alpha dT, kappa_v = v'' = -alpha dT/dy,
  // kappa_w = w'' = -alpha dT/dz (hotter fibres lengthen); their equivalent loads are the virtual
  // work int B^T E (A eps, I kappa) dx of the element's strain-displacement B (linear u, Hermite v
  // and w, w' = -ry): an axial pair and an end-moment pair per plane.
  const double N = section_.E * section_.A * t.expansion * t.uniform;
  const double Mz = -section_.E * section_.Iz * t.expansion * t.gradient_y;  // E Iz kappa_v
  const double My = -section_.E * section_.Iy * t.expansion * t.gradient_z;  // E Iy kappa_w
  Vec12 f = Vec12::Zero();
  f(0) = -N;
  f(6) = N;
  f(5) = -Mz;
  f(11) = Mz;
  f(4) = My;
  f(10) = -My;
  return f;
}

Vec6 BeamElement::section_forces(double s, const Vec12& end_forces, const ElementLoads& loads, CutSide side) const {
  return section_forces_at(s, end_forces, loads, side);
}

Vec12 LinearBeam::displacements(const NodalPoses& p) const {
  Vec12 u;
  u << p.x1 - X1_, log_so3(p.R1), p.x2 - X2_, log_so3(p.R2);
  return u;
}

ElementResponse LinearBeam::respond(const NodalPoses& p, Evaluate what) const {
  const Vec12 u = displacements(p);
  ElementResponse r;
  const Mat12 kl = local_stiffness();  // made once for K and the local end forces
  const Mat12 K = to_global(kl, R_);
  r.force = K * u;
  r.energy = 0.5 * u.dot(r.force);
  r.local_end_forces = kl * to_local(u);
  if (what == Evaluate::ForceAndTangent) r.tangent = K;
  else r.tangent.setZero();
  return r;
}

NodalPoses LinearBeam::advance(const NodalPoses& p, const Vec12& d) const {
  return {p.x1 + d.segment<3>(0), p.x2 + d.segment<3>(6), exp_so3(log_so3(p.R1) + d.segment<3>(3)),
          exp_so3(log_so3(p.R2) + d.segment<3>(9))};
}

Vec12 LinearBeam::fixed_end_forces_at(const NodalPoses&, const ElementLoads& loads) const {
  return -equivalent_loads(loads);
}

Vec3 LinearBeam::displacement_at(const NodalPoses& p, double xi) const {
  return beam_displacement_at(R_, L_, displacements(p), xi);
}

Vec3 beam_displacement_at(const Mat3& R, double L, const Vec12& u_global, double xi) {
  const Vec12 ul = beam_transformation(R) * u_global;
  const double N1 = 1 - 3 * xi * xi + 2 * xi * xi * xi;
  const double N2 = L * (xi - 2 * xi * xi + xi * xi * xi);
  const double N3 = 3 * xi * xi - 2 * xi * xi * xi;
  const double N4 = L * (-xi * xi + xi * xi * xi);
  Vec3 local;
  local.x() = (1 - xi) * ul(0) + xi * ul(6);
  local.y() = N1 * ul(1) + N2 * ul(5) + N3 * ul(7) + N4 * ul(11);
  local.z() = N1 * ul(2) - N2 * ul(4) + N3 * ul(8) - N4 * ul(10);
  return R.transpose() * local;
}

Mat6 cantilever_tip_stiffness(const BeamSection& s, double L) { return beam_local_stiffness(s, L).bottomRightCorner<6, 6>(); }

}  // namespace beamfea
