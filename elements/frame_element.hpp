#pragma once
// The element contract: what every two-node frame element answers, so that every analysis
// (linear statics, stiffness, buckling, modal, path following, vibrations along a path)
// assembles every element kind the same way (in the spirit of MFEM's integrators and ae108's
// element concept). An element never touches the global system: it answers for its own 12 DOFs
// and the caller scatters.
//
// Element kinds implementing it (each Euler-Bernoulli or Timoshenko by its section,
// BeamSection::shear_deformable()):
//   LinearBeam        (elements/beam.hpp)              small displacements and rotations;
//   CorotationalBeam  (elements/corotational_beam.hpp) large displacements, finite rotations.
// Both share the linear local element (beam_local_stiffness) and differ in the geometric
// transformation from the nodal kinematics to its local deformations (OpenSees' split).
// Behaviours that transform an element are FrameElements that hold another FrameElement and
// transform what it answers, so that no analysis branches on them (solvers/element_factory.hpp
// makes them):
//   ReleasedElement (elements/released_element.hpp) end releases: a condensation of released DOFs;
//   OffsetElement   (elements/offset_element.hpp)   rigid end zones and offsets: the rigid-arm
//                                                   transformation of force, tangent and mass.
// Tension-only and compression-only members are not an element transformation but a choice of which
// members are in the structure: an active set that the static solvers iterate
// (solvers/second_order.hpp), each member answering as itself or not at all.
//
// DOF order, global and local: [u1 v1 w1 rx1 ry1 rz1  u2 v2 w2 rx2 ry2 rz2], node 1 then node 2.
// Local axes: x from node 1 to node 2, y and z from the orientation vector (elements/beam.hpp);
// "local" below means these axes at the reference configuration, or the co-rotated axes at a
// state where a method takes NodalPoses. Iz governs bending in x-y (v, rz), Iy in x-z (w, ry).
//
// Kinematics: NodalPoses, the current positions and total rotations (from the reference
// configuration) of the two nodes. `advance` is the increment convention that `force` and
// `tangent` refer to: d = [du1 dw1 du2 dw2] (global axes),
//   CorotationalBeam: x <- x + du, R <- exp(dw) R   (dw a spatial spin);
//   LinearBeam:       x <- x + du, theta <- theta + dw  (rotation vectors add; theta = log R,
//                     valid on |theta| < pi: the small-rotation theory).
// `force` is the gradient of `energy` along d and `tangent` = d(force)/d(d) along the same
// increments (tangent(i, j) = d force_i / d d_j).
//
// Forces: `force` and `tangent` are global. End forces are the forces exerted ON the element at
// its ends, local components [N1 Vy1 Vz1 T1 My1 Mz1  N2 Vy2 Vz2 T2 My2 Mz2] (N2 > 0: tension).
// Section forces at a cut follow docs/conventions.md (positive face: -end forces at node 1).
// Member loads (ElementLoads, elements/span_loads.hpp) are given in local components at the
// reference, positions s in [0, L] from node 1.
#include "core/model.hpp"

namespace beamfea {

using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat12 = Eigen::Matrix<double, 12, 12>;

struct ElementLoads;     // elements/span_loads.hpp
enum class CutSide;      // elements/span_loads.hpp

enum class MassKind { Consistent, Lumped };

// Which geometric (initial-stress) stiffness an element gives (docs/analyses/second-order.md):
//   Full   the axial-force terms, Wagner's torsion term and the end-moment and torque couplings
//          (McGuire, Gallagher & Ziemian 2000, eq. 9.18: lateral-torsional buckling);
//   Axial  the axial-force terms alone, with the shear-deformable coefficients on a Timoshenko
//          beam (Przemieniecki 1968; Frame3DD's geometric_K), and Wagner's torsion term
//          N (Iy + Iz)/(A L): the common P-Delta convention.
// Both take the element's mean axial force and assume a linear moment diagram between its ends.
enum class GeometricStiffness { Full, Axial };

// Positions x_i and total rotations R_i (from the reference configuration) of the two nodes.
struct NodalPoses {
  Vec3 x1 = Vec3::Zero(), x2 = Vec3::Zero();
  Mat3 R1 = Mat3::Identity(), R2 = Mat3::Identity();
};

// What `respond` computes: the internal force, energy and end forces alone (a residual), or the
// tangent as well.
enum class Evaluate { Force, ForceAndTangent };

struct ElementResponse {
  Vec12 force = Vec12::Zero();             // global internal force, conjugate to `advance`'s d
  Mat12 tangent;                           // d force / d d (respond sets it: zero when not asked)
  double energy = 0.0;                     // strain energy
  Vec12 local_end_forces = Vec12::Zero();  // forces on the element at its ends, local axes at the state
};

// A temperature change over the cross-section, linear in y and z: Delta T(y, z) = uniform +
// gradient_y y + gradient_z z (local axes, the section's centroid at y = z = 0), and the
// material's coefficient of thermal expansion. No input reads it yet: the slot of the contract
// for thermal loads.
struct Temperature {
  double expansion = 0.0;   // coefficient of thermal expansion alpha (strain per degree)
  double uniform = 0.0;     // Delta T at the centroid
  double gradient_y = 0.0;  // d(Delta T)/dy
  double gradient_z = 0.0;  // d(Delta T)/dz
};

class FrameElement {
 public:
  virtual ~FrameElement() = default;

  // Reference geometry: length and local axes (rows are x, y, z in global components).
  virtual double length() const = 0;
  virtual const Mat3& axes() const = 0;
  // The nodes' poses at the reference configuration (identity rotations).
  virtual NodalPoses reference_poses() const = 0;
  // Local axes at a state (rows, global components): the co-rotated axes of a co-rotational
  // element, the reference axes of a linear one.
  virtual Mat3 axes_at(const NodalPoses& p) const = 0;

  // Linear (small-displacement) answers, global displacements u in the DOF order above.
  // Elastic stiffness at the reference, global: K = T^T k T (by value: a beam keeps k and R
  // alone, not K, so that a million-member lattice keeps a gigabyte less).
  virtual Mat12 stiffness() const = 0;
  // Local end forces k T u of the small displacements u (without member loads).
  virtual Vec12 local_end_forces(const Vec12& u) const = 0;

  // The element at a state: internal force, tangent, energy, end forces (see above).
  virtual ElementResponse respond(const NodalPoses& p, Evaluate what) const = 0;
  // The state `p` moved by the increment d (the convention the tangent refers to).
  virtual NodalPoses advance(const NodalPoses& p, const Vec12& d) const = 0;

  // Geometric (initial-stress) stiffness at the reference, global, of the element carrying the
  // local end forces f: the linearised stiffness about that state is stiffness() + this (for
  // buckling and loaded modes). Linear in f, symmetric. `kind` picks its terms (see above).
  virtual Mat12 geometric_stiffness(const Vec12& local_end_forces, GeometricStiffness kind) const = 0;
  Mat12 geometric_stiffness(const Vec12& local_end_forces) const {
    return geometric_stiffness(local_end_forces, GeometricStiffness::Full);
  }

  // Mass matrix (global) of the material's density (mass per unit volume): at the reference, and
  // at a state (the local mass turned to the axes at the state; mass is conserved).
  virtual Mat12 mass(MassKind kind, double density) const = 0;
  virtual Mat12 mass_at(const NodalPoses& p, MassKind kind, double density) const = 0;

  // Equivalent nodal loads (local, reference axes) of the loads between the nodes: the forces
  // they put on the nodes (add to the external load vector); the fixed-end forces are their
  // negative.
  virtual Vec12 equivalent_loads(const ElementLoads& loads) const = 0;
  // The fixed-end forces at a state of loads whose direction stays fixed in space (dead loads,
  // given as at the reference): local axes at the state (axes_at(p)), per unit reference length.
  virtual Vec12 fixed_end_forces_at(const NodalPoses& p, const ElementLoads& loads) const = 0;
  // Equivalent nodal loads (local) of a temperature change: the forces that, applied to the
  // free element, produce its free thermal deformation (axial alpha dT L, curvature alpha dT/dy
  // in x-y and alpha dT/dz in x-z).
  virtual Vec12 thermal_loads(const Temperature& t) const = 0;

  // Section forces [N Vy Vz T My Mz] at s in [0, L] (positive face), from the end forces (local,
  // member loads' fixed-end forces included) and the loads between the nodes.
  virtual Vec6 section_forces(double s, const Vec12& end_forces, const ElementLoads& loads, CutSide side) const = 0;

  // The drawn shape: displacement (global) of the point at xi in [0, 1] along the member at the
  // state p, from its reference position (for VTK output: a drawing, not a result).
  virtual Vec3 displacement_at(const NodalPoses& p, double xi) const = 0;
};

}  // namespace beamfea
