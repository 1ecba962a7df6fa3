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
#include <string>
#include <vector>

#include "core/dof_map.hpp"
#include "core/model.hpp"
#include "solvers/mechanism.hpp"

namespace beamfea {

struct CondensedStiffnessOptions {
  double rank_tolerance = 1e-9;   // eigenvalue / largest eigenvalue of the length-scaled K_c
  void validate() const;
};

struct CondensedStiffness {
  bool ok = false;
  std::string message;
  Mat6 K = Mat6::Zero();
  int rank = 0;
  std::vector<Vec6> null_space;    // unit vectors (in the length-scaled metric), u then rotation
  Vec6 eigenvalues = Vec6::Zero(); // of the length-scaled matrix, ascending
  std::vector<ZeroEnergyMode> modes;  // when holding the node leaves a mechanism
};

// The saddle-point condensation itself, onto any list of raw DOFs (rows of T_free).
struct RawCondensation {
  enum class Outcome { Ok, HeldDof, Mechanism };
  Outcome outcome = Outcome::Mechanism;
  Eigen::MatrixXd K;   // raw.size() square, symmetric
  int held = -1;       // Outcome::HeldDof: index into `raw` of a DOF with no free motion at all
};
RawCondensation condense_to_raw_dofs(const DofMap& map, const SparseMatrix& K, const std::vector<int>& raw);

// Condensed stiffness of `node` for the reduced matrix K (free x free) of `map`.
CondensedStiffness condense_to_node(const Model& model, const DofMap& map, const SparseMatrix& K, int node,
                                    const CondensedStiffnessOptions& options = {});

// Rank, null space and scaled eigenvalues of a 6x6 node stiffness (length scale L).
void analyse_rank(const Mat6& K, double L, double tolerance, CondensedStiffness& out);

// Linear (unloaded) condensed stiffness of a node of the model.
CondensedStiffness linear_node_stiffness(const Model& model, int node, const CondensedStiffnessOptions& options = {});

// Loaded-mode stiffness of a node (Klimchik, Pashkevich & Chablat's "loaded mode"): condensation
// of K + K_g, K_g the geometric stiffness (solvers/buckling.hpp) of the linear solution of the
// model's default loads (the preload: own weight, payload), linearised about the reference
// configuration.
CondensedStiffness loaded_node_stiffness(const Model& model, int node, const CondensedStiffnessOptions& options = {});

}  // namespace beamfea
