#include "elements/beam_mass.hpp"

#include <array>
#include <cassert>
#include <cmath>

namespace beamfea {

PlanarShape timoshenko_shape(double xi, double L, double phi) {
  // Reddy (1997) eq. 31 / Friedman & Kosmatka (1993), mu = 1/(1 + Phi).
  const double mu = 1.0 / (1.0 + phi);
  const double x2 = xi * xi, x3 = x2 * xi;
  PlanarShape s;
  s.v << mu * (2 * x3 - 3 * x2 - phi * xi + 1 + phi),
      mu * L * (x3 - (2 + 0.5 * phi) * x2 + (1 + 0.5 * phi) * xi),
      -mu * (2 * x3 - 3 * x2 - phi * xi),
      mu * L * (x3 - (1 - 0.5 * phi) * x2 - 0.5 * phi * xi);
  s.theta << 6 * mu / L * (x2 - xi),
      mu * (3 * x2 - (4 + phi) * xi + 1 + phi),
      -6 * mu / L * (x2 - xi),
      mu * (3 * x2 - (2 - phi) * xi);
  // d/dx = (1/L) d/dxi
  s.dv << mu / L * (6 * x2 - 6 * xi - phi),
      mu * (3 * x2 - 2 * (2 + 0.5 * phi) * xi + (1 + 0.5 * phi)),
      -mu / L * (6 * x2 - 6 * xi - phi),
      mu * (3 * x2 - 2 * (1 - 0.5 * phi) * xi - 0.5 * phi);
  s.dtheta << 6 * mu / (L * L) * (2 * xi - 1),
      mu / L * (6 * xi - (4 + phi)),
      -6 * mu / (L * L) * (2 * xi - 1),
      mu / L * (6 * xi - (2 - phi));
  return s;
}

namespace {

using Mat4 = Eigen::Matrix<double, 4, 4>;

// int_0^L (rhoA v^2 + rhoI theta^2) dx over (v1, theta1, v2, theta2), 4-point Gauss-Legendre
// (exact to degree 7; the integrands are of degree 6).
Mat4 planar_consistent_mass(double rhoA, double rhoI, double L, double phi) {
  const double a = std::sqrt(3.0 / 7.0 - 2.0 / 7.0 * std::sqrt(6.0 / 5.0));
  const double b = std::sqrt(3.0 / 7.0 + 2.0 / 7.0 * std::sqrt(6.0 / 5.0));
  const double wa = (18.0 + std::sqrt(30.0)) / 36.0, wb = (18.0 - std::sqrt(30.0)) / 36.0;
  const std::array<double, 4> pts{-b, -a, a, b};
  const std::array<double, 4> wts{wb, wa, wa, wb};
  Mat4 m = Mat4::Zero();
  for (int g = 0; g < 4; ++g) {
    const double xi = 0.5 * (1.0 + pts[g]);
    const double w = 0.5 * wts[g] * L;  // dx = L dxi, dxi = dt/2
    const PlanarShape s = timoshenko_shape(xi, L, phi);
    m += w * (rhoA * s.v.transpose() * s.v + rhoI * s.theta.transpose() * s.theta);
  }
  return m;
}

void place_planar(Mat12& M, const Mat4& mp, const std::array<int, 4>& dofs, const std::array<double, 4>& sign) {
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) M(dofs[a], dofs[b]) = sign[a] * sign[b] * mp(a, b);
}

}  // namespace

Mat12 beam_local_mass(const BeamSection& s, double rho, double L, MassKind kind) {
  assert(L > 0.0 && rho >= 0.0);
  Mat12 M = Mat12::Zero();
  const double m = rho * s.A * L;              // translational mass
  const double Ip = s.Iy + s.Iz;
  if (kind == MassKind::Lumped) {
    for (int k : {0, 1, 2, 6, 7, 8}) M(k, k) = 0.5 * m;
    M(3, 3) = M(9, 9) = 0.5 * rho * Ip * L;
    M(4, 4) = M(10, 10) = 0.5 * rho * s.Iy * L;
    M(5, 5) = M(11, 11) = 0.5 * rho * s.Iz * L;
    return M;
  }
  // axial and torsion: linear shape functions
  M(0, 0) = M(6, 6) = m / 3.0;
  M(0, 6) = M(6, 0) = m / 6.0;
  M(3, 3) = M(9, 9) = rho * Ip * L / 3.0;
  M(3, 9) = M(9, 3) = rho * Ip * L / 6.0;
  // bending in x-y: (v1, rz1, v2, rz2), theta = rz
  place_planar(M, planar_consistent_mass(rho * s.A, rho * s.Iz, L, s.phi_y(L)), {1, 5, 7, 11}, {1, 1, 1, 1});
  // bending in x-z: (w1, ry1, w2, ry2), theta = -ry
  place_planar(M, planar_consistent_mass(rho * s.A, rho * s.Iy, L, s.phi_z(L)), {2, 4, 8, 10}, {1, -1, 1, -1});
  return M;
}

Mat6 point_mass_matrix(double mass, const Mat3& inertia) {
  Mat6 M = Mat6::Zero();
  M.topLeftCorner<3, 3>() = mass * Mat3::Identity();
  M.bottomRightCorner<3, 3>() = inertia;
  return M;
}

}  // namespace beamfea
