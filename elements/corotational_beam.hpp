#pragma once
// 3-D co-rotational Euler-Bernoulli beam: large displacements and finite rotations, small strains.
//
// What it is: the linear local element of elements/beam.hpp (beam_local_stiffness) riding on a
// co-rotated frame that follows the member's rigid-body motion. The rigid rotation may be anything
// (a cantilever rolled into a full circle and beyond); the deformation relative to the co-rotated
// frame is assumed moderate (local rotations well below pi/2).
//
// Formulation: M.A. Crisfield (1990), "A consistent co-rotational formulation for non-linear,
// three-dimensional, beam-elements", Comput. Methods Appl. Mech. Engrg. 81, 131-150; with the
// co-rotated frame, local rotations and consistent tangent of J.-M. Battini, C. Pacoste (2002),
// "Co-rotational beam elements with warping effects in instability problems", Comput. Methods
// Appl. Mech. Engrg. 191, 1755-1789 (their co-rotational framework: frame from the chord and the
// mean nodal y axis, local rotations by the logarithm, variations through the matrices r, G, P
// and Ts^{-1}), written here in global spatial spins; the derivation, term by term, heads the
// .cpp. Equation numbers are not quoted because they were not re-checked against the paper.
//
// Kinematics in, per node i: the current position x_i and the total rotation R_i in SO(3) from
// the reference configuration (the nodal triad is R_i E0, E0 = reference local axes as columns).
// Rotations are never accumulated as rotation vectors; only the small local rotations below are.
//
// INCREMENT CONVENTION (the global solver relies on it):
//   The 12 generalised displacements are d = [du1 dw1 du2 dw2] in global axes, where du is a
//   translation (x <- x + du) and dw a SPATIAL spin: R <- exp_so3(dw) * R.
//   `force` is the gradient of `energy` along d (so its rotational parts are the nodal moments in
//   global axes, work-conjugate to spatial spins), and `tangent` = d(force)/d(d) along the same
//   multiplicative perturbations: tangent(i, j) = d force_i / d d_j. A Newton step solves
//   tangent * d = f_ext - force and updates x += du, R = exp_so3(dw) * R.
//
// Symmetry: the tangent is the second covariant derivative for left (spatial) perturbations plus
// half a Lie bracket; it is NOT symmetric at states with nodal moments. Exactly, per node,
//   tangent - tangent^T = -[m_i]x on node i's 3x3 rotation-rotation block (zero elsewhere),
// m_i the nodal moment in `force`. So tangent + blockdiag(0, [m1]x/2, 0, [m2]x/2) is symmetric
// always, and at zero end moments (e.g. pure axial force) the tangent itself is symmetric.
// Assembled: at an equilibrium state the internal nodal moments sum to the applied ones, so the
// assembled tangent's skew part is -[M_ext]x/2 on the rotation block of each node carrying an
// applied moment M_ext, and zero elsewhere: symmetric at equilibrium under forces alone (e.g. for
// a buckling eigen-analysis about a loaded state), non-symmetric under applied fixed-axis moments
// (which are not conservative in 3-D). During Newton iterations use a non-symmetric (LU)
// factorisation; symmetrising the tangent costs quadratic convergence wherever moments act.
//
// Co-rotated frame Rr = [r1 r2 r3] (Battini & Pacoste): r1 = (x2 - x1)/ln along the
// chord; q = (q1 + q2)/2, q_i = R_i E0 e2 the current nodal y axes; r3 = r1 x q / |r1 x q|,
// r2 = r3 x r1. In the reference configuration Rr = E0.
// Local deformational displacements: ubar = ln - L0 (elongation), thetabar_i = log(Rr^T R_i E0)
// (rotation vectors in the co-rotated axes). They are fed to the linear local element as the
// local displacement vector [0 0 0 thetabar_1  ubar 0 0 thetabar_2] (node 1 fixed at the origin
// of the chord, transverse displacements zero by construction of r1).
//
// Outputs: `energy` = 1/2 dl^T kl dl; `local_end_forces` = kl dl, i.e. [N Vy Vz T My Mz] at both
// ends in the co-rotated axes r1 r2 r3, in the convention of LinearBeam::local_end_forces
// (forces ON the element). The local moments are conjugate to thetabar (not to spins); the shears
// are those of equilibrium. The tangent already contains the element's geometric (initial-stress)
// stiffness: it IS the loaded stiffness at the current state; never add
// geometric_stiffness() to it (that matrix is for linearised buckling about the
// reference state, on LinearBeam).
//
// Shear deformation: the local element is beam_local_stiffness of the section, Timoshenko when the
// section has shear areas (the element's "theory"); the co-rotated frame is unchanged.
// Member loads: dead loads (fixed in space) through fixed_end_forces_at and the chord-following
// consistent vectors of elements/span_loads.hpp (DeadLoadTerm).
// Not supported: warping, large local strains (releases and offsets: wrappers); the frame
// is undefined when the mean nodal y axis q becomes parallel to the chord (local rotations near
// 90 deg about the member's z axis), which throws ModelError.
#include "elements/beam.hpp"

namespace beamfea {

// The contract's response (elements/frame_element.hpp): force conjugate to [du1 dw1 du2 dw2], its
// tangent in spatial spins (not symmetric, see above), energy, and [N Vy Vz T My Mz] at node 1 then
// node 2 in the co-rotated axes.
using CorotationalResponse = ElementResponse;

// The co-rotated frame and deformational displacements of one configuration.
struct CorotationalKinematics {
  Mat3 Rr;                 // columns r1 r2 r3: co-rotated axes in global components
  double length = 0.0;     // current chord length ln
  double elongation = 0.0; // ubar = ln - L0
  Vec3 theta1, theta2;     // local rotation vectors thetabar_i, co-rotated components
};

class CorotationalBeam final : public BeamElement {
 public:
  // Reference geometry: end positions X1, X2 and the orientation vector of elements/beam.hpp.
  // Throws ModelError for a zero length or an orientation parallel to the member.
  CorotationalBeam(const BeamSection& section, const Vec3& X1, const Vec3& X2, const Vec3& orientation);

  // Current positions x_i and total rotations R_i (from the reference configuration). Without
  // `with_tangent` the tangent is left zero (a residual evaluation: end forces, force, energy only).
  CorotationalResponse evaluate(const Vec3& x1, const Mat3& R1, const Vec3& x2, const Mat3& R2,
                                bool with_tangent = true) const;
  CorotationalKinematics kinematics(const Vec3& x1, const Mat3& R1, const Vec3& x2, const Mat3& R2) const;

  double reference_length() const { return L_; }
  // Columns are the reference local axes (the transpose of beam_local_axes).
  const Mat3& reference_axes() const { return E0_; }

  // The element contract (elements/frame_element.hpp). axes_at: the co-rotated axes as rows
  // (Rr^T); respond: evaluate; advance: x += du, R = exp(dw) R; mass_at: the local mass in the
  // co-rotated axes; fixed_end_forces_at: dead loads in the co-rotated axes; displacement_at: the
  // chord plus the cubic deflection of the local end rotations, in the co-rotated axes.
  // geometric_stiffness (from BeamElement) is the matrix at the reference, for linearised
  // buckling: the tangent already contains the geometric stiffness at a state.
  Mat3 axes_at(const NodalPoses& p) const override;
  ElementResponse respond(const NodalPoses& p, Evaluate what) const override;
  NodalPoses advance(const NodalPoses& p, const Vec12& d) const override;
  Mat12 mass_at(const NodalPoses& p, MassKind kind, double density) const override;
  Vec12 fixed_end_forces_at(const NodalPoses& p, const ElementLoads& loads) const override;
  Vec3 displacement_at(const NodalPoses& p, double xi) const override;

 private:
  Mat3 E0_;
};

}  // namespace beamfea
