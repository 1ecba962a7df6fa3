#pragma once
// Linearised buckling about the linear static state of the model's loads:
//     (K + lambda K_g) phi = 0,   lambda > 0 the load factors, phi the modes.
//
// K   the elastic stiffness (beams, joint springs) on the free DOFs (DofMap, reference state);
// K_g the geometric (initial-stress) stiffness of the linear solution at lambda = 1:
//     - beams: FrameElement::geometric_stiffness (Yang & McGuire 1986, McGuire et al. 2000 eq. 9.18)
//       from each beam's linear end forces; its moment terms carry lateral-torsional buckling;
//     - rigid links and joints: the constraint-curvature matrix G of solvers/nonlinear_structure.hpp
//       for the raw forces f_int - f_ext - reactions transmitted at the slave nodes, mapped to the
//       free DOFs by Z (the DofMap's T_f rows at the independent DOFs). A chain of rigid links with
//       rotational springs under an end load P has G = -P/L per hinge: lambda_cr = K_theta/(P L).
//     - closed loops (an edge of rigid links/joints outside the forest): the closure curvature of
//       solvers/nonlinear_structure.hpp contracted with the loop's multipliers from the linear
//       solution (DofMap::constraint_forces; the minimum-norm split where closure rows are redundant,
//       whose indeterminate part carries no load in a planar loop under in-plane loads).
// K_g is symmetrised (it is symmetric at equilibrium under forces; applied moments add a small
// skew part that is dropped for the eigen-problem).
//
// Eigen-solver: SLEPc's Krylov-Schur on (-K_g) phi = mu K phi (solvers/slepc_eigen.hpp) when the
// model's "solver" asks for the iterative solver (or auto, at or above kIterativeEigenDofs free
// DOFs); otherwise Spectra's SymGEigsShiftSolver in buckling mode (K positive definite, K_G = -K_g
// indefinite) with a positive shift below the first load factor estimated from the Rayleigh
// quotient of the linear solution; small systems are solved densely. Only positive load factors
// are reported, ascending.
//
// Not supported: prebuckling displacements
// (linearised theory). Member loads and self-weight enter through the elements' mean axial forces
// (a column under its own weight converges to Greenhill's load with the mesh); the change of their
// consistent moments with the chord (a load stiffness) is left out of K_g.
#include <string>
#include <vector>

#include "core/dof_map.hpp"
#include "core/model.hpp"
#include "elements/frame_element.hpp"
#include "solvers/slepc_eigen.hpp"

namespace beamfea {

struct BucklingOptions {
  int modes = 4;
  // The beams' K_g: Full (McGuire's, with the end-moment terms) or Axial (elements/frame_element.hpp).
  GeometricStiffness geometric_stiffness = GeometricStiffness::Full;
  void validate() const;
};

enum class BucklingStatus { Succeeded, NoCompression, Mechanism, NotConverged, Failed };
const char* to_string(BucklingStatus s);

struct BucklingResult {
  BucklingStatus status = BucklingStatus::Failed;
  std::string message;
  int free_dofs = 0;
  Eigen::VectorXd load_factors;          // ascending, positive
  std::vector<Eigen::VectorXd> modes;    // raw displacement per mode, largest translation = 1
  Eigen::VectorXd linear_u;              // raw linear static displacement (lambda = 1)
  // Which eigen-solver ran; residual = max_k ||K phi_k + lambda_k K_g phi_k|| / ||K phi_k|| over
  // the free DOFs, computed from the returned vectors.
  EigenSolverReport solver;
};

// Buckling under `loads` (a load case of the model); the first form under its default loads.
BucklingResult solve_buckling(const Model& model, const BucklingOptions& options = {});
BucklingResult solve_buckling(const Model& model, const LoadSet& loads, const BucklingOptions& options = {});

// Normalises a raw mode: largest node translation 1 (or largest rotation 1 when nothing
// translates), with that component positive.
Eigen::VectorXd normalise_mode(const Model& model, const Eigen::VectorXd& u_raw);

}  // namespace beamfea
