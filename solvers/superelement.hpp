#pragma once
// Superelements: the stiffness and mass of a structure reduced onto the six DOFs of each of its
// interface nodes (global axes, in the order given), and optionally onto m fixed-interface normal
// modes (docs/analyses/superelement.md has the equations).
//
// Guyan (1965) reduction. The interface DOFs d (6 per node) are rows of the DofMap transformation,
// d = A u over the free DOFs u. The reduction basis X (free x r) holds, column by column, the
// static displacement of the structure for a unit interface displacement with every other DOF
// free of load: the minimiser of 1/2 u^T K u subject to A u = z,
//   K_z = X^T K X = K_bb - K_bi K_ii^-1 K_ib           (superelement.md eq. 3; Guyan 1965)
//   M_z = X^T M X,   X = [I; -K_ii^-1 K_ib]            (eq. 2 and 4: Guyan's consistent mass)
// where the interface rows pick free DOFs of their own (b) and i are the others; K_ii is factorised
// once and solved for the 6n columns of K_ib. Where they do not (an interface node that a rigid
// link or a joint carries, a skewed support) X and K_z come from the saddle point
//   [K A^T; A 0][X; L] = [0; I],  K_z = -L    (solvers/condensation.hpp).
//
// Craig & Bampton (1968) reduction, modes m > 0: the m lowest fixed-interface modes Phi (K phi =
// omega^2 M phi with A phi = 0, mass-normalised) join the basis [X, Phi] (superelement.md eq. 6;
// Craig & Bampton 1968); the reduced stiffness is block-diagonal, diag(K_z, Omega^2) (X^T K Phi = 0: K X is a
// multiple of A^T), the reduced mass [M_z, X^T M Phi; Phi^T M X, I] (eq. 7).
//
// Interface DOFs the model holds (a support on the interface node, or a constraint that ties them
// to other interface DOFs): the reduced matrices act on the directions the interface can move; a
// held DOF has a zero row and column (a supported DOF: its reaction is the model's support's). The
// directions are found by the SVD of the interface rows scaled to length units (rotations x L, the
// model's length scale), as solvers/condensed_stiffness.hpp does for one node.
//
// Free-free: when holding the interface leaves the rest stable but nothing else supports the
// structure, K_z is singular; its null space (length-scaled, relative eigenvalue below
// rank_tolerance) is reported as rigid-body modes: vectors of the reduced size (6n + m, the modal
// part zero). When holding the interface still leaves a mechanism, the outcome is Mechanism.
#include <string>
#include <vector>

#include "core/model.hpp"
#include "elements/beam_mass.hpp"

namespace beamfea {

struct SuperelementOptions {
  int modes = 0;                       // fixed-interface modes (Craig-Bampton); 0: Guyan
  MassKind mass = MassKind::Consistent;
  // Eigenvalue / largest eigenvalue of the length-scaled K_z below which a direction is a
  // rigid-body mode (the criterion of the stiffness analysis, solvers/condensed_stiffness.hpp).
  double rank_tolerance = 1e-9;
  // Singular value / largest of the length-scaled interface rows below which a direction cannot
  // move (held): rows eliminated exactly are zero up to rounding of the elimination.
  double motion_tolerance = 1e-10;
  void validate() const;
};

enum class SuperelementStatus {
  Succeeded,
  Mechanism,  // holding the interface leaves a mechanism
  NoMass,     // fixed-interface modes asked of a model without mass
  Failed,     // the eigen-solver did not converge
};
const char* to_string(SuperelementStatus s);

struct SuperelementResult {
  SuperelementStatus status = SuperelementStatus::Failed;
  std::string message;
  int free_dofs = 0;
  // (6n + m) square, symmetric: interface DOFs ux..rz node by node, then the modal coordinates.
  Eigen::MatrixXd stiffness, mass;
  bool has_mass = false;               // the model has mass on its free DOFs
  Eigen::VectorXd frequencies;         // Hz, of the fixed-interface modes (ascending)
  std::vector<Eigen::VectorXd> rigid_body_modes;  // of the reduced size, unit length-scaled norm
  std::vector<std::string> held_dofs;  // interface DOFs the model holds, "node 'A' uz"
};

// The reduction of `model` onto `interface` (node indices, distinct).
SuperelementResult reduce_superelement(const Model& model, const std::vector<int>& interface,
                                       const SuperelementOptions& options = {});

// The sub-structure of `members` (indices, distinct) of `model`: their elements and nodes, the
// materials and sections, the joints, supports, prescribed DOFs, ties, constraints and point masses
// whose nodes are all among those nodes (loads are dropped). `node_of[i]` receives the sub-model's
// index of node i, or -1.
Model sub_model(const Model& model, const std::vector<int>& members, std::vector<int>& node_of);

}  // namespace beamfea
