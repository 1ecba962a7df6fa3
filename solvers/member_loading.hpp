#pragma once
// A load case on the model: member loads and self-weight distributed onto the analysis elements
// (ElementLoads, elements/span_loads.hpp: the loads between one element's nodes), the external
// load vector over raw DOFs, dead-load terms and fixed-end forces for the co-rotational analyses,
// and section forces at stations along members. The one owner of member loads in solvers/.
//
// A member load follows its member over its segments: a distributed load on [from, to] (fractions
// of the member's length) is cut at the segment ends, its intensity interpolated linearly; a point
// load goes to the segment that contains it (at a segment end, to the segment that starts there).
// Self-weight: q = density x A x gravity on every beam element (force per unit length, global);
// point masses: mass x gravity at their node.
#include <Eigen/Core>
#include <vector>

#include "core/dof_map.hpp"
#include "core/model.hpp"
#include "elements/span_loads.hpp"

namespace beamfea {

// Loads between the nodes of every element (local components; empty for rigid links).
std::vector<ElementLoads> element_loads(const Model& model, const LoadSet& loads);
// The same written over `out` (each element's lists keep their storage).
void element_loads(const Model& model, const LoadSet& loads, std::vector<ElementLoads>& out);

// External forces over raw DOFs: nodal and joint loads, the equivalent nodal loads of the member
// loads and self-weight (global axes), and the weight of the point masses.
Eigen::VectorXd external_force(const Model& model, const DofMap& map, const LoadSet& loads);
// The same with the loads' element_loads(model, loads) already at hand.
Eigen::VectorXd external_force(const Model& model, const DofMap& map, const LoadSet& loads,
                               const std::vector<ElementLoads>& element_loads);
// The same written over `f` (its storage kept when it has the size).
void external_force(const Model& model, const DofMap& map, const LoadSet& loads, const std::vector<ElementLoads>& element_loads,
                    Eigen::VectorXd& f);

// Dead-load terms of every element (global directions, fixed at the reference configuration),
// for the co-rotational analyses (elements/span_loads.hpp, DeadLoadTerm).
std::vector<std::vector<DeadLoadTerm>> element_dead_loads(const Model& model, const LoadSet& loads);

// The member loads' share of deformed beams' end forces, for the geometrically nonlinear analyses.
// A co-rotational beam's internal forces are its nodal forces only; the loads between its nodes
// (member loads, self-weight) are dead loads whose direction stays fixed in space. Their fixed-end
// forces in the element's co-rotated axes at the state (CorotationalBeam::fixed_end_forces_at)
// times the load factor complete its end forces; at a small load they tend to linear_static's.
// Per element (zero for rigid links and unloaded beams); x, R: node positions and rotations from
// the reference.
std::vector<Vec12> corotated_fixed_end_forces(const Model& model, const LoadSet& loads, const std::vector<Vec3>& x,
                                              const std::vector<Mat3>& R, double factor);

// Section forces [N Vy Vz T My Mz] (local, positive face, docs/conventions.md) at x, the distance
// from the member's first node.
struct Station {
  double x = 0.0;
  Vec6 forces = Vec6::Zero();
};
// Stations of a beam member: both ends, every segment end, both sides of every point load, every
// start and end of a distributed load, and `interior` equally spaced points (x = L k/(interior+1)).
// end_forces: per element, k u + fixed-end forces (local); loads: element_loads(...).
std::vector<Station> member_stations(const Model& model, int member, const std::vector<Vec12>& end_forces,
                                     const std::vector<ElementLoads>& loads, int interior = 10);
// The same written over `out`, with `positions` as scratch: both keep their storage, so that a
// caller writing member after member, case after case, allocates nothing once they have their sizes
// (members without loads between their nodes).
void member_stations(const Model& model, int member, const std::vector<Vec12>& end_forces,
                     const std::vector<ElementLoads>& loads, int interior, std::vector<Station>& out,
                     std::vector<double>& positions);

}  // namespace beamfea
