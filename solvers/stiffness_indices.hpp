#pragma once
// Stiffness indices of a node from its compliance (solvers/condensed_stiffness.hpp).
//
// A force f at the node with the moments free moves it by u_t = C_tt f, C_tt the 3x3 translational
// block of the 6x6 compliance C [ux uy uz rx ry rz]; a moment m with the forces free turns it by
// C_rr m. The eigen-stiffnesses of a block are the eigenvalues of its inverse, 1 / lambda_i(C_tt),
// along the unit eigenvectors: the stiffest and the most compliant direction of a force (moment)
// at the node (the "stiffness ellipsoid" indices of robot stiffness analysis, e.g. Pashkevich,
// Klimchik & Chablat 2011, "Enhanced stiffness modeling of manipulators with passive joints",
// Mech. Mach. Theory 46, sec. 5; Bu 2012's index as the extreme eigenvalues of K).
//
// Three kinds of direction in a block, as the compliance tells them apart:
// - free: the node moves without resistance (an unbounded direction of the compliance, a mechanism
//   seen from the node). A force along the direction part of an unbounded direction n (its
//   translational part for a force, rotational part for a moment) does work on n: the
//   eigen-stiffness is zero. The free directions of a block span the parts of the unbounded
//   directions; the other directions are the block compressed onto their orthogonal complement
//   Q: Q^T C Q (the finite eigenvalues of C + (1/eps) N N^T as eps -> 0 are those of Q^T C Q).
// - blocked: the node cannot move (supports, rigid links, loops): the compliance is zero there; the
//   eigen-stiffness is infinite. Blocked directions are left out of min, max and the condition.
// - finite: the rest, eigen-stiffness 1 / lambda.
// min = 0 when the block has a free direction; condition = max / min is then unbounded (empty).
// With no direction that moves (all blocked), min, max and condition are empty.
//
// Decisions are made in the length-scaled metric of condensed_stiffness.hpp (S = diag(1,1,1,L,L,L),
// wrench (f, m / L), motion (u, L r)), so that translations and rotations share one tolerance.
#include <array>
#include <optional>
#include <vector>

#include "core/model.hpp"

namespace beamfea {

struct StiffnessIndicesOptions {
  // A compliance eigenvalue (scaled) below this fraction of the largest eigenvalue of the scaled
  // 6x6 compliance counts as zero: the node cannot move that way. In a blocked direction the
  // compliance is zero to the rounding of C = S^-1 U K^+ U^T S^-1 (1e-16 relative); the most
  // compliant finite direction is at least 1e-9 of the stiffest's compliance, because the rank test
  // of the condensation counts eigenvalues of K below 1e-9 of the largest as zero.
  double blocked_tolerance = 1e-12;
  // A component of a unit unbounded direction (or of a unit wrench along one) below this counts as
  // zero: those directions are null vectors of the condensed stiffness, accurate to about
  // rounding / (gap to the smallest nonzero eigenvalue) = 1e-16 / 1e-9 = 1e-7.
  double free_tolerance = 1e-6;
  void validate() const;
};

// The indices of one 3x3 block (translational: force, N/m in SI; rotational: moment, N m/rad).
struct BlockIndices {
  // The extreme eigen-stiffnesses over the directions that move (finite and free) and their unit
  // directions (sign: the largest component positive). Empty when every direction is blocked.
  std::optional<double> min, max;
  Vec3 direction_min = Vec3::Zero(), direction_max = Vec3::Zero();
  // max / min: empty when min is zero (a free direction) or empty.
  std::optional<double> condition;
  // The unit directions the node cannot move (infinitely stiff) and those it moves freely.
  std::array<Vec3, 3> blocked{}, free{};
  int blocked_count = 0, free_count = 0;
};

struct StiffnessIndices {
  BlockIndices translational;
  BlockIndices rotational;
};

// The indices of a compliance (6x6, zero in blocked directions and, by convention, in the
// unbounded ones), its unbounded directions (unit vectors in the scaled metric) and the length L.
StiffnessIndices stiffness_indices(const Mat6& compliance, const std::vector<Vec6>& unbounded_directions, double L,
                                   const StiffnessIndicesOptions& options = {});

// The stiffness along a direction d (normalised here; nonzero), 1 / (d^T C_tt d): the force along d
// over the displacement along d of a force along d. Zero when d has a component along a free
// direction; empty (infinite) when the node cannot move along d.
std::optional<double> stiffness_along(const Mat6& compliance, const std::vector<Vec6>& unbounded_directions, double L,
                                      const Vec3& d, const StiffnessIndicesOptions& options = {});

// The motion C w [ux uy uz rx ry rz] under the wrench w [fx fy fz mx my mz]; empty when w does work
// on an unbounded direction (the motion is unbounded).
std::optional<Vec6> deflection_under(const Mat6& compliance, const std::vector<Vec6>& unbounded_directions, double L,
                                     const Vec6& wrench, const StiffnessIndicesOptions& options = {});

// The principal axes of a 3x3 compliance block: its eigenvalues, descending (rounding below zero
// written as zero), and the unit eigenvectors as the columns of `axes` (signed as above): the
// semi-axes of the compliance ellipsoid { C f : |f| = 1 }.
struct ComplianceAxes {
  Vec3 semi_axes = Vec3::Zero();
  Mat3 axes = Mat3::Identity();
};
ComplianceAxes compliance_axes(const Mat3& C);

}  // namespace beamfea
