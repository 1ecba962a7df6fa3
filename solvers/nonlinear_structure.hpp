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
// Closed loops (solvers/nonlinear_structure_closures.cpp). An edge of the constraint graph outside
// the forest (DofMap::loop_edges: a rigid link or joint that closes a loop, through the ground or
// not) is not eliminated but kept as six nonlinear equality constraints c(x) = 0 on the state. Its
// "virtual body" b' is where nodes[1] = b would be if the edge were part of the tree, carried by
// nodes[0] = a:
//   rigid link  y = x_a + R_a (X_b - X_a),  S = R_a
//   joint       y = x_a + R_a t(q),         S = R_a P(q)   (P: product of exponentials, or Q)
//   c_t = x_b - y   (3),   c_r = log(R_b S^T)   (3, spatial)
// Its multipliers mu = (F, M) are the force and moment that a's side exerts on b through the edge
// (a force F and moment M on b, -F and -M on the virtual body b'). The residual gains B^T mu with
// B the virtual work of that pair of wrenches over the gens:
//   B_t = sum_{i in chain b} (v_i + w_i x x_b) - sum_{i in chain b'} (v_i + w_i x y)   (= dc_t exactly)
//   B_r = sum_{i in chain b} w_i - sum_{i in chain b'} w_i       (= dc_r where c_r = 0)
// and the tangent gains d(B^T mu)/dx at fixed mu: the constraint curvature of the two wrenches,
// the same formula G as for the forces at slave nodes, with the point y and the chain of b'. The
// exact gradient of c_r is T_s(c_r)^-1 (w_b - M w_S), M = R_b S^T (T_s: core/rotation.hpp).
// No penalty: the solvers add mu as unknowns (a saddle-point system).
//
// Not supported (ModelError): springs on spherical joints.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/dof_map.hpp"
#include "core/model.hpp"
#include "elements/corotational_beam.hpp"
#include "elements/span_loads.hpp"

namespace beamfea {

struct NonlinearState {
  std::vector<Vec3> x;                 // node positions
  std::vector<Mat3> R;                 // node rotations from the reference
  std::vector<Eigen::VectorXd> q;      // joint coordinates (spherical: rotation vector of Q, output only)
  std::vector<Mat3> Q;                 // spherical joints: relative rotation; identity otherwise
};

// A joint's relative motion in the frame of nodes[0]: the rotation exp(q_1 a_1) exp(q_2 a_2) ... of
// its scalar rotational coordinates (identity for a spherical joint: its Q is kept in the state), and
// the translation sum_t a_t q_t of a virtual spring's translations.
Mat3 joint_product(const Joint& j, const Eigen::VectorXd& q);
Vec3 joint_offset(const Joint& j, const Eigen::VectorXd& q);

// Rank-revealing choice of independent constraint rows (Householder QR of C^T with column pivoting):
// C is m x n, already scaled so that its entries are commensurable (rows and coordinates in lengths:
// rotation rows and rotation coordinates' columns scaled by the model length). A row whose pivot is
// below `tolerance` times the largest is redundant: a linear combination of the kept ones. Returns
// the kept rows (ascending) and the redundant ones.
// Why 1e-9: exact elimination leaves rounding of ~1e-15 relative in a row that truly vanishes, while
// a genuine constraint of a model with aspect ratio up to 1e6 keeps pivots far above 1e-9.
inline constexpr double kRedundancyTolerance = 1e-9;
struct RowSelection {
  std::vector<int> kept, redundant;
};
RowSelection independent_rows(const Eigen::MatrixXd& C, double tolerance = kRedundancyTolerance);

// The Configuration (core/dof_map.hpp) of a state: positions, rotations, current spatial axes.
Configuration configuration_of(const Model& model, const NonlinearState& state);

struct Twist {
  Vec3 v = Vec3::Zero();
  Vec3 w = Vec3::Zero();
};

class NonlinearStructure {
 public:
  // `loads`: the reference load whose member loads and self-weight act as dead loads (a case or
  // combination of the model, or its default loads; it must outlive the structure's construction).
  NonlinearStructure(const Model& model, const LoadSet& loads);
  explicit NonlinearStructure(const Model& model) : NonlinearStructure(model, model.default_loads()) {}

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
  // The co-rotational element of a beam (solvers/element_factory.hpp), null for a rigid link.
  const FrameElement* beam(int element) const { return beams_[element].get(); }
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
  // mu: multipliers of the closures (empty: none, or all zero); residual += B^T mu, tangent +=
  // closure_curvature(mu).
  // dead_load_factor: the load factor of the default case's loads between the nodes of beams
  // (member loads, self-weight): f_app holds them at the reference configuration (external_force);
  // their consistent vector follows the chords (elements/span_loads.hpp, DeadLoadTerm), so
  // evaluate adds dead_load_factor x (vector at s - vector at the reference) and its derivative
  // (an unsymmetric load stiffness) to the tangent.
  Evaluation evaluate(const NonlinearState& s, const Eigen::VectorXd& f_app, bool with_tangent,
                      const Eigen::VectorXd& mu = Eigen::VectorXd(), double dead_load_factor = 0.0) const;
  // The change of the dead loads' raw vector from the reference to s, per unit load factor.
  Eigen::VectorXd dead_load_change(const NonlinearState& s) const;
  // T^T f_raw over gens (virtual work of raw forces).
  Eigen::VectorXd reduce(const NonlinearState& s, const std::vector<Twist>& tw, const Eigen::VectorXd& f_raw) const;
  // The constraint-curvature matrix G alone, for raw forces f (over gens).
  SparseMatrix constraint_curvature(const NonlinearState& s, const std::vector<Twist>& tw,
                                    const Eigen::VectorXd& f_raw) const;

  // Closures of loops: one per DofMap loop edge, six rows each (ux uy uz rx ry rz of c).
  struct Closure {
    ConstraintEdge edge;       // parent = nodes[0] (a), child = nodes[1] (b)
    std::vector<int> chain;    // upstream gens of the virtual body b', upstream first
  };
  const std::vector<Closure>& closures() const { return closures_; }
  int closure_rows() const { return 6 * static_cast<int>(closures_.size()); }
  // "joint 'j4' ry" / "element 'r3' uz": what a closure row constrains.
  std::string describe_closure_row(int row) const;
  // Pose of the virtual body b' of closure k.
  std::pair<Vec3, Mat3> closure_body(const NonlinearState& s, int k) const;
  // c(x), closure_rows() values.
  Eigen::VectorXd closure_values(const NonlinearState& s) const;
  // Exact gradient of c over gens (closure_rows() x size()).
  SparseMatrix closure_jacobian(const NonlinearState& s, const std::vector<Twist>& tw) const;
  // B: the virtual work of the multipliers' wrenches over gens (closure_rows() x size()).
  SparseMatrix closure_force_rows(const NonlinearState& s, const std::vector<Twist>& tw) const;
  // d(B^T mu)/d gens at fixed mu (size() x size()).
  SparseMatrix closure_curvature(const NonlinearState& s, const std::vector<Twist>& tw, const Eigen::VectorXd& mu) const;

  // Displacement (x - X) and rotation vector log(R) of a node.
  Vec6 node_displacement(const NonlinearState& s, int node) const;
  // Cubic shape of a co-rotational beam at xi, displacement from the reference (for drawing).
  Vec3 beam_shape(const NonlinearState& s, int element, double xi) const;

 private:
  void add_gen(Gen g);
  void build_closures();
  // Adds to t the curvature of a wrench (f, m) held at a point x carried by the gens of `chain`.
  void add_point_curvature(const Vec3& x, const Vec3& f, const Vec3& m, const std::vector<int>& chain,
                           const std::vector<Twist>& tw, std::vector<Eigen::Triplet<double>>& t) const;
  const Model* model_;
  DofMap map_;
  double L_ = 1.0;
  std::vector<Gen> gens_;
  std::vector<int> raw_to_gen_;
  std::vector<std::vector<int>> chain_;
  std::vector<std::unique_ptr<FrameElement>> beams_;  // solvers/element_factory.hpp
  std::vector<std::vector<DeadLoadTerm>> dead_;  // per element: dead loads between its nodes
  std::vector<Vec12> dead_ref_;                   // their vector at the reference configuration
  std::vector<Closure> closures_;
  std::vector<char> loop_joint_;  // per joint: 1 when it closes a loop
};

}  // namespace beamfea
