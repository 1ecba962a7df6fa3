#pragma once
// DofMap: numbering of degrees of freedom and elimination of constraints.
//
// Glossary
//   raw DOF       a node component (ux uy uz rx ry rz; 6 per node) or a joint coordinate; what
//                 elements, loads and supports refer to. Raw index: 6*node + comp for nodes, then
//                 the joint coordinates, joint by joint.
//   released      the relative rotations a joint frees; each is a raw DOF of its own, the joint
//                 coordinate q_i (revolute 1, universal 2, spherical 3).
//   slave         a node whose motion follows another node through a rigid link or a joint: the
//                 rigid links and joints form a graph; a spanning forest of it is rooted at
//                 supported nodes where possible, and every non-root node of a tree is a slave
//                 of its parent. Its raw DOFs are eliminated exactly (no penalty numbers).
//   independent   a raw DOF of a non-slave node, or a joint coordinate.
//   prescribed    an independent DOF whose value is given: a support (value 0) or an entry of
//                 "prescribed" (an imposed displacement or actuator motion). Also the value of
//                 a support or prescription that falls on a slave node.
//   dependent     an independent DOF eliminated by an extra constraint: a loop of rigid links
//                 and joints closed by an edge outside the forest, a support on a slave, or a
//                 user's constraint row (a skewed support's fixed axis, a tie, a linear constraint).
//   user rows     the rows of skewed supports, ties and linear constraints (Model::supports with
//                 axes, Model::ties, Model::constraints): each must remove a DOF of its own; a
//                 redundant or contradictory one is an InputError naming it (/ties/<i> ...).
//   free          independent, neither prescribed nor dependent: the unknowns of the system.
//   condensation  eliminating all free DOFs but those of one node (the stiffness analysis).
//
// The map is linear about a configuration: raw u = T_f u_free + T_p u_prescribed. For the
// reference configuration it is exact for linear analyses; nonlinear analyses rebuild T about
// the current configuration (Configuration), since rigid offsets and joint axes turn with bodies.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <map>
#include <string>
#include <vector>

#include "core/model.hpp"
#include "core/sparse_row.hpp"

namespace beamfea {

using SparseMatrix = Eigen::SparseMatrix<double>;                 // column-major CSC
using SparseRowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// The current geometry that the linearised constraints depend on.
struct Configuration {
  std::vector<Vec3> x;        // node positions
  std::vector<Mat3> R;        // node rotations (from the reference)
  std::vector<std::vector<Vec3>> joint_axes;  // current spatial axes of each joint's coordinates
};
// The reference configuration of a model: x = X, R = I, axes as given.
Configuration reference_configuration(const Model& m);
// The same written over `c` (its vectors keep their storage: a cache that builds map after map).
void reference_configuration(const Model& m, Configuration& c);

// One edge of the constraint graph (a rigid link or a joint).
struct ConstraintEdge {
  enum class Kind { Rigid, Joint };
  Kind kind = Kind::Rigid;
  int index = -1;   // element index (rigid) or joint index
  int parent = -1;  // node whose motion is carried over
  int child = -1;   // the slave node
  bool forward = true;  // joint only: parent is the joint's nodes[0]
};

class DofMap {
 public:
  DofMap(const Model& model, const Configuration& configuration) { rebuild(model, configuration); }
  explicit DofMap(const Model& model) : DofMap(model, reference_configuration(model)) {}

  // Builds the map of `model` in `configuration` over this one: the same map as a new DofMap's,
  // written into the storage of the last build (its vectors, sparse matrices and build scratch), so
  // that a sweep whose geometry changes every case builds map after map without allocating once
  // the sizes are reached. On a throw the map is unusable until the next rebuild succeeds.
  void rebuild(const Model& model, const Configuration& configuration);

  int raw_size() const { return n_raw_; }
  int free_size() const { return n_free_; }
  int prescribed_size() const { return static_cast<int>(prescribed_.size()); }

  int raw_node(int node, int comp) const { return 6 * node + comp; }
  int raw_joint(int joint, int coord) const { return joint_offset_[joint] + coord; }
  int raw_index(const DofRef& d) const;
  DofRef raw_ref(int raw) const;

  // raw u = T_free * u_free + T_prescribed * u_prescribed
  const SparseRowMatrix& T_free() const { return Tf_; }
  const SparseRowMatrix& T_prescribed() const { return Tp_; }

  // What each free DOF is (an independent raw DOF).
  const std::vector<DofRef>& free_dofs() const { return free_refs_; }
  // What each prescribed value is, and its value in the model (supports: 0).
  struct PrescribedValue {
    DofRef dof;
    double value = 0.0;
    bool support = false;  // from "supports" (reaction reported) rather than "prescribed"
    // >= 0: the value of linear constraint `constraint` (no raw DOF is held; `dof` is its first
    // term's, for messages): a column of T_prescribed like the others.
    int constraint = -1;
  };
  const std::vector<PrescribedValue>& prescribed() const { return prescribed_; }
  Eigen::VectorXd prescribed_values() const;

  // Free index of an independent raw DOF, or -1 when it is not free.
  int free_index(int raw) const { return raw_to_free_[raw]; }
  // Prescribed index of a raw DOF that is prescribed, or -1.
  int prescribed_index(int raw) const;

  bool is_slave(int node) const { return parent_edge_[node] >= 0; }
  const std::vector<ConstraintEdge>& tree_edges() const { return tree_edges_; }
  // Tree edges in an order where parents come before children.
  const std::vector<int>& tree_order() const { return tree_order_; }
  // The edges outside the forest: each closes a loop of rigid links and joints (written from the
  // edge's nodes[0] (parent) to nodes[1] (child)). Linear analyses eliminate their six rows; the
  // nonlinear ones keep them as constraints with multipliers (solvers/nonlinear_structure.hpp).
  const std::vector<ConstraintEdge>& loop_edges() const { return loop_edges_; }

  Eigen::VectorXd expand(const Eigen::VectorXd& u_free, const Eigen::VectorXd& u_prescribed) const;
  // The same written over `u` (its storage kept when it has the size).
  void expand(const Eigen::VectorXd& u_free, const Eigen::VectorXd& u_prescribed, Eigen::VectorXd& u) const;
  Eigen::VectorXd reduce(const Eigen::VectorXd& f_raw) const { return Tf_.transpose() * f_raw; }
  // The same written over `f` (its storage kept when it has the size).
  void reduce(const Eigen::VectorXd& f_raw, Eigen::VectorXd& f) const { f.noalias() = Tf_.transpose() * f_raw; }

  // Constraint forces from the raw residual r = f_int - f_ext at an equilibrium.
  struct ConstraintForces {
    std::vector<double> prescribed;        // one per prescribed value: reaction (force or moment)
    std::vector<Vec6> joint;               // per joint: force and moment that the body of
                                           // nodes[0] exerts on the body of nodes[1], global axes
    std::vector<Vec6> loop;                // per loop edge: multipliers of its six rows (force and
                                           // moment that nodes[0]'s side exerts on nodes[1]); the
                                           // minimum-norm split where rows are redundant
    std::vector<Vec6> support_local;       // per support: the reaction in its frame (skewed
                                           // supports only: the multipliers of their rows)
    std::vector<Vec6> tie;                 // per tie: the force (moment) it applies to nodes[1]
                                           // along each tied DOF (nodes[0] takes the opposite)
    std::vector<double> constraint;        // per linear constraint: the multiplier lambda; the
                                           // constraint applies coefficient * lambda to each DOF
    Eigen::VectorXd user_raw;              // the raw forces of the user rows, sum lambda C
  };
  ConstraintForces constraint_forces(const Eigen::VectorXd& r_raw) const;
  // The arrays of the computation (per node, the residual accumulated from the leaves; the residual
  // over independent DOFs and the one the multipliers leave), kept by a caller that solves case
  // after case.
  struct ConstraintForceScratch {
    std::vector<Vec6> node;
    Eigen::VectorXd r_ind, r;
  };
  // The same written over `out` (its vectors keep their storage, and `scratch`'s).
  void constraint_forces(const Eigen::VectorXd& r_raw, ConstraintForces& out, ConstraintForceScratch& scratch) const;

  // The constraint rows found redundant (over-constrained loops, supports on one rigid body): their
  // reactions are statically indeterminate; e.g. "joint 'jC' uz", "node 'D' dof rx". Linear analyses
  // report the minimum-norm split of those reactions.
  const std::vector<std::string>& redundant_constraints() const { return redundant_names_; }

  // Prescribed values that must agree (redundant supports on one rigid body): returns the
  // message of the first conflict for these values, or "" when consistent.
  std::string check_consistency(const Eigen::VectorXd& u_prescribed) const;

  // Points the map at `model`, which must equal the model it was built from in everything the
  // constructor reads (the per-thread cache of solvers/structure_cache.hpp checks that before it
  // reuses a map for a sweep's next case): the map's later calls (messages, constraint forces)
  // then read the live model instead of a destroyed one.
  void rebind(const Model& model) { model_ = &model; }

 private:
  struct Term {
    int ind;
    double coef;
  };
  using Row = std::vector<Term>;
  // The forest (build_forest): adjacency lists, the candidate roots ranked, a breadth-first search.
  void build_forest(const Model& m);
  void build_adjacency(const Model& m);
  void rank_roots(const Model& m);
  void search_forest(const Model& m);
  void build_tree_rows(const Model& m, const Configuration& c);
  void build_extra_rows(const Model& m, const Configuration& c);
  // The extra rows eliminated (eliminate_extra_rows), the free DOFs numbered (number_free_dofs),
  // then Tf_ and Tp_ (build_transforms).
  void eliminate(const Model& m);
  void eliminate_extra_rows(const Model& m);
  void number_free_dofs();
  void build_transforms();
  // The expression of dependent independent DOF `ind` from the last elimination, or null.
  const SparseRow* dependent_expr(int ind) const;
  // Row k of loop edge `e` over raw DOFs, written over `row`.
  void edge_row_raw(const Model& m, const Configuration& c, const ConstraintEdge& e, int k, Row& row) const;

  const Model* model_ = nullptr;
  int n_nodes_ = 0;
  int n_raw_ = 0;
  int n_ind_ = 0;
  int n_free_ = 0;
  std::vector<int> joint_offset_;
  std::vector<int> parent_edge_;            // per node: index into tree_edges_ or -1
  std::vector<ConstraintEdge> tree_edges_;
  std::vector<int> tree_order_;
  std::vector<ConstraintEdge> loop_edges_;
  std::vector<int> raw_to_ind_;             // -1 for slave raw DOFs
  std::vector<int> ind_to_raw_;
  // Extra constraints: sum(row over raw) = sum(coef * prescribed) (loop edges, slave supports).
  struct ExtraRow {
    Row raw;                               // over raw DOFs
    std::vector<Term> rhs;                 // over prescribed indices
    int joint = -1, joint_row = -1;        // loop joint rows: which joint and component (0..5)
    int prescribed = -1;                   // slave support rows: which prescribed value
    int loop = -1;                         // loop edge rows: which loop edge (row = joint_row)
    int support = -1, tie = -1, constraint = -1;  // user rows: which item of the model
    int comp = -1;                         // skewed support and tie rows: which DOF (0..5)
  };
  // extra_[next++], emptied (its vectors keep their storage).
  ExtraRow& next_extra_row(std::size_t& next);
  bool is_user_row(const ExtraRow& x) const { return x.support >= 0 || x.tie >= 0 || x.constraint >= 0; }
  // The rows of skewed supports, ties and linear constraints, appended to extra_ from `next`.
  void build_user_rows(const Model& m, std::size_t& next);
  // A user row found redundant or contradictory (reduced to `e`, no free DOF left): InputError.
  [[noreturn]] void reject_user_row(const Model& m, const ExtraRow& x, const SparseRow& e, double scale) const;
  std::vector<ExtraRow> extra_;  // resized, not cleared, by a rebuild: each row keeps its storage
  // The link, joint or DOF an extra row came from, written over `out` (its storage kept).
  void describe_extra(const Model& m, const ExtraRow& x, std::string& out) const;
  // Extra row `x`, reduced to `e` with no free DOF left, recorded as redundant (the n_names-th
  // name, and the n_rows-th row where prescribed values remain; both counts advanced).
  void add_redundant_row(const Model& m, const ExtraRow& x, const SparseRow& e, double scale, std::size_t& n_names,
                         std::size_t& n_rows);
  std::vector<int> ind_prescribed_;         // per independent DOF: prescribed index or -1
  std::vector<PrescribedValue> prescribed_;
  std::vector<int> raw_prescribed_;         // per raw DOF: prescribed index or -1
  std::vector<int> raw_to_free_;
  std::vector<DofRef> free_refs_;
  std::vector<Row> redundant_;              // rows over prescribed indices that must vanish
  std::vector<std::string> redundant_names_;
  std::vector<std::string> redundant_what_;  // per redundant_ row: the link, joint or DOF it came from
  std::vector<SparseRow> extra_ind_;        // extra rows over independent DOFs
  std::vector<char> ind_dependent_;
  std::vector<Vec3> x_;                     // node positions of the configuration
  SparseRowMatrix Tf_, Tp_;
  SparseRowMatrix Tind_;                    // raw <- independent (tree only): the tree rows

  // The working arrays of a build (the forest's search, the slaves' rows, the elimination), kept
  // for the next rebuild. Not part of the map's value: a copy of a map starts with none.
  struct BuildScratch {
    struct Adj {
      ConstraintEdge::Kind kind;
      int index, other;
    };
    BuildScratch() = default;
    BuildScratch(const BuildScratch&) {}
    BuildScratch& operator=(const BuildScratch&) { return *this; }
    // build_forest
    std::vector<int> first, fill, support_count, order, queue;
    std::vector<Adj> adj;
    std::vector<std::array<char, 6>> held;
    std::vector<char> visited, used_rigid, used_joint;
    // build_tree_rows
    std::vector<int> slave_slot;
    RowStore slave_rows;
    SparseRow acc, lever;
    // eliminate: each dependent independent DOF's expression in a slot of `dependent` (slots
    // reused, with their storage, build after build), in the order the DOFs were eliminated.
    SparseRow row, e, expr;
    std::vector<SparseRow> dependent;
    std::vector<int> dependent_slot;  // per independent DOF: its slot in `dependent`, or -1
    std::vector<int> dependent_ind;   // per slot: the independent DOF
    std::vector<int> ind_to_free;
    std::vector<SparseRow::Term> tf, tp;
  };
  BuildScratch scratch_;
};

}  // namespace beamfea
