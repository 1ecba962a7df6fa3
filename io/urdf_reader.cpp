#include "io/urdf_reader.hpp"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/errors.hpp"
#include "core/rotation.hpp"
#include "io/json_util.hpp"
#include "io/model_reader.hpp"

namespace beamfea {

// The import's helpers, in a named namespace: io is compiled in unity batches (CMake's
// UNITY_BUILD), where anonymous namespaces of the batch's files would meet.
namespace urdf_import {

using json = nlohmann::json;
using ojson = nlohmann::ordered_json;

// Relative distance (times the robot's size) below which two points of the description coincide:
// a joint then joins the link frame node itself, a centre of mass sits on it. Well below the joint
// reader's tolerance for coincident nodes (1e-9), above the round-off of composing a few transforms.
constexpr double kSamePoint = 1e-12;

// A rigid-body frame in global axes: position and rotation (columns: the frame's axes).
struct Frame {
  Vec3 x = Vec3::Zero();
  Mat3 R = Mat3::Identity();
  Vec3 point(const Vec3& local) const { return x + R * local; }
};

Vec3 vec(const urdf::Vector3& v) { return {v.x, v.y, v.z}; }

// URDF's rotation: the quaternion urdfdom made from rpy, R = Rz(yaw) Ry(pitch) Rx(roll).
Mat3 rotation(const urdf::Rotation& r) { return Eigen::Quaterniond(r.w, r.x, r.y, r.z).normalized().toRotationMatrix(); }

ojson xyz(const Vec3& v) { return ojson::array({v.x(), v.y(), v.z()}); }

ojson matrix(const Mat3& M) {
  ojson rows = ojson::array();
  for (int r = 0; r < 3; ++r) rows.push_back(ojson::array({M(r, 0), M(r, 1), M(r, 2)}));
  return rows;
}

// The parser's own messages (console_bridge), kept for the error it ends in: urdfdom reports what
// is wrong (a joint's missing parent link, a malformed attribute) only through its log. The log
// handler is process-wide: the import is not meant to run on several threads at once.
class CapturedLog : public console_bridge::OutputHandler {
 public:
  CapturedLog() { console_bridge::useOutputHandler(this); }
  ~CapturedLog() override { console_bridge::restorePreviousOutputHandler(); }
  CapturedLog(const CapturedLog&) = delete;
  CapturedLog& operator=(const CapturedLog&) = delete;
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) errors_.push_back(text);
  }
  std::string errors() const {
    std::string s;
    for (const auto& e : errors_) s += (s.empty() ? "" : "; ") + e;
    return s.empty() ? "not a valid URDF robot description" : s;
  }

 private:
  std::vector<std::string> errors_;
};

// A flexible link of the side-car: a beam between two points of the link frame.
struct LinkBeam {
  std::string material, section;
  Vec3 from = Vec3::Zero(), to = Vec3::Zero();
  int divisions = 1;
  std::optional<Vec3> orientation;  // in the link frame
};

// What the side-car gives, checked against the robot description.
struct Sidecar {
  std::map<std::string, double> stiffness;  // per movable joint
  std::map<std::string, LinkBeam> beams;    // per link
  ojson materials = ojson::array(), sections = ojson::array();
  bool inertials = true;
};

[[noreturn]] void unknown_name(const std::string& pointer, const std::string& what, const std::string& name,
                               const std::vector<std::string>& known, const std::string& source) {
  std::string message = source + ": unknown " + what + " '" + name + "'";
  const std::string near = json_in::nearest_key(name, known);
  if (!near.empty()) message += " (did you mean '" + near + "'?)";
  else if (known.empty()) message += " (there are none)";
  throw InputError(pointer, message);
}

Sidecar read_sidecar(const json& doc, const std::string& source, const urdf::ModelInterface& robot) {
  using namespace json_in;
  Sidecar s;
  const std::string what = "side-car " + source;
  const Pointer root;
  const json& top = object(doc, root, what);
  const Fields f(top, root, {"joints", "links", "materials", "sections", "inertials"});
  std::vector<std::string> movable, links;
  for (const auto& [name, j] : robot.joints_)
    if (j->type == urdf::Joint::REVOLUTE || j->type == urdf::Joint::CONTINUOUS || j->type == urdf::Joint::PRISMATIC)
      movable.push_back(name);
  for (const auto& [name, l] : robot.links_) links.push_back(name);
  if (const json* joints = f.get("joints")) {
    object(*joints, Pointer("/joints"), what + " joints");
    for (const auto& [name, value] : joints->items()) {
      const std::string p = "/joints/" + name;
      if (robot.joints_.count(name) && !std::count(movable.begin(), movable.end(), name))
        throw InputError(p, what + ": joint '" + name + "' is not revolute, continuous or prismatic: it has no coordinate to give a stiffness");
      if (!std::count(movable.begin(), movable.end(), name)) unknown_name(p, "joint", name, movable, what);
      const Pointer jp(p);
      const Fields fj(object(value, jp, what + " joint"), jp, {"stiffness"});
      const auto k = numbers(fj.require("stiffness", what + " joint '" + name + "'"), child(jp, "stiffness"),
                             What(what, " joint stiffness"));
      if (k.size() != 1) throw InputError(p + "/stiffness", what + ": joint '" + name + "' has one coordinate: give one stiffness");
      if (k[0] < 0.0) throw InputError(p + "/stiffness/0", what + ": joint '" + name + "': stiffness must not be negative");
      s.stiffness[name] = k[0];
    }
  }
  if (const json* l = f.get("links")) {
    object(*l, Pointer("/links"), what + " links");
    for (const auto& [name, value] : l->items()) {
      const std::string p = "/links/" + name;
      if (!robot.links_.count(name)) unknown_name(p, "link", name, links, what);
      const Pointer lp(p);
      const Fields fl(object(value, lp, what + " link"), lp, {"beam"});
      const std::string bps = p + "/beam";
      const Pointer bp(bps);
      const std::string bw = what + " link '" + name + "' beam";
      const Fields fb(object(fl.require("beam", what + " link '" + name + "'"), bp, bw), bp,
                      {"material", "section", "from", "to", "divisions", "orientation"});
      LinkBeam b;
      b.material = id(fb.require("material", bw), child(bp, "material"), What(bw, " material"));
      b.section = id(fb.require("section", bw), child(bp, "section"), What(bw, " section"));
      b.from = vec3(fb.require("from", bw), child(bp, "from"), What(bw, " from"));
      b.to = vec3(fb.require("to", bw), child(bp, "to"), What(bw, " to"));
      if ((b.to - b.from).norm() == 0.0) throw InputError(bps + "/to", bw + ": \"to\" equals \"from\"");
      if (const json* d = fb.get("divisions")) b.divisions = integer_at_least(*d, child(bp, "divisions"), What(bw, " divisions"), 1);
      if (const json* o = fb.get("orientation")) b.orientation = vec3(*o, child(bp, "orientation"), What(bw, " orientation"));
      s.beams[name] = b;
    }
  }
  // Materials and sections are the model's own entries (checked by the model reader); the beams'
  // references to them are checked here, where the side-car can be named.
  auto ids_of = [&](const char* key, ojson& into) {
    std::vector<std::string> ids;
    if (const json* v = f.get(key)) {
      const std::string p = std::string("/") + key;
      array(*v, Pointer(p), What(what, " ", key));
      for (std::size_t i = 0; i < v->size(); ++i) {
        const std::string ip = p + "/" + std::to_string(i), idp = ip + "/id";
        const json& item = object((*v)[i], Pointer(ip), What(what, " ", key));
        ids.push_back(id(json_in::require(item, Pointer(ip), "id", What(what, " ", key)), Pointer(idp), What(what, " id")));
      }
      into = ojson::parse(v->dump());
    }
    return ids;
  };
  const auto materials = ids_of("materials", s.materials);
  const auto sections = ids_of("sections", s.sections);
  for (const auto& [name, b] : s.beams) {
    if (!std::count(materials.begin(), materials.end(), b.material))
      unknown_name("/links/" + name + "/beam/material", "material", b.material, materials, what);
    if (!std::count(sections.begin(), sections.end(), b.section))
      unknown_name("/links/" + name + "/beam/section", "section", b.section, sections, what);
  }
  if (const json* v = f.get("inertials")) s.inertials = boolean(*v, Pointer("/inertials"), What(what, " inertials"));
  return s;
}

// Builds the document link by link from the root, depth first.
class Builder {
 public:
  Builder(const urdf::ModelInterface& robot, const Sidecar& sidecar, const std::string& source)
      : robot_(robot), sidecar_(sidecar), source_(source) {}

  ojson build() {
    const auto root = robot_.getRoot();
    if (!root) throw InputError("", source_ + ": the robot has no root link");
    scale_ = size_of(*root, 0.0);
    add_link(*root, Frame{});
    supports_.push_back({{"node", root->name}, {"fix", "all"}});
    ojson doc;
    doc["nodes"] = std::move(nodes_);
    if (!sidecar_.materials.empty()) doc["materials"] = sidecar_.materials;
    if (!sidecar_.sections.empty()) doc["sections"] = sidecar_.sections;
    if (!elements_.empty()) doc["elements"] = std::move(elements_);
    if (!joints_.empty()) doc["joints"] = std::move(joints_);
    if (!ties_.empty()) doc["ties"] = std::move(ties_);
    doc["supports"] = std::move(supports_);
    if (!masses_.empty()) doc["masses"] = std::move(masses_);
    return doc;
  }

 private:
  // An upper bound of the robot's size (the sum of its offsets): the scale of kSamePoint.
  double size_of(const urdf::Link& link, double sum) const {
    if (link.inertial) sum += vec(link.inertial->origin.position).norm();
    if (const auto b = sidecar_.beams.find(link.name); b != sidecar_.beams.end()) sum += b->second.from.norm() + b->second.to.norm();
    for (const auto& j : link.child_joints) {
      const auto child = robot_.getLink(j->child_link_name);
      sum = size_of(*child, sum + vec(j->parent_to_joint_origin_transform.position).norm());
    }
    return sum;
  }

  bool same(const Vec3& a, const Vec3& b) const { return (a - b).norm() <= kSamePoint * std::max(scale_, 1.0); }

  void add_node(const std::string& id, const Vec3& x) {
    nodes_.push_back({{"id", id}, {"xyz", xyz(x)}});
    position_[id] = x;
  }

  // Welds node b to node a: a rigid link, or a tie of all six DOFs where they coincide.
  void weld(const std::string& a, const std::string& b, const std::string& id) {
    if (same(position_.at(a), position_.at(b)))
      ties_.push_back({{"nodes", {a, b}}, {"dofs", {"ux", "uy", "uz", "rx", "ry", "rz"}}});
    else
      elements_.push_back({{"id", id}, {"type", "rigid"}, {"nodes", {a, b}}});
  }

  // The node at point x of a link whose body node is `body`: the body node itself where they
  // coincide, else a new node `id` rigidly attached to it.
  std::string attached(const std::string& body, const std::string& id, const Vec3& x) {
    if (same(position_.at(body), x)) return body;
    add_node(id, x);
    weld(body, id, id);
    return id;
  }

  // The link's frame node (unless `with_node` is false: added already), its body and its subtree.
  void add_link(const urdf::Link& link, const Frame& F, bool with_node = true) {
    const std::string& L = link.name;
    if (with_node) add_node(L, F.x);
    // The node the link's children hang from: the link frame, or the end of its flexible beam.
    std::string carrier = L;
    if (const auto b = sidecar_.beams.find(L); b != sidecar_.beams.end()) {
      const LinkBeam& beam = b->second;
      const std::string from = attached(L, L + "@from", F.point(beam.from));
      add_node(L + "@to", F.point(beam.to));
      ojson e = {{"id", L}, {"type", "beam"}, {"nodes", {from, L + "@to"}}, {"material", beam.material}, {"section", beam.section}};
      if (beam.orientation) e["orientation"] = xyz(F.R * *beam.orientation);
      if (beam.divisions > 1) e["divisions"] = beam.divisions;
      elements_.push_back(std::move(e));
      carrier = L + "@to";
    }
    if (sidecar_.inertials && link.inertial && link.inertial->mass > 0.0) {
      const urdf::Inertial& in = *link.inertial;
      const std::string com = attached(L, L + "@com", F.point(vec(in.origin.position)));
      Mat3 I;
      I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
      const Mat3 Rc = F.R * rotation(in.origin.rotation);  // the inertial frame in global axes
      ojson m = {{"node", com}, {"mass", in.mass}};
      if (!I.isZero(0.0)) m["inertia"] = matrix(Rc * I * Rc.transpose());
      masses_.push_back(std::move(m));
    }
    for (const auto& j : link.child_joints) {
      const urdf::Joint& joint = *j;
      const Frame J{F.point(vec(joint.parent_to_joint_origin_transform.position)),
                    F.R * rotation(joint.parent_to_joint_origin_transform.rotation)};
      const auto child = robot_.getLink(joint.child_link_name);
      const std::string& C = child->name;
      switch (joint.type) {
        case urdf::Joint::FIXED:
          add_node(C, J.x);  // the child's frame node first: the weld needs its position
          weld(carrier, C, L + "@" + joint.name);
          add_link(*child, J, false);
          break;
        case urdf::Joint::REVOLUTE:
        case urdf::Joint::CONTINUOUS:
        case urdf::Joint::PRISMATIC: {
          add_joint(joint, attached(carrier, L + "@" + joint.name, J.x), C, J);
          add_link(*child, J);
          break;
        }
        default:
          throw InputError("", source_ + ": joint '" + joint.name + "' attribute type: " +
                                   (joint.type == urdf::Joint::FLOATING ? "floating" : joint.type == urdf::Joint::PLANAR ? "planar" : "unknown") +
                                   " joints are not supported (revolute, continuous, prismatic, fixed)");
      }
    }
  }

  void add_joint(const urdf::Joint& joint, const std::string& a, const std::string& b, const Frame& J) {
    const Vec3 axis = vec(joint.axis);
    if (axis.norm() == 0.0) throw InputError("", source_ + ": joint '" + joint.name + "' element axis attribute xyz: the axis is zero");
    const bool prismatic = joint.type == urdf::Joint::PRISMATIC;
    ojson o = {{"id", joint.name}, {"type", prismatic ? "prismatic" : "revolute"}, {"nodes", {a, b}},
               {"axes", ojson::array({xyz(J.R * axis.normalized())})}};
    if (const auto k = sidecar_.stiffness.find(joint.name); k != sidecar_.stiffness.end()) o["stiffness"] = {k->second};
    // A continuous joint has no limits; a revolute or prismatic one's bound its coordinate (poses).
    if (joint.type != urdf::Joint::CONTINUOUS && joint.limits)
      o["limits"] = ojson::array({ojson::array({joint.limits->lower, joint.limits->upper})});
    joints_.push_back(std::move(o));
  }

  const urdf::ModelInterface& robot_;
  const Sidecar& sidecar_;
  const std::string& source_;
  double scale_ = 0.0;
  std::map<std::string, Vec3> position_;
  ojson nodes_ = ojson::array(), elements_ = ojson::array(), joints_ = ojson::array(), ties_ = ojson::array(),
        supports_ = ojson::array(), masses_ = ojson::array();
};

// Node ids made here ("<link>@<joint>", "<link>@com", "<link>@from", "<link>@to") must not be a
// link's name: the '@' is refused in link and joint names.
void check_names(const urdf::ModelInterface& robot, const std::string& source) {
  for (const auto& [name, l] : robot.links_)
    if (name.find('@') != std::string::npos)
      throw InputError("", source + ": link '" + name + "' attribute name: '@' is reserved for the nodes the import adds");
  for (const auto& [name, j] : robot.joints_)
    if (name.find('@') != std::string::npos)
      throw InputError("", source + ": joint '" + name + "' attribute name: '@' is reserved for the nodes the import adds");
}

std::string read_text(const std::string& path, const char* what) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError("", std::string("cannot read ") + what + " '" + path + "': no such file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("", std::string("cannot open ") + what + " '" + path + "'");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace urdf_import

nlohmann::ordered_json urdf_to_model(const std::string& urdf, const std::string& source, const std::optional<nlohmann::json>& sidecar,
                    const std::string& sidecar_source) {
  using namespace urdf_import;
  urdf::ModelInterfaceSharedPtr robot;
  {
    CapturedLog log;
    robot = urdf::parseURDF(urdf);
    if (!robot) throw InputError("", "URDF " + source + ": " + log.errors());
  }
  const std::string what = "URDF " + source;
  check_names(*robot, what);
  Sidecar s;
  if (sidecar) {
    try {
      s = read_sidecar(*sidecar, sidecar_source, *robot);
    } catch (const InputError& e) {
      // The key policy's messages ("unknown key ...") do not know which file they are about.
      std::string message = e.what();
      if (message.find("side-car") != std::string::npos) throw;
      if (message.rfind(e.pointer() + ": ", 0) == 0) message.erase(0, e.pointer().size() + 2);
      throw InputError(e.pointer(), "side-car " + sidecar_source + ": " + message);
    }
  }
  return Builder(*robot, s, what).build();
}

nlohmann::ordered_json urdf_file_to_model(const std::string& urdf_path, const std::optional<nlohmann::json>& sidecar,
                                          const std::string& sidecar_source) {
  return urdf_to_model(urdf_import::read_text(urdf_path, "URDF file"), "'" + urdf_path + "'", sidecar, sidecar_source);
}

}  // namespace beamfea
