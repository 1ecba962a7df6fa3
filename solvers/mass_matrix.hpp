#pragma once
// The mass matrix of a model: beams (FrameElement::mass, from the material's density) and
// point masses ("masses"), over raw DOFs, assembled on the free DOFs through the DofMap.
//
// Rigid links and joints carry the mass of what they connect exactly: the raw DOFs of a slave
// node are raw u = T_f u_free + T_p u_p like the stiffness's, so M_ff = T_f^T M_raw T_f. A point
// mass m at a node offset r from its master by a rigid link gives the master m on translations,
// the coupling m [r]x and the rotary inertia m (r^T r I - r r^T) (the parallel-axis theorem), with
// no approximation. Joint coordinates carry no mass of their own.
#include "core/assembly.hpp"
#include "core/dof_map.hpp"
#include "core/model.hpp"
#include "elements/beam_mass.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

// Adds every beam's and point mass's matrix over its raw DOFs to `assembler` (begin/end are the
// caller's).
void assemble_mass(const LinearStructure& structure, const DofMap& map, MassKind kind, SystemAssembler& assembler);

// M_raw u_raw (raw DOFs), element by element.
Eigen::VectorXd raw_mass_product(const LinearStructure& structure, const DofMap& map, MassKind kind,
                                 const Eigen::VectorXd& u_raw);

// The 6 raw rigid-body motions of the whole model about the origin, as columns: unit
// translations along x, y, z, then unit rotations about the global x, y, z axes through the
// origin (node translation theta x X, rotation theta); joint coordinates zero.
Eigen::MatrixXd rigid_body_motions(const Model& model, const DofMap& map);

// The same restricted to the free DOFs, for an algebraic multigrid's near null space: the entries
// at the free independent DOFs (where T_f is the identity); a slave node's motion follows from
// them, joint coordinates stay zero in a rigid motion.
Eigen::MatrixXd free_rigid_body_motions(const Model& model, const DofMap& map);

}  // namespace beamfea
