#pragma once
// Natural frequencies about a converged state of a path: small vibrations about the deformed
// equilibrium, so that a frequency falls to zero where the path loses stability (a pinned column
// under P: omega = omega_0 sqrt(1 - P/P_cr); Bazant & Cedolin, Stability of Structures, 1991,
// sec. 3.1).
//
//   K_c phi = omega^2 M_c phi,   f = omega / (2 pi)   (negative f = -sqrt(-omega^2)/(2 pi): unstable)
//
// K_c  the path's converged tangent restricted to the admissible variations, Z^T K_t Z
//      (constrained_tangent, solvers/path/stability.hpp: co-rotational beams with their geometric
//      stiffness, the constraint curvature of rigid links and joints, closures of loops with their
//      multipliers, supports on slave nodes), symmetrised: exactly the matrix whose inertia the
//      path's stability analysis counts. The controlled DOF is held only under imposed motion
//      (displacement control without loads: the loading device holds it); with loads the load is
//      the physical agent and the DOF vibrates freely.
// M_c  the mass in the DEFORMED configuration, transformed through the path's coordinates:
//      M_c = (T Z)^T M_raw(x) (T Z), T the Jacobian of the nodes' raw DOFs (translations, spatial
//      spins) over the free independent coordinates at the state (NonlinearStructure::raw_row:
//      rigid links and joints carry their mass exactly, as in solvers/mass_matrix.hpp). M_raw(x):
//      each beam's local mass (elements/beam_mass.hpp, at its reference length: mass is conserved)
//      in its current co-rotated axes (CorotationalBeam::kinematics), each point mass's inertia
//      rotated with its node, R J R^T. At the reference state it is the modal analysis's mass.
//
// Eigen-pairs: solvers/generalized_eigen.hpp with the modal analysis's shift just below zero, so
// that the lowest modes come first while the state is stable; beyond a critical point the
// eigenvalues nearest zero come first (the first negative ones, then the lowest positive ones).
// A mode whose Jacobi-scaled Rayleigh quotient is below the modal zero tolerance has frequency 0.
#include <Eigen/Core>
#include <string>

#include "elements/beam_mass.hpp"
#include "solvers/path/equilibrium.hpp"
#include "solvers/path/stability.hpp"

namespace beamfea {

struct PathFrequencyOptions {
  int modes = 0;                          // 0: none computed
  MassKind mass = MassKind::Consistent;
};

struct PathFrequencies {
  bool ok = false;
  std::string message;                    // why not, when not ok
  Eigen::VectorXd eigenvalues;            // omega^2, ascending
  Eigen::VectorXd frequencies;            // Hz; negative where omega^2 < 0
};

// The mass over the nodes' raw DOFs (6 per node, DofMap numbering) in the configuration of `state`.
SparseMatrix deformed_raw_mass(const NonlinearStructure& ns, const NonlinearState& state, MassKind kind);

// The lowest frequencies about converged state c. `tangent`: constrained_tangent(sys, factors, c,
// control) with the controlled DOF held under an imposed motion.
PathFrequencies path_frequencies(const PathSystem& sys, const Converged& c, const StabilityAnalysis& tangent,
                                 const PathFrequencyOptions& options);

}  // namespace beamfea
