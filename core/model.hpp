#pragma once
// The structural model: what the user described, after parsing and meshing.
//
// Units are the user's consistent set (e.g. N, m, Pa or N, mm, MPa); beamfea never converts.
// Indices (int) refer to the vectors of Model; the user's ids are kept for messages and output.
//
// A *member* is what the user wrote in "elements"; a beam member with "divisions": n is meshed
// into n *elements* of equal length with n-1 internal nodes named "<member>#1" ... "<member>#(n-1)".
#include <array>
#include <algorithm>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/rotation.hpp"

namespace beamfea {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// Node DOF components, in this order everywhere: ux uy uz rx ry rz.
inline constexpr std::array<const char*, 6> kDofNames{"ux", "uy", "uz", "rx", "ry", "rz"};
// Index of a DOF name ("ux" ... "rz"), or -1.
int dof_index(const std::string& name);

// Node, Material, Section, Element, Joint, Support, Prescribed, Tie and LinearConstraint: a field added here that the
// DofMap or LinearStructure constructors read must join the cache key's comparison in
// solvers/structure_cache.cpp, or a sweep would reuse a stale map.
struct Node {
  std::string id;
  Vec3 x;                     // reference position
  int member = -1;            // >= 0 for a node made by meshing a member
};

struct Material {
  std::string id;
  double E = 0.0;
  double G = 0.0;
  double density = 0.0;   // mass per unit volume (0: massless); self-weight and mass matrices
  double alpha = 0.0;     // coefficient of thermal expansion (strain per degree); temperature loads
};

struct Section {
  std::string id;
  double A = 0.0;
  double Iy = 0.0;   // second moment about local y: bending in the local x-z plane
  double Iz = 0.0;   // second moment about local z: bending in the local x-y plane
  double J = 0.0;    // torsion constant
  double ky = 0.0;   // shear correction factors: shear areas A/ky (along local y), A/kz (along z)
  double kz = 0.0;   // of Timoshenko beams; 0 = not given (a Timoshenko beam then needs them)
};

enum class MemberType { Beam, Rigid };
// Beam theory of a beam member: Euler-Bernoulli (the default) or shear-deformable Timoshenko.
enum class BeamTheory { EulerBernoulli, Timoshenko };
// Which sign of axial force a beam member carries: both (the default), or only tension (a bracing
// rod, a cable) or only compression (a contact strut); solvers/second_order.hpp iterates on them.
enum class MemberBehaviour { Both, TensionOnly, CompressionOnly };

// A member as the user wrote it.
struct Member {
  std::string id;
  MemberType type = MemberType::Beam;
  std::array<int, 2> nodes{};     // end nodes
  int material = -1;              // beams only
  int section = -1;               // beams only
  Vec3 orientation = Vec3::Zero();  // a vector in the local x-z plane (OpenSees' vecxz)
  BeamTheory theory = BeamTheory::EulerBernoulli;
  int divisions = 1;
  MemberBehaviour behaviour = MemberBehaviour::Both;
  std::vector<int> elements;      // the elements meshed from it, in order from nodes[0] to nodes[1]
  // End releases, local DOFs ux uy uz rx ry rz at the start (nodes[0]) and at the end (nodes[1]):
  // true where the member's end does not follow its node (elements/released_element.hpp). The
  // first segment takes the start's, the last the end's.
  std::array<std::array<bool, 6>, 2> releases{};
  // Rigid end zones: lengths at the start and at the end, along the member's flexible axis, that
  // are rigid (Frame3DD's node radii); and eccentricities: global vectors from each node to the
  // member's end (core/meshing.hpp places the flexible part between the two).
  std::array<double, 2> rigid_ends{};
  std::array<Vec3, 2> offsets{Vec3::Zero(), Vec3::Zero()};
};

// An analysis element: a beam between two nodes, or an exact rigid link.
struct Element {
  std::string id;
  MemberType type = MemberType::Beam;
  std::array<int, 2> nodes{};
  int material = -1;
  int section = -1;
  Vec3 orientation = Vec3::Zero();
  BeamTheory theory = BeamTheory::EulerBernoulli;
  int member = -1;
  // Released local DOFs in the element's DOF order (node 1's six, then node 2's): statically
  // condensed inside the element (elements/released_element.hpp).
  std::array<bool, 12> released{};
  bool has_releases() const { return std::any_of(released.begin(), released.end(), [](bool r) { return r; }); }
  // Rigid arms: global vectors from each node to the element's flexible end (zero: the end is at
  // its node); the element's beam lies between the flexible ends (elements/offset_element.hpp).
  std::array<Vec3, 2> offsets{Vec3::Zero(), Vec3::Zero()};
  bool has_offsets() const { return !offsets[0].isZero(0.0) || !offsets[1].isZero(0.0); }
};

enum class JointType { Revolute, Universal, Spherical, VirtualSpring, Prismatic };
const char* joint_type_name(JointType t);
int joint_coordinate_count(JointType t);

// A joint joins two coincident nodes and frees relative motions along/about its axes.
// The axes are fixed in the body of nodes[0]. Revolute: R2 = R1 exp(q a); universal (Cardan):
// R2 = R1 exp(q1 a1) exp(q2 a2), a2 carried by the cross; spherical: three rotations.
// A virtual spring (the 6-D virtual joint of the VJM, Pashkevich et al. 2010, eq. 1) has six
// coordinates, three translations then three rotations along/about the axes of its frame:
// T_3D(theta) = Tx Ty Tz Rx Ry Rz.
// A prismatic joint has one translation q along its axis a (fixed in nodes[0]'s body):
// x2 = x1 + R1 a q, R2 = R1 (a slider; the translation of a virtual spring with one coordinate).
// stiffness[i] = 0 means a passive (free) coordinate, > 0 an actuator spring on q_i; a full
// (symmetric) stiffness_matrix, when given, replaces the diagonal: energy 1/2 q^T K q.
struct Joint {
  std::string id;
  JointType type = JointType::Revolute;
  std::array<int, 2> nodes{};
  std::vector<Vec3> axes;         // unit vectors, one per coordinate
  int translations = 0;           // the first `translations` coordinates are translations
  std::vector<double> stiffness;  // one per coordinate
  Eigen::MatrixXd stiffness_matrix;  // empty, or coordinates() x coordinates()
  // Range [lo, hi] of each coordinate, measured from the reference geometry (empty: none). Checked
  // by poses (solvers/pose.hpp); analyses about a pose do not read them.
  std::vector<std::array<double, 2>> limits;
  std::vector<double> damping;    // viscous coefficient per coordinate (empty: none); dynamics only
  int coordinates() const { return static_cast<int>(axes.size()); }
  bool is_translation(int c) const { return c < translations; }
  // The stiffness as a matrix (the diagonal when no full matrix was given).
  Eigen::MatrixXd stiffness_as_matrix() const;
  bool has_stiffness() const;
};

// A raw degree of freedom: component `comp` of node `index`, or coordinate `comp` of joint `index`.
struct DofRef {
  enum class Owner { Node, Joint };
  Owner owner = Owner::Node;
  int index = -1;
  int comp = -1;
  bool operator==(const DofRef&) const = default;
};

// A support fixes DOFs of a node at 0. A skewed support names them in its own orthonormal frame:
// row k of `axes` is the frame's axis k in global components, and fixing component k (ux, uy, uz)
// holds axes.row(k) . u = 0 (rx, ry, rz: axes.row(k - 3) . theta = 0), an inclined roller.
struct Support {
  int node = -1;
  std::array<bool, 6> fixed{};
  bool skewed = false;          // "axes" given: the DOFs are in that frame
  Mat3 axes = Mat3::Identity();  // rows: the frame's axes (global components)
};

// A tie (OpenSees' equalDOF): the listed DOFs of nodes[1] equal those of nodes[0], in global axes.
struct Tie {
  std::array<int, 2> nodes{};
  std::array<bool, 6> dofs{};
};

// A linear multi-point constraint: sum over terms of coefficient * u(dof) = value, over node DOFs
// (translations, and rotations: the rotation vector's components).
struct ConstraintTerm {
  DofRef dof;
  double coefficient = 0.0;
};
struct LinearConstraint {
  std::vector<ConstraintTerm> terms;
  double value = 0.0;
};

struct Prescribed {
  DofRef dof;
  double value = 0.0;
};

struct NodalLoad {
  int node = -1;
  Vec3 force = Vec3::Zero();
  Vec3 moment = Vec3::Zero();
};

// A point mass at a node (payload, motor): mass, and optionally its 3x3 rotational inertia
// about the node in global axes (symmetric positive semi-definite; zero when not given).
struct PointMass {
  int node = -1;
  double mass = 0.0;
  Mat3 inertia = Mat3::Zero();
};

// The damping of the dynamic analyses (frequency response, transient), the top-level "damping":
// Rayleigh, C = alpha M + beta K of the constrained system; or modal, a damping ratio per mode
// (the last one given holds for the higher modes). Joints add their own viscous coefficients
// (Joint::damping) to either.
struct Damping {
  enum class Kind { None, Rayleigh, Modal };
  Kind kind = Kind::None;
  double alpha = 0.0, beta = 0.0;
  std::vector<double> modal;
  // The damping ratio of mode k (0-based): modal[k], or the last ratio beyond; 0 when not modal.
  double modal_ratio(std::size_t k) const { return modal.empty() ? 0.0 : modal[std::min(k, modal.size() - 1)]; }
};

// The linear solver of every analysis that solves with the stiffness, the top-level "solver"
// (docs/analyses/solver.md): a direct sparse factorisation, an iterative Krylov solve with an
// algebraic multigrid preconditioner (PETSc), or the choice made from the model's size (Auto).
struct SolverChoice {
  enum class Type { Auto, Direct, Iterative };
  // Default: hypre's BoomerAMG where PETSc has it (Debian's has), GAMG otherwise.
  enum class Preconditioner { Default, Gamg, Hypre };
  Type type = Type::Auto;
  double rtol = 1e-10;                  // relative residual ||F - K u|| / ||F|| an iterative solve must reach
  Preconditioner preconditioner = Preconditioner::Default;
  int max_iterations = 10000;           // an iterative solve that needs more has not converged
  bool given = false;                   // the model has a "solver"
};

// A generalised force (actuator torque or force) on a joint coordinate.
struct JointLoad {
  int joint = -1;
  int coordinate = 0;
  double value = 0.0;
};

// Index from ids to positions in one of Model's vectors. Kept by Model::add_node / add_member /
// add_joint / add_material / add_section; a lookup falls back to a linear scan when the vector was
// filled directly (tests build models with push_back), so it is never wrong, only faster when kept.
// The first of two equal ids wins, as a scan would find it.
// An open-addressing hash table of positions (linear probing, at most half full): the ids stay in
// the items, so recording one allocates nothing, and clear() keeps the table (a model read again
// into the same Model, case after case of a sweep, reuses it).
class IdIndex {
 public:
  // Records position `i` of `items` under items[i].id; returns false (and keeps the first) when
  // that id is already there.
  template <class V>
  bool add(const V& items, int i) {
    if (2 * (size_ + 1) > slots_.size()) grow(items);
    for (std::size_t s = slot_of(items[i].id);; s = (s + 1) & (slots_.size() - 1)) {
      if (slots_[s] < 0) {
        slots_[s] = i;
        ++size_;
        return true;
      }
      if (items[slots_[s]].id == items[i].id) return false;
    }
  }
  // The position of `id` in `items`, or -1 (the index is used when in step with `items`).
  template <class V>
  int find(const V& items, std::string_view id) const {
    if (size_ == items.size()) {
      if (size_ == 0) return -1;
      for (std::size_t s = slot_of(id);; s = (s + 1) & (slots_.size() - 1)) {
        if (slots_[s] < 0) return -1;
        if (items[slots_[s]].id == id) return slots_[s];
      }
    }
    for (std::size_t i = 0; i < items.size(); ++i)
      if (items[i].id == id) return static_cast<int>(i);
    return -1;
  }
  // Empties the index; its table keeps its size.
  void clear() {
    std::fill(slots_.begin(), slots_.end(), -1);
    size_ = 0;
  }
  // Room for n ids without growing (an empty index only: growing needs the items).
  void reserve(std::size_t n) {
    if (size_ == 0 && 2 * n > slots_.size()) slots_.assign(table_size(n), -1);
  }
  std::size_t size() const { return size_; }

 private:
  static constexpr std::size_t kMinTable = 16;  // slots of a first table (a power of two)
  // A power of two holding n ids at most half full.
  static std::size_t table_size(std::size_t n) {
    std::size_t t = kMinTable;
    while (t < 2 * n) t *= 2;
    return t;
  }
  std::size_t slot_of(std::string_view id) const { return std::hash<std::string_view>{}(id) & (slots_.size() - 1); }
  template <class V>
  void grow(const V& items) {
    std::vector<int> old = std::move(slots_);
    slots_.assign(std::max(kMinTable, 2 * old.size()), -1);
    for (const int k : old) {
      if (k < 0) continue;
      std::size_t s = slot_of(items[k].id);
      while (slots_[s] >= 0) s = (s + 1) & (slots_.size() - 1);
      slots_[s] = k;
    }
  }

  std::vector<int> slots_;  // -1: empty; else a position in the items
  std::size_t size_ = 0;    // positions recorded
};

// A load between the end nodes of a beam member, following the member over its segments.
// Positions are fractions of the member's length from its first node. Components are global, or
// in the member's local axes when `local` (docs/conventions.md); in nonlinear analyses both keep
// the direction they have in the reference configuration (dead loads).
struct MemberLoad {
  enum class Kind { Distributed, Point, Temperature };
  int member = -1;
  Kind kind = Kind::Distributed;
  bool local = false;
  // Distributed: force per unit length, varying linearly from q_from at `from` to q_to at `to`.
  Vec3 q_from = Vec3::Zero(), q_to = Vec3::Zero();
  double from = 0.0, to = 1.0;
  // Point: a force and a moment at `at`.
  Vec3 force = Vec3::Zero(), moment = Vec3::Zero();
  double at = 0.5;
  // Temperature: a change over the whole member, Delta T(y, z) = uniform + gradient_y y +
  // gradient_z z in its local axes (the section's centroid at y = z = 0); the strain it causes is
  // the material's alpha times it.
  double uniform = 0.0, gradient_y = 0.0, gradient_z = 0.0;
};

// What one load case applies: nodal, joint and member loads, and gravity (acceleration) acting on
// the beams' mass (density x A per unit length) and on the point masses.
struct LoadSet {
  std::vector<NodalLoad> nodal;
  std::vector<JointLoad> joint;
  std::vector<MemberLoad> member;
  Vec3 gravity = Vec3::Zero();
  // Every load multiplied by `factor`, appended to this set.
  void add_scaled(const LoadSet& other, double factor);
};

// The id of an analysis's "load_case" that selects the top-level loads and gravity.
inline constexpr const char* kDefaultLoadCase = "default";

struct LoadCase {
  std::string id;
  LoadSet loads;
};

// A factored sum of load cases.
struct Combination {
  std::string id;
  std::vector<std::pair<int, double>> factors;  // (index into Model::load_cases, factor)
  // The sum itself, made once when the combination is added (Model::add_combination).
  LoadSet loads;
};

// A pose (solvers/pose.hpp): joint coordinates measured from the reference geometry, and node
// targets (a position, and optionally a rotation relative to the reference) that free the
// actuator coordinates. After the model is posed, `solved` holds every joint's coordinates and
// the model's geometry is the posed one.
struct PoseTarget {
  int node = -1;
  Vec3 xyz = Vec3::Zero();
  bool has_rotation = false;
  Mat3 rotation = Mat3::Identity();
};
struct Pose {
  bool given = false;                                   // the model has a "pose"
  std::vector<std::pair<int, Eigen::VectorXd>> joints;  // (joint index, its coordinates)
  std::vector<PoseTarget> nodes;
  std::vector<Eigen::VectorXd> solved;                  // per joint, after posing
};

struct Model {
  std::vector<Node> nodes;
  std::vector<Material> materials;
  std::vector<Section> sections;
  std::vector<Member> members;
  std::vector<Element> elements;
  std::vector<Joint> joints;
  std::vector<Support> supports;
  std::vector<Prescribed> prescribed;
  std::vector<Tie> ties;
  std::vector<LinearConstraint> constraints;
  std::vector<PointMass> masses;
  Damping damping;
  SolverChoice solver;
  // The default load case: the top-level loads and gravity. Named cases and combinations are
  // selected by an analysis's "load_case" (loads_for).
  LoadSet default_case;
  std::vector<LoadCase> load_cases;
  std::vector<Combination> combinations;
  // The pose the geometry was moved to (Pose::given false: the reference geometry as read).
  Pose pose;

  // Appending with an index kept (ids must be unique: the caller checks; a repeated id is not
  // indexed and a later lookup finds the first). Each returns the new position.
  int add_node(Node n);
  int add_member(Member m);
  int add_joint(Joint j);
  int add_material(Material m);
  int add_section(Section s);

  int find_node(const std::string& id) const;    // -1 if absent
  int find_member(const std::string& id) const;  // -1 if absent
  int find_joint(const std::string& id) const;   // -1 if absent
  int find_material(const std::string& id) const;  // -1 if absent
  int find_section(const std::string& id) const;   // -1 if absent
  int find_load_case(const std::string& id) const;    // -1 if absent
  int find_combination(const std::string& id) const;  // -1 if absent
  // Appends a combination of the load cases already added, with its sum (Combination::loads).
  void add_combination(Combination c);
  // The default load case (top-level loads and gravity).
  const LoadSet& default_loads() const { return default_case; }
  // The loads an analysis's "load_case" selects: a named case, a combination (its cases' loads,
  // factored), or the default case for "" and "default" (kDefaultLoadCase) unless a case or a
  // combination has that id. find_loads returns null when `id` selects nothing; loads_for throws
  // ModelError naming the id and the known ones.
  const LoadSet* find_loads(const std::string& id) const;
  const LoadSet& loads_for(const std::string& id) const;
  // The ids loads_for accepts, as "default, dead, tool, uls" (a message's list).
  std::string known_load_cases() const;
  // Replaces the default load case by `loads`.
  void set_default_loads(const LoadSet& loads) { default_case = loads; }
  // "node 'A' dof uz", "joint 'j1' coordinate 0"
  std::string describe(const DofRef& d) const;
  // Length scale of the model (bounding-box diagonal, at least 1e-300); used to make
  // rotations and translations commensurable in rank decisions.
  double length_scale() const;

  // Empties the model (as a default Model), keeping the storage of its vectors and id indexes
  // (a model read again into the same Model: io/model_reader.hpp's ModelBuffer). A vector added
  // to Model is cleared here too.
  void clear();

  // Id indexes of nodes, members, joints, materials and sections (see IdIndex).
  IdIndex node_index;
  IdIndex member_index;
  IdIndex joint_index;
  IdIndex material_index;
  IdIndex section_index;
};

// The position at the reference of a beam element's end `end` (0, 1) where its flexible part
// begins or ends: its node, moved by the element's rigid arm (Element::offsets).
inline Vec3 flexible_end(const Model& m, const Element& el, int end) { return m.nodes[el.nodes[end]].x + el.offsets[end]; }

// Building a model again out of an old one's storage (io/model_reader.hpp's ModelBuffer: a sweep
// worker reads a model per case): recycled(spare, i) is a default item (every field as a fresh one)
// that holds the storage of (*spare)[i]'s strings and vectors, emptied, when there is such an item,
// so that a model of the same shape is built without allocating. `spare` may be null (a fresh
// model). A string or vector field added to an item may join its adopt_storage; one left out is
// only allocated afresh, never stale.
inline void adopt_storage(Node& to, Node& from) { to.id.swap(from.id), to.id.clear(); }
inline void adopt_storage(Material& to, Material& from) { to.id.swap(from.id), to.id.clear(); }
inline void adopt_storage(Section& to, Section& from) { to.id.swap(from.id), to.id.clear(); }
inline void adopt_storage(Element& to, Element& from) { to.id.swap(from.id), to.id.clear(); }
inline void adopt_storage(Member& to, Member& from) {
  to.id.swap(from.id), to.id.clear();
  to.elements.swap(from.elements), to.elements.clear();
}
inline void adopt_storage(Joint& to, Joint& from) {
  to.id.swap(from.id), to.id.clear();
  to.axes.swap(from.axes), to.axes.clear();
  to.stiffness.swap(from.stiffness), to.stiffness.clear();
  to.limits.swap(from.limits), to.limits.clear();
  to.damping.swap(from.damping), to.damping.clear();
}
template <class T>
T recycled(std::vector<T>* spare, std::size_t i) {
  T t;
  if (spare && i < spare->size()) adopt_storage(t, (*spare)[i]);
  return t;
}

}  // namespace beamfea
