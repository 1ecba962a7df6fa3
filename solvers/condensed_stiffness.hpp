#pragma once
// The Cartesian stiffness matrix of one node: static condensation of all other free DOFs.
//
// K_c is defined by the minimum of the strain energy over all motions that give the node the
// displacement u_n:  1/2 u_n^T K_c u_n = min { 1/2 u^T K u : T_n u = u_n }, where T_n are the
// node's six rows of the DofMap transformation. It is computed from the saddle-point system
//   [ K    T_n^T ] [ X ]   [ 0 ]
//   [ T_n  0     ] [ M ] = [ I ]      K_c = -M,
// which stays regular when K itself is singular, as long as holding the node makes the
// structure stable (e.g. a chain ending in a spherical joint: K_c has rank 3 there).
// Rank and null space are decided on K_c scaled by the model's length (rotations x L).
//
// Any node (node_compliance): the node's motion u_n = T_n u over the coordinates u may be restricted
// (supports, prescribed values, closed loops, rigid links): T_n has rank r <= 6. With S = diag(1,1,1,
// L,L,L) and the coordinates' rotations scaled by 1/L, the SVD of the scaled S T_n splits R^6 into the
// r directions the node can move (U_r) and the 6 - r it cannot (rigid_directions). The saddle point
// with the r independent rows z = U_r^T S T_n u gives the stiffness K_z on the movable directions; K_z
// may be singular (the node moves freely: null_space, a mechanism direction of the node). Then
//   compliance C = S^-1 U_r K_z^+ U_r^T S^-1   (6x6, symmetric, finite: zero where the node cannot
//                                               move and in the free directions, where it is unbounded)
//   matrix     K = S U_r K_z U_r^T S           (the pseudo-inverse of C on the directions it can move)
// so that a node free in all six directions gets K = K_c and C = K_c^-1 exactly.
#include <string>
#include <vector>

#include "core/dof_map.hpp"
#include "core/model.hpp"
#include "solvers/condensation.hpp"
#include "solvers/mechanism.hpp"
#include "solvers/second_order.hpp"

namespace beamfea {

struct CondensedStiffnessOptions {
  double rank_tolerance = 1e-9;   // eigenvalue / largest eigenvalue of the length-scaled K_c
  // Singular value / largest of the length-scaled node rows S T_n below which the node cannot move
  // that way: rows eliminated exactly are zero up to rounding of the elimination (1e-14 relative).
  double motion_tolerance = 1e-10;
  void validate() const;
};

struct CondensedStiffness {
  bool ok = false;
  std::string message;
  Mat6 K = Mat6::Zero();
  // Zero in rigid directions, and (by convention: a finite matrix) in the directions where the node
  // moves freely, where the true compliance is unbounded: compliance_bounded() says whether there
  // are any, unbounded_directions() which they are. A zero entry alone does not say which.
  Mat6 compliance = Mat6::Zero();
  int rank = 0;
  std::vector<Vec6> null_space;    // unit vectors (in the length-scaled metric), u then rotation
  std::vector<Vec6> rigid_directions;  // directions the node cannot move (unit vectors, same metric)
  Vec6 eigenvalues = Vec6::Zero(); // of the length-scaled matrix, ascending
  std::vector<ZeroEnergyMode> modes;  // when holding the node leaves a mechanism
  std::vector<std::string> statically_indeterminate;  // redundant constraint rows (DofMap)
  // The linear solves of the condensation (analyses.<id>.solver): direct, or the model's iterative
  // solver; not_converged when an iterative solve stopped above its rtol (then not ok, no modes).
  SolverReport solver;
  bool not_converged = false;

  // The directions in which the node moves freely (mechanism directions of the node held nowhere
  // else), in the metric of null_space: a load (force, moment / L) with a component along one of
  // them does work along a motion that nothing resists, so the displacement is unbounded there.
  // They are the null space of the stiffness on the directions the node can move.
  const std::vector<Vec6>& unbounded_directions() const { return null_space; }
  // True when the compliance is the whole answer: every direction the node can move is resisted
  // (those it cannot move are in rigid_directions, with zero compliance).
  bool compliance_bounded() const { return null_space.empty(); }
};

// The saddle-point condensation itself, onto any list of raw DOFs: condense (solvers/condensation.hpp).

// Stiffness and compliance of a node (see the header comment) for a symmetric stiffness K (n x n) over
// some coordinates, the node's six raw rows Tn (6 x n) over the same coordinates, col_scale (n): 1 for a
// translation-like coordinate, 1/L for a rotation-like one, and the model's length L. Outcome not ok
// (message empty) when holding the node's movable directions still leaves a mechanism.
CondensedStiffness node_compliance(const SparseMatrix& K, const Eigen::MatrixXd& Tn, const Eigen::VectorXd& col_scale,
                                   double L, const CondensedStiffnessOptions& options = {});
// The same for a dense K (small models: solvers/dense_condensation.hpp).
CondensedStiffness node_compliance(const Eigen::MatrixXd& K, const Eigen::MatrixXd& Tn, const Eigen::VectorXd& col_scale,
                                   double L, const CondensedStiffnessOptions& options = {});

// Condensed stiffness of `node` for the reduced matrix K (free x free) of `map`. A sparse K is
// condensed by the iterative solver where the model's "solver" chooses it (solves_iteratively):
// X = K^-1 T_n^T by conjugate gradients with multigrid (the rigid-body modes as its near null
// space), K must then be positive definite; a K that only holding the node makes regular (a chain
// ending in a spherical joint) is condensed directly.
CondensedStiffness condense_to_node(const Model& model, const DofMap& map, const SparseMatrix& K, int node,
                                    const CondensedStiffnessOptions& options = {});
CondensedStiffness condense_to_node(const Model& model, const DofMap& map, const Eigen::MatrixXd& K, int node,
                                    const CondensedStiffnessOptions& options = {});

// Rank, null space and scaled eigenvalues of a 6x6 node stiffness (length scale L).
void analyse_rank(const Mat6& K, double L, double tolerance, CondensedStiffness& out);

// Linear (unloaded) condensed stiffness of a node of the model.
CondensedStiffness linear_node_stiffness(const Model& model, int node, const CondensedStiffnessOptions& options = {});
// The same, written over `out`: afterwards equal, field for field, to what the overload above
// returns, but its message and lists keep their storage, so that a caller condensing case after
// case into one CondensedStiffness (a sweep worker) allocates nothing for them.
void linear_node_stiffness(const Model& model, int node, CondensedStiffness& out,
                           const CondensedStiffnessOptions& options = {});

// Loaded-mode stiffness of a node (Klimchik, Pashkevich & Chablat's "loaded mode"): condensation
// of K + K_g, K_g the geometric stiffness (solvers/buckling.hpp) of the linear solution of the
// model's default loads (the preload: own weight, payload), linearised about the reference
// configuration. The second form about the linear solution of `loads` (a load case of the model).
CondensedStiffness loaded_node_stiffness(const Model& model, int node, const CondensedStiffnessOptions& options = {});
CondensedStiffness loaded_node_stiffness(const Model& model, const LoadSet& loads, int node,
                                         const CondensedStiffnessOptions& options = {});
// The same about the equilibrium and with the K_g that `preload` names (solvers/second_order.hpp:
// the linear static state or the second-order equilibrium; full or axial K_g).
CondensedStiffness loaded_node_stiffness(const Model& model, const LoadSet& loads, int node, const PreloadOptions& preload,
                                         const CondensedStiffnessOptions& options = {});

}  // namespace beamfea
