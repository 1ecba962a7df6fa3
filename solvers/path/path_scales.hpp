#pragma once
// The structure's own scales, from which the path's arc-length metric, its automatic first step and
// its convergence test are built, so that none of them depends on the magnitude of the reference
// load or on the model's size alone (a reference load scaled by 1e-3 or 1e3 gives the same physical
// path in the same steps).
//
//   t           linear response: tangent displacement per unit load factor at the start
//               (solvers/path/equilibrium.hpp), |t|_W its norm in the arc-length metric;
//   lambda_ref  the structure's own load-factor scale: the lowest positive linearised buckling
//               factor (solvers/buckling.hpp) where there is one (and it is not above
//               kRoundOffBucklingRatio times the linear scale below), otherwise the load factor whose
//               linear response moves some node by the model size L (L / max|t_translation|), or,
//               where no translation is free (rigid links and joints: a lumped model), turns some
//               coordinate by a radian (1 / max|t_rotation|);
//   psi         the arc-length weight of the load factor (Crisfield 1991, vol. 1, eq. 9.13:
//               |Delta|_W^2 + psi^2 dlambda^2 = ds^2): psi = max(|t|_W, L / lambda_cr), the larger
//               of the linear response per unit load factor and the model size per buckling factor
//               (an increment of the load factor by lambda_cr weighs like a displacement of the model
//               size). Both scale as 1 / (reference load), so psi dlambda is a physical length. The
//               second term keeps a stiff primary path (a column: |t| tiny) from making the load
//               factor free in the metric; for a column loaded by its Euler load it is the former
//               weight psi = L.
//   ds_auto     the first arc length of "arc_length": "auto": the step that increases the load
//               factor by lambda_ref / kAutoIncrementsToReference along the initial tangent,
//               ds_auto = dlambda_0 sqrt(|t|_W^2 + psi^2).
//   F_ref       the force scale of the convergence test: the reference load at lambda_ref
//               (max |f_ext| lambda_ref, moments divided by L), with a floor for round-off
//               (PathSystem's round-off floor).
#include "core/model.hpp"
#include "solvers/path/equilibrium.hpp"
#include "solvers/path/factor_cache.hpp"

namespace beamfea {

// The first step of "arc_length": "auto" raises the load factor by lambda_ref / 10: the first
// critical point of a structure that buckles near its linearised load is some 10-30 steps away.
inline constexpr double kAutoIncrementsToReference = 10.0;
// A linearised buckling factor above this many times the linear response's load-factor scale is
// taken for round-off (no scale of the path): such a load hardly stiffens or softens the structure.
inline constexpr double kRoundOffBucklingRatio = 1e8;
// Default step bounds of an automatic arc length, relative to its first step.
inline constexpr double kAutoMinArcRatio = 1e-4;
inline constexpr double kAutoMaxArcRatio = 10.0;

struct PathScales {
  double lambda_ref = 0.0;      // 0: none (no loads)
  double buckling_factor = 0.0; // lowest positive linearised buckling factor; 0: none
  double t_norm = 0.0;          // |t|_W
  double psi = 0.0;             // arc-length weight of the load factor
  double ds_auto = 0.0;
};

// The scales of the path from `start` (its tangent factorised in `factors`). A model with loads
// solves the linearised buckling problem for lambda_cr (once per path); one without (an imposed
// motion) has none of these scales (all zero).
PathScales path_scales(const Model& model, const PathSystem& sys, FactorCache& factors, const Converged& start);

}  // namespace beamfea
