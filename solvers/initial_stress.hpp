#pragma once
// The geometric (initial-stress) stiffness of a linear static state on the free DOFs: what the
// buckling analysis multiplies by lambda and what the modal analysis about a loaded equilibrium
// adds to K.
//
//   K_g = sum_beams FrameElement::geometric_stiffness(end forces)  (T^T kg T, elements/geometric_stiffness.hpp)
//       + Z^T G Z                                            (rigid links and joints)
// G is the constraint-curvature matrix of solvers/nonlinear_structure.hpp for the raw forces
// f_int - f_ext - reactions at slave nodes that rigid links and joints transmit, Z the DofMap's
// T_f rows at the independent DOFs. K_g is symmetrised (it is symmetric at equilibrium under
// forces; applied fixed-axis moments add a small skew part that is dropped).
//
// Member loads and self-weight enter through the beams' end forces (fixed-end forces included:
// kg takes the element's mean axial force, so a column under its own weight converges to
// Greenhill's load with the mesh); the change of their consistent moments with the chord (a load
// stiffness) is left out. Closed loops: each closure's curvature contracted with the forces it
// transmits (its multipliers).
//
// Timoshenko beams: kg is the Euler-Bernoulli matrix (cubic Hermite shapes, end rotations read
// as w'): it keeps the axial-force (P-Delta) and moment/torque coupling terms but no shear-
// deformation correction; with mesh refinement a Timoshenko column buckles at Engesser's load
// P_E/(1 + P_E/(G As)), which this matrix converges to (its rotation terms vanish with h).
//
// Used by buckling (K_g times lambda), the loaded-mode stiffness of a node and the modal analysis
// about a loaded equilibrium.
#include "core/dof_map.hpp"
#include "core/model.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

// K_g (free x free, NOT symmetrised) of the linear solution `lin` of `loads`, the beams' matrices
// of the given kind (elements/frame_element.hpp, GeometricStiffness).
SparseMatrix geometric_stiffness(const Model& model, const DofMap& map, const LinearStructure& structure,
                                 const LinearStaticResult& lin, const LoadSet& loads,
                                 GeometricStiffness kind = GeometricStiffness::Full);

class NonlinearStructure;  // solvers/nonlinear_structure.hpp

// The rigid links' and joints' part Z^T G Z of K_g (free x free) at the reference, for the raw
// residual forces r = f_int - f_ext of a state (the reactions at slave nodes taken out here): what
// geometric_stiffness adds to the beams' matrices. Zero (no entries) without rigid links, joints
// or loops. `ns` is NonlinearStructure(model).
SparseMatrix constraint_geometric_stiffness(const NonlinearStructure& ns, const DofMap& map, Eigen::VectorXd r);

}  // namespace beamfea
