#pragma once
// Modal analysis: natural frequencies and mode shapes of the constrained structure,
//     K phi = omega^2 M phi,   f = omega / (2 pi),
// optionally about a loaded equilibrium: K is then the tangent K + K_g of the linear static state
// of the loads (solvers/initial_stress.hpp) or of their second-order equilibrium
// (solvers/second_order.hpp, loaded_tangent), so that a compressive preload lowers the
// frequencies (a pinned column under P: omega = omega_0 sqrt(1 - P/P_cr)) and a frequency falls
// to zero at buckling.
//
// K   the elastic stiffness on the free DOFs (beams, Euler-Bernoulli or Timoshenko, and joint
//     springs), through the DofMap like every analysis: supports, prescribed DOFs (held at their
//     value: zero motion about it), rigid links and joints eliminated exactly;
// M   the mass on the free DOFs (solvers/mass_matrix.hpp): consistent (default) or lumped beam
//     mass, point masses; it condenses through rigid links and joints exactly.
//
// Eigen-solver: solvers/generalized_eigen.hpp (shift-invert Lanczos, dense when small), or SLEPc's
// Krylov-Schur with the same shift-and-invert (solvers/slepc_eigen.hpp) when the model's "solver"
// asks for the iterative solver (or auto, at or above kIterativeEigenDofs free DOFs), with a
// shift sigma = -kShiftRelative * min_i(K_ii / M_ii) just below zero, so that K - sigma M is
// positive definite even with rigid-body or mechanism modes, and the lowest modes come first.
//
// Zero-frequency modes: a mode whose Jacobi-scaled Rayleigh quotient phi^T K phi / phi^T D_K phi
// (D_K = diag K) is below `zero_tolerance` (the criterion the linear static analysis uses for
// mechanisms) has frequency 0 and is reported as a rigid-body mode when it is a rigid motion of
// the whole model, otherwise as a mechanism mode. Under a preload beyond buckling omega^2 < 0:
// the mode is "unstable" and its frequency is reported as -sqrt(-omega^2)/(2 pi).
//
// Modes are mass-normalised: phi^T M phi = 1 over the free DOFs (= u^T M_raw u over raw DOFs).
// Participation factors Gamma_kd = phi_k^T M_raw r_d for the 6 rigid-body motions r_d about the
// origin (translations x y z, rotations about the global axes through the origin: the base moves
// as a rigid body); effective masses m_kd = Gamma_kd^2 (translations: mass; rotations: inertia
// about the axis through the origin). Their sum over all modes is at most the total
// r_d^T M_raw r_d (equal for the translations of a structure on a single rigid base when every
// mode is counted).
#include <string>
#include <vector>

#include "core/model.hpp"
#include "elements/beam_mass.hpp"
#include "solvers/second_order.hpp"
#include "solvers/slepc_eigen.hpp"

namespace beamfea {

struct ModalOptions {
  int modes = 10;
  MassKind mass = MassKind::Consistent;
  bool preload = false;           // about an equilibrium of the loads (about_state says which)
  PreloadOptions about_state;     // linear static (default) or second order; which K_g
  double zero_tolerance = 1e-10;  // Jacobi-scaled Rayleigh quotient of a zero-frequency mode
  void validate() const;
};

enum class ModalStatus {
  Succeeded,
  NoMass,           // the model has no mass (no density, no point masses)
  MasslessMechanism,  // K - sigma M singular: a mechanism that moves no mass
  PreloadFailed,    // the linear static solution of the preload failed
  Failed,           // the eigen-solver did not converge
};
const char* to_string(ModalStatus s);

enum class ModeKind { Elastic, RigidBody, Mechanism, Unstable };
const char* to_string(ModeKind k);

struct ModalResult {
  ModalStatus status = ModalStatus::Failed;
  std::string message;                  // one line: outcome and key figures
  int free_dofs = 0;
  Eigen::VectorXd eigenvalues;          // omega^2, ascending
  Eigen::VectorXd frequencies;          // Hz; 0 for zero modes, negative for unstable ones
  std::vector<ModeKind> kinds;
  std::vector<Eigen::VectorXd> modes;   // raw displacement per mode, mass-normalised
  Eigen::MatrixXd participation;        // modes x 6: Gamma_kd
  Eigen::MatrixXd effective_mass;       // modes x 6: Gamma_kd^2
  Vec6 total_mass = Vec6::Zero();       // r_d^T M_raw r_d
  // Which eigen-solver ran; residual = max_k ||K phi_k - omega_k^2 M phi_k|| / ||K phi_k|| over the
  // free DOFs (relative_eigen_residual: a zero-frequency mode is measured against kZeroActionRelative ||D_K phi||).
  EigenSolverReport solver;
  std::string brief_report() const { return message; }
};

// The second form with `loads` (a load case of the model) as the preload; the first with the
// model's default loads.
ModalResult solve_modal(const Model& model, const ModalOptions& options = {});
ModalResult solve_modal(const Model& model, const LoadSet& loads, const ModalOptions& options = {});

// The number of free DOFs of a model (the most modes a modal analysis can give).
int modal_dof_count(const Model& model);

}  // namespace beamfea
