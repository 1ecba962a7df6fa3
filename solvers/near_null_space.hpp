#pragma once
// The near null space of a frame's reduced stiffness: the six rigid-body motions of the whole
// structure, written over the free DOFs. Algebraic multigrid by smoothed aggregation builds its
// coarse spaces from these (Vanek, Mandel, Brezina, Computing 56 (1996) 179-196, sec. 3: the
// coarse basis is the near null space restricted to each aggregate), so that an aggregate of beam
// nodes can translate and rotate rigidly at no cost, as the beams can.
//
// A rigid motion of translation t and small rotation theta about the point x_c moves node n by
//   u_n = t + theta x (x_n - x_c),   and turns it by   r_n = theta,
// and leaves every joint coordinate at zero (the bodies on both sides turn together). The map's
// free DOFs are independent raw DOFs (core/dof_map.hpp): a free DOF takes the motion of the raw
// DOF it is, and T_free then carries it to the slave nodes exactly as a rigid motion would. x_c
// is the nodes' centroid, so that the rotational columns are not dominated by the translations.
#include <Eigen/Core>

#include "core/dof_map.hpp"
#include "core/model.hpp"

namespace beamfea {

// The six rigid-body modes (tx, ty, tz, rx, ry, rz) of `model` restricted to `map`'s free DOFs,
// orthonormalised; a mode that the supports remove entirely (its free part depends on the
// others) is left out, so the result has at most six columns.
Eigen::MatrixXd rigid_body_modes(const Model& model, const DofMap& map);

// 6 when `map`'s free DOFs are whole nodes, each node's six components consecutive and in order
// (no joint coordinate and no partly supported node among them); 1 otherwise. Smoothed aggregation then
// aggregates nodes instead of single DOFs, keeping each node's six DOFs in one aggregate as the
// rigid-body modes couple them (PETSc's MatSetBlockSize).
int node_block_size(const DofMap& map);

}  // namespace beamfea
