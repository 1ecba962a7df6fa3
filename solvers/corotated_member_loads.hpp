#pragma once
// The member loads' share of a deformed beam's end forces, for the geometrically nonlinear
// analyses (path steps).
//
// linear_static reports end forces = k u + fixed-end forces of the loads between the nodes
// (elements/member_loads.hpp). A co-rotational beam's internal forces (elements/
// corotational_beam.hpp) are its nodal forces only; the loads between its nodes (member loads,
// self-weight) are dead loads whose direction stays fixed in space (solvers/nonlinear_structure.hpp,
// DeadLoadTerm). Their fixed-end forces in the element's current co-rotated frame Rr, over the
// reference length (the loads are per unit reference length), times the load factor, complete the
// end forces: at a small load they tend to linear_static's.
#include <vector>

#include "core/model.hpp"
#include "elements/beam.hpp"

namespace beamfea {

// Per element (zero for rigid links and unloaded beams): factor x the fixed-end forces of the
// loads of `loads` between the beam's nodes, in its co-rotated axes at the state (x, R: node
// positions and rotations from the reference).
std::vector<Vec12> corotated_fixed_end_forces(const Model& model, const LoadSet& loads, const std::vector<Vec3>& x,
                                              const std::vector<Mat3>& R, double factor);

}  // namespace beamfea
