#pragma once
// The model at large displacements and finite rotations: state on SO(3), exact kinematics of rigid
// links and joints, residual and consistent tangent over the independent coordinates.
//
// State (NonlinearState): positions x and rotations R in SO(3) of every node, joint coordinates q
// (scalar angles/translations), and for spherical joints a relative rotation matrix Q. Rotations
// are never accumulated as rotation vectors.
//
// Independent coordinates ("gens"): the 6 DOFs of every node that is not a slave (translations,
// then SPATIAL spins: x <- x + du, R <- exp(dw) R, the increment convention of
// elements/corotational_beam.hpp), and every joint coordinate (scalars: q <- q + dq; spherical:
// Q <- exp(A dq) Q, A = the joint's axes, body-fixed in the body of nodes[0]).
//
// Slaves follow exactly from the spanning forest of DofMap (rigid links and joints):
//   rigid link p -> s:  x_s = x_p + R_p (X_s - X_p),  R_s = R_p
//   joint n0 -> n1:     R_n1 = R_n0 exp(q_1 [a_1]) exp(q_2 [a_2]) ...   (rotational coordinates,
//                       product of exponentials, axes body-fixed in nodes[0], Pashkevich eq. 1)
//                       x_n1 = x_n0 + R_n0 sum_t a_t q_t                  (virtual-spring translations)
//                       spherical: R_n1 = R_n0 Q
//   a joint met from nodes[1] to nodes[0] in the forest is inverted exactly.
//
// Each independent coordinate i moves every node downstream of it by a spatial twist
// xi_i = (v_i, w_i): a point y moves by v_i + w_i x y, a frame spins by w_i. The Jacobian of a
// node's raw DOFs (translation, spatial spin) is T_n = [v_i + w_i x x_n ; w_i] over its chain of
// upstream coordinates. The residual over the independent coordinates is r = T^T (f_int - f_app)
// (virtual work), and its consistent tangent
//   K_t = T^T K_raw T + G,
//   G_ij = sum_slaves g [ f_g . d(v_i + w_i x x_g)/d_j + m_g . d w_i / d_j ]
//        = sum_g f_g . ( [xi_j, xi_i]_v + [xi_j, xi_i]_w x x_g  +  w_i x (v_j + w_j x x_g) )
//          + m_g . [xi_j, xi_i]_w                      (bracket only for j strictly upstream of i)
// with the Lie bracket of twists [xi_a, xi_b] = (w_a x v_b - w_b x v_a, w_a x w_b). G is the
// constraint-curvature (geometric) stiffness of rigid links and joints: a chain of rigid links
// carrying axial force buckles through it. Coordinates updated "simultaneously" (a node's three
// spins, a spherical joint's three spins, a node's three translations) do not bracket each other,
// except the three spins of a spherical joint met from nodes[1] in the forest, whose axes are fixed in
// the body they move: those bracket each other both ways.
//
// Not supported (ModelError): closed loops of rigid links/joints (the loop-closing edge is named);
// springs on spherical joints.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "core/dof_map.hpp"
#include "core/model.hpp"
#include "elements/corotational_beam.hpp"
#include "elements/member_loads.hpp"

namespace beamfea {

struct NonlinearState {
  std::vector<Vec3> x;                 // node positions
  std::vector<Mat3> R;                 // node rotations from the reference
  std::vector<Eigen::VectorXd> q;      // joint coordinates (spherical: rotation vector of Q, output only)
  std::vector<Mat3> Q;                 // spherical joints: relative rotation; identity otherwise
};

// The Configuration (core/dof_map.hpp) of a state: positions, rotations, current spatial axes.
Configuration configuration_of(const Model& model, const NonlinearState& state);

struct Twist {
  Vec3 v = Vec3::Zero();
  Vec3 w = Vec3::Zero();
};

class NonlinearStructure {
 public:
  explicit NonlinearStructure(const Model& model);

  enum class GenKind { NodeTranslation, NodeSpin, JointScalar, JointSpherical };
  struct Gen {
    GenKind kind;
    int owner = -1;  // node or joint
    int comp = 0;    // component or coordinate
    int group = 0;   // coordinates of one group are updated simultaneously (no mutual bracket)
    int raw = -1;    // raw DOF index (DofMap numbering)
    // The group's axes are fixed in the body they move (a spherical joint met from nodes[1]): its
    // coordinates bracket each other both ways.
    bool mutual = false;
  };

  const Model& model() const { return *model_; }
  const DofMap& reference_map() const { return map_; }
  int size() const { return static_cast<int>(gens_.size()); }
  const std::vector<Gen>& gens() const { return gens_; }
  int gen_of_raw(int raw) const { return raw_to_gen_[raw]; }
  // The upstream coordinates of a node, upstream first.
  const std::vector<int>& chain(int node) const { return chain_[node]; }
  bool is_slave(int node) const { return map_.is_slave(node); }
  // Lengths for making rotations commensurable with translations.
  double length_scale() const { return L_; }
  // True when gen i is a rotation-like coordinate (spin, joint angle).
  bool is_rotation(int i) const;

  NonlinearState reference_state() const;
  // state (+) delta over gens (delta indexed like gens); slaves recomputed.
  NonlinearState retract(const NonlinearState& base, const Eigen::VectorXd& delta) const;
  // d(fresh increment)/d(delta) at base (+) delta: identity except spin blocks T_s(delta_w).
  // Returned as a sparse matrix over gens.
  SparseMatrix retraction_jacobian(const Eigen::VectorXd& delta) const;
  // Recomputes slave poses and joint outputs from the independent part of `s`.
  void complete(NonlinearState& s) const;

  // Twists of all gens at a state.
  std::vector<Twist> twists(const NonlinearState& s) const;
  // Row of raw DOF (node n, comp k in 0..5) over gens: pairs (gen, coefficient).
  std::vector<std::pair<int, double>> raw_row(const NonlinearState& s, const std::vector<Twist>& tw, int node,
                                              int comp) const;

  struct Evaluation {
    Eigen::VectorXd f_int_raw;    // internal force over raw DOFs (beams, joint springs)
    Eigen::VectorXd residual;     // over gens: T^T (f_int - f_app)
    SparseMatrix tangent;         // over gens: T^T K_raw T + G (empty when not asked)
    std::vector<Vec12> end_forces;  // per element: co-rotated local end forces (beams), zero otherwise
    double energy = 0.0;
  };
  // f_app: applied raw forces (external loads times the load factor, reactions on slaves).
  // dead_load_factor: the load factor of the default case's loads between the nodes of beams
  // (member loads, self-weight): f_app holds them at the reference configuration (external_force);
  // their consistent vector follows the chords (elements/member_loads.hpp, DeadLoadTerm), so
  // evaluate adds dead_load_factor x (vector at s - vector at the reference) and its derivative
  // (an unsymmetric load stiffness) to the tangent.
  Evaluation evaluate(const NonlinearState& s, const Eigen::VectorXd& f_app, bool with_tangent,
                      double dead_load_factor = 0.0) const;
  // The change of the dead loads' raw vector from the reference to s, per unit load factor.
  Eigen::VectorXd dead_load_change(const NonlinearState& s) const;
  // T^T f_raw over gens (virtual work of raw forces).
  Eigen::VectorXd reduce(const NonlinearState& s, const std::vector<Twist>& tw, const Eigen::VectorXd& f_raw) const;
  // The constraint-curvature matrix G alone, for raw forces f (over gens).
  SparseMatrix constraint_curvature(const NonlinearState& s, const std::vector<Twist>& tw,
                                    const Eigen::VectorXd& f_raw) const;

  // Displacement (x - X) and rotation vector log(R) of a node.
  Vec6 node_displacement(const NonlinearState& s, int node) const;
  // Cubic shape of a co-rotational beam at xi, displacement from the reference (for drawing).
  Vec3 beam_shape(const NonlinearState& s, int element, double xi) const;

 private:
  void add_gen(Gen g);
  const Model* model_;
  DofMap map_;
  double L_ = 1.0;
  std::vector<Gen> gens_;
  std::vector<int> raw_to_gen_;
  std::vector<std::vector<int>> chain_;
  std::vector<std::optional<CorotationalBeam>> beams_;
  std::vector<std::vector<DeadLoadTerm>> dead_;  // per element: dead loads between its nodes
  std::vector<Vec12> dead_ref_;                   // their vector at the reference configuration
};

}  // namespace beamfea
