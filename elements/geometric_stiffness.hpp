#pragma once
// Geometric (initial-stress) stiffness of the 3-D Euler-Bernoulli beam of elements/beam.hpp.
//
// What it is: the 12x12 local matrix kg such that (ke + kg) is the linearised stiffness of a
// member carrying the end forces `f` (P-Delta / linearised buckling: det(K + lambda Kg) = 0).
// kg is linear in f and symmetric.
//
// Formulation: Yang & McGuire (1986), "Stiffness matrix for geometric nonlinear analysis",
// J. Struct. Eng. 112(4) 853-877; as printed in McGuire, Gallagher & Ziemian, Matrix Structural
// Analysis, 2nd ed. (2000), eq. 9.18 (doubly symmetric section, shear centre = centroid, no
// warping). Its terms, with N = Fx2 the axial force (tension > 0), T = Mx2 the torque:
//   - axial:   N/L [1 -1; -1 1] on u;   N/(30L) [36 3L -36 3L; ...; 4L^2 ...] on (v, rz), (w, ry)
//              (the consistent matrix of the cubic Hermite shape functions);
//   - Wagner-type torsion:  N (Ip/A)/L [1 -1; -1 1] on rx, with Ip/A = (Iy + Iz)/A;
//   - bending-moment/twist coupling (lateral-torsional buckling): My1, Mz1, My2, Mz2 couple the
//     twist rx with the transverse translations and end rotations;
//   - torque/bending coupling: T couples (v, w) and (ry, rz).
// The moment terms are those of semitangential end moments (Yang & McGuire 1986, Argyris): the
// element matrix is symmetric and the (rx, ry/rz) end terms cancel between neighbouring elements.
//
// DOF order and local axes exactly as elements/beam.hpp: [u1 v1 w1 rx1 ry1 rz1 u2 ... rz2],
// x from node 1 to node 2, Iz for bending in x-y (v, rz), Iy for bending in x-z (w, ry).
//
// End forces: the convention of LinearBeam::local_end_forces, i.e. the forces exerted ON the
// element at its ends in local axes, f = [N1 Vy1 Vz1 T1 My1 Mz1  N2 Vy2 Vz2 T2 My2 Mz2].
// McGuire's symbols map as Fx2 = f[6], Mx2 = f[9], My1 = f[4], Mz1 = f[5], My2 = f[10],
// Mz2 = f[11]. For a member not exactly in equilibrium, N and T are taken as the averages
// (f[6] - f[0])/2 and (f[9] - f[3])/2. The end shears enter only through the moments
// (Vy = -(Mz1 + Mz2)/L etc. by equilibrium) and are not read.
//
// The axial-force matrix (GeometricStiffness::Axial, beam_local_axial_geometric_stiffness): the
// terms of N alone, the common P-Delta convention (Frame3DD, Pynite's P-Delta, design codes'
// second-order elastic analysis). On a Timoshenko beam with the shear parameters Phi_y, Phi_z of
// elements/beam.hpp, the shear-deformable coefficients of Przemieniecki, Theory of Matrix
// Structural Analysis (1968), sec. 15.3, as Frame3DD's geometric_K codes them, for bending in x-y
// (Phi = Phi_y, D = (1 + Phi)^2; x-z alike with Phi_z and the signs of w, ry):
//   kg(v1, v1)   =  N/L (6/5 + 2 Phi + Phi^2)/D       kg(v1, rz1) = N/(10 D)
//   kg(rz1, rz1) =  N L (2/15 + Phi/6 + Phi^2/12)/D   kg(rz1, rz2) = -N L (1/30 + Phi/6 + Phi^2/12)/D
// (Phi = 0: the Hermite matrix above), the axial term N/L [1 -1; -1 1] on u and Wagner's torsion
// term N (Iy + Iz)/(A L) [1 -1; -1 1] on rx (Frame3DD takes J instead of Iy + Iz there). Under a
// rigid rotation the matrix gives the force pair N theta of the rotated axial force, as it must.
//
// Not supported: warping torsion (no bimoment DOF), mono-symmetric sections (Wagner coefficient
// beta_x), load-height effects, member loads between the nodes.
#include "elements/beam.hpp"

namespace beamfea {

// Local geometric stiffness of a member of length L, area A, second moments Iy, Iz, carrying the
// local end forces `local_end_forces` (see above). Global: T^T kg T with T = beam_transformation.
Mat12 beam_local_geometric_stiffness(double L, double A, double Iy, double Iz, const Vec12& local_end_forces);

// The axial-force matrix (see above) of a member of section s (Timoshenko coefficients when
// s.shear_deformable()) and length L carrying the local end forces `local_end_forces` (N their
// mean axial force).
Mat12 beam_local_axial_geometric_stiffness(const BeamSection& s, double L, const Vec12& local_end_forces);

}  // namespace beamfea
