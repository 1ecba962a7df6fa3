#pragma once
// Span loads: the loads between the nodes of one beam element (elements/beam.hpp), in the
// element's local axes: equivalent nodal loads, fixed-end forces, section forces along the
// element, and the consistent vector of a dead load (fixed direction) in a rotated configuration.
// The elements answer through the contract (FrameElement::equivalent_loads, section_forces,
// fixed_end_forces_at); the model's member loads become span loads in solvers/member_loading.hpp.
//
// Formulation. The equivalent (consistent) nodal loads are the virtual work of the load on the
// element's shape functions, f = int N^T q ds + N(a)^T P + N'(a)^T m: linear for the axial
// displacement and the twist, the cubic Hermite functions for the deflections v, w
//   N1 = 1 - 3 xi^2 + 2 xi^3,   N2 = L (xi - 2 xi^2 + xi^3),
//   N3 = 3 xi^2 - 2 xi^3,        N4 = L (xi^3 - xi^2),          xi = s / L,
// with v = N1 v1 + N2 rz1 + N3 v2 + N4 rz2, w = N1 w1 - N2 ry1 + N3 w2 - N4 ry2 (w' = -ry), as
// elements/beam.cpp. The Hermite cubics solve the homogeneous Euler-Bernoulli equation, so these
// are exactly the negated fixed-end reactions of the clamped member (Przemieniecki 1968, sec. 5.8;
// McGuire, Gallagher & Ziemian 2000, sec. 4.4 and Appendix tables): the nodal displacements of a
// model loaded by them are exact.
// Distributed loads vary linearly between s = a and s = b; their integrals (degree <= 4) use
// 3-point Gauss-Legendre quadrature, exact to degree 5.
//
// Conventions: local axes and DOF order of elements/beam.hpp, [u1 v1 w1 rx1 ry1 rz1 u2 ... rz2];
// loads in local components; positions s in [0, L] from node 1.
//   equivalent nodal loads: forces the load puts on the nodes (add to the external load vector);
//   fixed-end forces:       forces the nodes exert on the clamped, loaded element = -equivalent;
//   end forces of a loaded element: k u + fixed-end forces (forces on the element at its ends);
//   section forces: internal forces on the positive face of a cut at s (N > 0 tension), the
//   convention of docs/conventions.md: -end forces at node 1, +end forces at node 2.
//
// Not supported: distributed moments; loads on an eccentric line (torque from an offset load).
#include <vector>

#include "elements/beam.hpp"

namespace beamfea {

// A distributed load (force per unit length) varying linearly from q_a at s = a to q_b at s = b.
struct LocalDistributedLoad {
  double a = 0.0, b = 0.0;
  Vec3 q_a = Vec3::Zero(), q_b = Vec3::Zero();
};

// A concentrated force and moment at s = a.
struct LocalPointLoad {
  double a = 0.0;
  Vec3 force = Vec3::Zero();
  Vec3 moment = Vec3::Zero();
};

// The loads between the nodes of one element, local components, and the temperature change over
// it (whose equivalent loads need the section: the element's equivalent_loads adds them,
// FrameElement::thermal_loads; the free functions below are the span loads' alone).
struct ElementLoads {
  std::vector<LocalDistributedLoad> distributed;
  std::vector<LocalPointLoad> points;
  Temperature temperature;
  bool has_temperature() const {
    return temperature.expansion != 0.0 && (temperature.uniform != 0.0 || temperature.gradient_y != 0.0 || temperature.gradient_z != 0.0);
  }
  bool empty() const { return distributed.empty() && points.empty() && !has_temperature(); }
};

// Equivalent nodal loads (local) of the loads on an element of length L.
Vec12 equivalent_nodal_loads(double L, const LocalDistributedLoad& q);
Vec12 equivalent_nodal_loads(double L, const LocalPointLoad& p);
Vec12 equivalent_nodal_loads(double L, const ElementLoads& loads);
// Fixed-end forces (local): -equivalent_nodal_loads.
Vec12 fixed_end_forces(double L, const ElementLoads& loads);

// Where a point load sits exactly at the cut: which side the cut is taken on.
enum class CutSide { Before, After };

// Section forces [N Vy Vz T My Mz] (local, positive face) at s in [0, L], from the element's end
// forces (k u + fixed-end forces) and its loads, by the equilibrium of the part [0, s]:
//   F(s) = -F1 - int_0^s q - sum P,   M(s) = -M1 + s e_x x F1 - int_0^s (t - s) e_x x q dt
//          - sum [(a - s) e_x x P + m].
Vec6 section_forces_at(double s, const Vec12& end_forces, const ElementLoads& loads, CutSide side = CutSide::After);

// Positions (ascending, in [0, L]) where the section forces are discontinuous or change law:
// starts and ends of distributed loads, point loads.
std::vector<double> load_discontinuities(double L, const ElementLoads& loads);

// A dead load in the co-rotational setting. A load of fixed global direction on an element whose
// chord has the unit direction e: the equivalent nodal loads in global axes depend on e alone
// (the Hermite interpolation is the same in the local x-y and x-z planes), as
//   force-like load Q (a distributed load of one shape, or a point force):
//     F_i = alpha_i (Q - (e.Q) e) + gamma_i (e.Q) e,     M_i = beta_i e x Q
//   moment-like load m (a point moment):
//     F_i = eps_i e x m,     M_i = delta_i (m - (e.m) e) + gamma_i (e.m) e
// with scalar coefficients per node i = 1, 2 read off the local equivalent loads of unit loads.
struct DeadLoadTerm {
  bool moment = false;   // moment-like (point moment) rather than force-like
  Vec3 Q = Vec3::Zero(); // global vector: force (per unit length for a distributed shape) or moment
  double alpha[2]{}, beta[2]{}, gamma[2]{};  // force-like; moment-like uses eps in alpha, delta in beta
};
// The terms of one distributed load q(s) = q_a (1 - t) + q_b t (global q_a, q_b, t = (s-a)/(b-a)),
// or of a point force/moment, on an element of reference length L.
std::vector<DeadLoadTerm> dead_load_terms(double L, double a, double b, const Vec3& q_a, const Vec3& q_b);
std::vector<DeadLoadTerm> dead_load_terms(double L, double a, const Vec3& force, const Vec3& moment);

// Global equivalent nodal loads [F1 M1 F2 M2] of the terms for the chord direction e.
Vec12 dead_load_vector(const std::vector<DeadLoadTerm>& terms, const Vec3& e);
// Their derivative with respect to the chord vector d = x2 - x1 (length ln): 12 x 3, so that
// dF = D (dx2 - dx1); de = (I - e e^T) dd / ln.
Eigen::Matrix<double, 12, 3> dead_load_derivative(const std::vector<DeadLoadTerm>& terms, const Vec3& e, double ln);

}  // namespace beamfea
