#include "core/model.hpp"

#include <algorithm>

#include "core/errors.hpp"

namespace beamfea {

int dof_index(const std::string& name) {
  for (int i = 0; i < 6; ++i)
    if (name == kDofNames[i]) return i;
  return -1;
}

const char* joint_type_name(JointType t) {
  switch (t) {
    case JointType::Revolute: return "revolute";
    case JointType::Universal: return "universal";
    case JointType::Spherical: return "spherical";
    case JointType::VirtualSpring: return "virtual_spring";
    case JointType::Prismatic: return "prismatic";
  }
  return "?";
}

int joint_coordinate_count(JointType t) {
  switch (t) {
    case JointType::Revolute: return 1;
    case JointType::Universal: return 2;
    case JointType::Spherical: return 3;
    case JointType::VirtualSpring: return 6;
    case JointType::Prismatic: return 1;
  }
  return 0;
}

Eigen::MatrixXd Joint::stiffness_as_matrix() const {
  if (stiffness_matrix.size() > 0) return stiffness_matrix;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(coordinates(), coordinates());
  for (int i = 0; i < coordinates() && i < static_cast<int>(stiffness.size()); ++i) K(i, i) = stiffness[i];
  return K;
}

bool Joint::has_stiffness() const {
  if (stiffness_matrix.size() > 0) return stiffness_matrix.cwiseAbs().maxCoeff() > 0.0;
  for (double k : stiffness)
    if (k != 0.0) return true;
  return false;
}

namespace {

template <class V, class T>
int add_indexed(V& items, IdIndex& index, T item) {
  const int i = static_cast<int>(items.size());
  // An index out of step (items pushed directly) is rebuilt first, so that it stays usable.
  if (index.size() != items.size()) {
    index.clear();
    for (std::size_t k = 0; k < items.size(); ++k) index.add(items, static_cast<int>(k));
  }
  items.push_back(std::move(item));
  index.add(items, i);
  return i;
}

}  // namespace

int Model::add_node(Node n) { return add_indexed(nodes, node_index, std::move(n)); }
int Model::add_member(Member m) { return add_indexed(members, member_index, std::move(m)); }
int Model::add_joint(Joint j) { return add_indexed(joints, joint_index, std::move(j)); }
int Model::add_material(Material m) { return add_indexed(materials, material_index, std::move(m)); }
int Model::add_section(Section s) { return add_indexed(sections, section_index, std::move(s)); }

int Model::find_node(const std::string& id) const { return node_index.find(nodes, id); }
int Model::find_member(const std::string& id) const { return member_index.find(members, id); }
int Model::find_joint(const std::string& id) const { return joint_index.find(joints, id); }
int Model::find_material(const std::string& id) const { return material_index.find(materials, id); }
int Model::find_section(const std::string& id) const { return section_index.find(sections, id); }
// Few cases and combinations: a scan.
template <class V>
static int scan_for_id(const V& v, const std::string& id) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (v[i].id == id) return static_cast<int>(i);
  return -1;
}

int Model::find_load_case(const std::string& id) const { return scan_for_id(load_cases, id); }
int Model::find_combination(const std::string& id) const { return scan_for_id(combinations, id); }

void LoadSet::add_scaled(const LoadSet& o, double k) {
  for (NodalLoad l : o.nodal) {
    l.force *= k;
    l.moment *= k;
    nodal.push_back(l);
  }
  for (JointLoad l : o.joint) {
    l.value *= k;
    joint.push_back(l);
  }
  for (MemberLoad l : o.member) {
    l.q_from *= k;
    l.q_to *= k;
    l.force *= k;
    l.moment *= k;
    l.uniform *= k;
    l.gradient_y *= k;
    l.gradient_z *= k;
    member.push_back(l);
  }
  gravity += k * o.gravity;
}

void Model::add_combination(Combination c) {
  c.loads = LoadSet{};
  for (const auto& [k, f] : c.factors) c.loads.add_scaled(load_cases.at(k).loads, f);
  combinations.push_back(std::move(c));
}

const LoadSet* Model::find_loads(const std::string& id) const {
  if (const int c = find_load_case(id); c >= 0) return &load_cases[c].loads;
  if (const int k = find_combination(id); k >= 0) return &combinations[k].loads;
  if (id.empty() || id == kDefaultLoadCase) return &default_case;
  return nullptr;
}

const LoadSet& Model::loads_for(const std::string& id) const {
  if (const LoadSet* s = find_loads(id)) return *s;
  throw ModelError("load case '" + id + "'", "is neither a load case nor a combination (known: " + known_load_cases() + ")");
}

std::string Model::known_load_cases() const {
  std::string s = kDefaultLoadCase;
  for (const auto& c : load_cases) s += ", " + c.id;
  for (const auto& c : combinations) s += ", " + c.id;
  return s;
}

void Model::clear() {
  nodes.clear();
  materials.clear();
  sections.clear();
  members.clear();
  elements.clear();
  joints.clear();
  supports.clear();
  prescribed.clear();
  ties.clear();
  constraints.clear();
  masses.clear();
  damping = Damping{};
  solver = SolverChoice{};
  default_case.nodal.clear();
  default_case.joint.clear();
  default_case.member.clear();
  default_case.gravity = Vec3::Zero();
  load_cases.clear();
  combinations.clear();
  pose = Pose{};
  node_index.clear();
  member_index.clear();
  joint_index.clear();
  material_index.clear();
  section_index.clear();
}

std::string Model::describe(const DofRef& d) const {
  if (d.owner == DofRef::Owner::Node)
    return "node '" + nodes.at(d.index).id + "' dof " + kDofNames.at(d.comp);
  return "joint '" + joints.at(d.index).id + "' coordinate " + std::to_string(d.comp);
}

double Model::length_scale() const {
  if (nodes.empty()) return 1.0;
  Vec3 lo = nodes[0].x, hi = nodes[0].x;
  for (const auto& n : nodes) {
    lo = lo.cwiseMin(n.x);
    hi = hi.cwiseMax(n.x);
  }
  const double d = (hi - lo).norm();
  return d > 0.0 ? d : 1.0;
}

}  // namespace beamfea
