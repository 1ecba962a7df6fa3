#pragma once
// Mass matrices of the 3-D beam of elements/beam.hpp (Euler-Bernoulli or Timoshenko) and of a
// point mass.
//
// Consistent mass: M = int_0^L (rho A N_u^T N_u + rho I N_theta^T N_theta) dx with the shape
// functions that give the element its stiffness, so M and K are consistent:
//   - axial u and twist rx: linear; M = rho A L/6 [2 1; 1 2] and rho Ip L/6 [2 1; 1 2], the
//     torsional (polar) inertia Ip = Iy + Iz (the section's polar moment; exact for a circle,
//     the usual approximation otherwise);
//   - bending in each plane: translation v and section rotation theta interpolated by the
//     "interdependent interpolation" functions of the Timoshenko beam (Reddy 1997, "On locking-
//     free shear deformable beam finite elements", Comput. Methods Appl. Mech. Engrg. 149, 113-132,
//     eq. 31; Friedman & Kosmatka 1993, Comput. Struct. 47, 473-481), which are exact static
//     solutions of the Timoshenko equations and reduce to the cubic Hermite functions (theta = v')
//     when Phi = 0. Translational inertia rho A and rotary inertia rho I (Iz for bending in x-y,
//     Iy for x-z). With Phi = 0 this is the classical consistent matrix, rho A L/420 [156 22L 54
//     -13L; ...] plus the rotary part rho I/(30 L) [36 3L -36 3L; ...] (Przemieniecki 1968,
//     eqs. 11.18 and 11.41). The integral is evaluated by 4-point Gauss quadrature, exact for the
//     polynomials of degree 6 involved.
// Lumped mass: half of the member's translational mass rho A L at each node, and half of its
// rotary (rho Iy L, rho Iz L) and torsional (rho Ip L) inertia on the node's rotations: diagonal.
//
// DOF order and local axes exactly as elements/beam.hpp; bending in x-z uses theta = -ry
// (w' = -ry). Global: T^T M T with T = beam_transformation(R).
//
// Point mass: 6x6 diag(m, m, m) and the 3x3 rotational inertia (global axes, about the node) on
// the rotations. Exact for small motions: the kinetic energy of a rigid body whose reference
// point is the node, with its centre of mass at the node.
//
// Not supported: mass eccentricity (a centre of mass away from the node: use a rigid link to a
// node at the centre of mass), warping inertia.
#include "elements/beam.hpp"

namespace beamfea {

// Local mass matrix of a member of length L, density rho (mass per unit volume).
Mat12 beam_local_mass(const BeamSection& s, double rho, double L, MassKind kind);

// The planar shape functions of one bending plane at xi = x/L in [0, 1], over the element DOFs
// (v1, theta1, v2, theta2) with theta the section rotation: v = N_v d, theta = N_theta d.
// Phi: the plane's shear parameter (BeamSection::phi_y / phi_z; 0 for Euler-Bernoulli).
struct PlanarShape {
  Eigen::Matrix<double, 1, 4> v, theta;     // values
  Eigen::Matrix<double, 1, 4> dv, dtheta;   // derivatives along x (not xi)
};
PlanarShape timoshenko_shape(double xi, double L, double phi);

// 6x6 mass matrix of a point mass at a node: mass on the translations, inertia on the rotations.
Mat6 point_mass_matrix(double mass, const Mat3& inertia);

}  // namespace beamfea
