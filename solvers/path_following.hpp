#pragma once
// Path following of the geometrically nonlinear structure (solvers/nonlinear_structure.hpp):
// load, displacement or arc-length control, stability at every converged step, critical points
// located by bisection and classified, branch switching and imperfections.
//
// Equilibrium: r(x, lambda) = T^T (f_int - lambda f_ext - reactions) = 0 over the free independent
// coordinates, with supports or imposed values on slave nodes as constraints c(x) = c_0 whose
// multipliers are the reactions. Each step solves for the increment Delta about the step's start
// state, state = start (+) Delta (x + du, exp(dw) R, q + dq), with SUNDIALS KINSOL and UMFPACK
// (solvers/kinsol_solver.hpp); the Jacobian is K_t * D(Delta), D the derivative of the retraction.
//
// Controls (the extra equation and unknown):
//   load factor    lambda prescribed per increment;
//   displacement   u_c(x) = s prescribed; unknown lambda when the model has loads (classic
//                  displacement control), otherwise the reaction of the controlled DOF (imposed
//                  motion: the lumped-model use case, e.g. the end of a chain pushed to a point);
//   arc length     Crisfield's spherical constraint |Delta|_W^2 + psi^2 Delta lambda^2 = ds^2 (W: 1 on
//                  translations, L^2 on rotations, L the model size), psi^2 = max(|t|_W^2, L^2) with t the
//                  initial tangent displacement per unit load factor; the predictor's sign follows the previous step
//                  direction (t . Delta_prev > 0); ds adapts to the Newton iteration count.
// Non-convergence: the step is cut (halved) up to max_cuts times; then the path stops with the
// reason in `termination`; every converged step is kept.
//
// Stability (the FEA form of Pashkevich et al. eqs. 18-23): at every converged state the tangent is
// restricted to the null space Z of the constraint Jacobian (eq. 19-21; Z by exact elimination),
// symmetrised, and its inertia counted by a sparse LDL^T (Sylvester's law of inertia): stable when it
// has no negative eigenvalue (eq. 23: the second variation of the energy is positive on all admissible
// variations). min_eigenvalue is the lowest eigenvalue of the Jacobi-scaled matrix (dimensionless).
// The loaded Cartesian stiffness of a node (eq. 28 in FEA form) is the condensed tangent
//   [ K_t  T_n^T ; T_n  0 ] [X; M] = [0; I],  K_c = -M.
//
// Critical points: a change of the negative-eigenvalue count between two steps; located by bisection
// of the step (arc length, load factor or control value) to `critical_tolerance` of the step; a limit
// point when the critical mode phi does work on the load pattern (|phi . p| > 1e-3 |phi| |p|), a
// bifurcation otherwise. Branch switching (arc-length control): from the last stable state before a
// bifurcation, the next predictor is the critical mode scaled to the arc length.
// Singular poses of closed loops (solvers/path/singularity.hpp): a passive sub-chain (or the whole
// constraint Jacobian) losing rank; a crossing is located by bisection on the sign of the scaled
// smallest singular value and passed, a fold where no step converges ends the path (termination
// Singularity) instead of "no convergence".
// Redundant constraint rows (solvers/path/equilibrium.hpp, PathSystem::reselect): chosen at the
// reference, chosen afresh along the path where the rows kept lose rank and the constraints do not
// (a spatial over-constrained loop: a Bennett linkage), at a converged state, within a step whose
// passive Jacobian changes sign for the rows' sake, or before a failed step is cut; the step where
// they change records the rows dropped from it on. A dropped row that departs from its target where
// the constraints gained rank (a model built at a pose singular for its loops) stops the path
// (termination RankChanged).
//
// The parts, one job each (solvers/path/):
//   path_types        options, per-step records, critical points, result (PathTermination)
//   equilibrium       the bordered equilibrium system of a step (PathSystem): an immutable description
//                     of the structure, its numbering, constraints and scales
//   factor_cache      the mutable half: the converged state's evaluation, tangent and factorisation
//   corrector         a step's solve: chord iterations on that factor, then full Newton (KINSOL)
//   step_control      what a step prescribes, its size, cuts and adaptation
//   predictor         the initial guess of a step along the tangent (or a given direction)
//   stability         inertia, lowest eigenvalue, loaded Cartesian stiffness of a node
//   critical_points   detection, location by bisection, classification, branch switching
//   singularity       singular poses of closed loops: measures, crossings, the end at a fold
//   vibration         natural frequencies about a converged state
// follow_path (solvers/path_following.cpp) is the loop that composes them: each part receives the
// const system and, where it factorises or solves, the factor cache.
#include "core/model.hpp"
#include "solvers/path/path_types.hpp"
#include "solvers/path/stability.hpp"

namespace beamfea {

// The path of the model (possibly with an imperfection applied, see PathOptions).
PathResult follow_path(const Model& model, const PathOptions& options);
// The same with `loads` (a load case or combination of the model) as the reference load instead of
// the model's default loads: no copy of the model is made for it.
PathResult follow_path(const Model& model, const LoadSet& loads, const PathOptions& options);

// The model with buckling mode `mode` (1-based) added to its node positions at `amplitude`.
Model imperfect_model(const Model& model, int mode, double amplitude);
Model imperfect_model(const Model& model, const LoadSet& loads, int mode, double amplitude);

}  // namespace beamfea
