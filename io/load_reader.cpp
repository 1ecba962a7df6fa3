#include "io/load_reader.hpp"

#include <Eigen/Eigenvalues>
#include <map>

#include "core/errors.hpp"
#include "io/json_util.hpp"
#include "io/model_reader.hpp"

namespace beamfea {

using json = nlohmann::json;
using namespace json_in;

namespace {

// Relative tolerances of an inertia matrix's symmetry and positive semi-definiteness (round-off
// of user-typed numbers, relative to its largest entry).
constexpr double kInertiaSymmetry = 1e-9;
constexpr double kInertiaPsd = 1e-9;

double fraction(const json& o, const json_in::Pointer& p, const char* key, double fallback, const std::string& what) {
  if (!o.contains(key)) return fallback;
  const double v = number(o[key], child(p, key), What(what, " ", key));
  if (!(v >= 0.0 && v <= 1.0))
    throw InputError(child(p, key), what + ": '" + key + "' must lie in [0, 1] (a fraction of the member's length)");
  return v;
}

MemberLoad read_member_load(const Model& m, const json& o, const json_in::Pointer& p) {
  MemberLoad l;
  const std::string id = json_in::id(o["element"], child(p, "element"), "load element");
  l.member = m.find_member(id);
  if (l.member < 0) throw InputError(child(p, "element"), "load on unknown element '" + id + "'");
  const std::string what = "load on element '" + id + "'";
  if (m.members[l.member].type != MemberType::Beam)
    throw InputError(child(p, "element"), what + ": a rigid link carries no member loads; load its nodes");
  if (o.contains("axes")) {
    const std::string axes = string(o["axes"], child(p, "axes"), What(what, " axes"));
    if (axes == "local") l.local = true;
    else if (axes != "global") throw InputError(child(p, "axes"), what + ": axes must be \"local\" or \"global\"");
  }
  if (o.contains("temperature")) {
    l.kind = MemberLoad::Kind::Temperature;
    expect_keys(o, p, {"element", "temperature"});
    const json_in::Pointer tp = child(p, "temperature");
    const json& t = o["temperature"];
    if (!t.is_object()) throw InputError(tp, what + ": temperature must be an object {\"uniform\", \"gradient_y\", \"gradient_z\"}");
    expect_keys(t, tp, {"uniform", "gradient_y", "gradient_z"});
    if (t.empty()) throw InputError(tp, what + ": temperature needs 'uniform', 'gradient_y' or 'gradient_z'");
    if (t.contains("uniform")) l.uniform = number(t["uniform"], child(tp, "uniform"), What(what, " temperature uniform"));
    if (t.contains("gradient_y")) l.gradient_y = number(t["gradient_y"], child(tp, "gradient_y"), What(what, " temperature gradient_y"));
    if (t.contains("gradient_z")) l.gradient_z = number(t["gradient_z"], child(tp, "gradient_z"), What(what, " temperature gradient_z"));
    const Material& mat = m.materials[m.members[l.member].material];
    if (!(mat.alpha != 0.0))
      throw InputError(tp, what + ": material '" + mat.id + "' has no thermal expansion 'alpha' (/materials, field alpha)");
    return l;
  }
  const bool dist = o.contains("distributed");
  const bool point = o.contains("point") || o.contains("moment");
  if (dist == point)
    throw InputError(p, what + ": give either 'distributed' (force per unit length), 'point'/'moment' with 'at', or 'temperature'");
  if (dist) {
    l.kind = MemberLoad::Kind::Distributed;
    l.q_from = vec3(o["distributed"], child(p, "distributed"), What(what, " distributed"));
    l.q_to = o.contains("distributed_end") ? vec3(o["distributed_end"], child(p, "distributed_end"), What(what, " distributed_end"))
                                           : l.q_from;
    l.from = fraction(o, p, "from", 0.0, what);
    l.to = fraction(o, p, "to", 1.0, what);
    if (!(l.from < l.to))
      throw InputError(child(p, o.contains("to") ? "to" : "from"),
                       what + ": 'from' must be below 'to' (got from " + std::to_string(l.from) + ", to " +
                           std::to_string(l.to) + ")");
    expect_keys(o, p, {"element", "distributed", "distributed_end", "from", "to", "axes"});
  } else {
    l.kind = MemberLoad::Kind::Point;
    if (o.contains("point")) l.force = vec3(o["point"], child(p, "point"), What(what, " point"));
    if (o.contains("moment")) l.moment = vec3(o["moment"], child(p, "moment"), What(what, " moment"));
    if (!o.contains("at")) throw InputError(child(p, "at"), what + ": missing 'at' (fraction of the member's length)");
    l.at = fraction(o, p, "at", 0.5, what);
    expect_keys(o, p, {"element", "point", "moment", "at", "axes"});
  }
  return l;
}

Vec3 read_gravity(const json& v, const json_in::Pointer& p) { return vec3(v, p, "gravity"); }

PointMass read_mass(const Model& m, const json& o, const json_in::Pointer& p) {
  PointMass pm;
  pm.node = node_ref(m, require(o, p, "node", "mass"), child(p, "node"));
  const std::string what = "mass at node '" + m.nodes[pm.node].id + "'";
  pm.mass = number(require(o, p, "mass", what), child(p, "mass"), what);
  if (!(pm.mass >= 0.0)) throw InputError(child(p, "mass"), what + ": mass must not be negative");
  if (o.contains("inertia")) {
    const json_in::Pointer ip = child(p, "inertia");
    const auto& rows = array(o["inertia"], ip, What(what, " inertia"));
    if (rows.size() != 3) throw InputError(ip, what + ": inertia must be a 3x3 matrix");
    for (int r = 0; r < 3; ++r) {
      const auto v = numbers(rows[r], child(ip, r), What(what, " inertia"));
      if (v.size() != 3) throw InputError(child(ip, r), what + ": inertia must be a 3x3 matrix");
      for (int c = 0; c < 3; ++c) pm.inertia(r, c) = v[c];
    }
    const double scale = pm.inertia.cwiseAbs().maxCoeff();
    if ((pm.inertia - pm.inertia.transpose()).cwiseAbs().maxCoeff() > kInertiaSymmetry * scale)
      throw InputError(ip, what + ": inertia must be symmetric");
    Eigen::SelfAdjointEigenSolver<Mat3> es(pm.inertia);
    if (es.eigenvalues().minCoeff() < -kInertiaPsd * scale)
      throw InputError(ip, what + ": inertia must be positive semi-definite");
  }
  expect_keys(o, p, {"node", "mass", "inertia"});
  return pm;
}

}  // namespace

namespace {
// read_load_list, appending to the three vectors (the model's own, for its default case: their
// storage is reused when a model is read again into the same Model).
void append_load_list(const Model& m, const json& list, const json_in::Pointer& base, std::vector<NodalLoad>& nodal,
                      std::vector<JointLoad>& joint, std::vector<MemberLoad>& member) {
  array(list, base, "loads");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const json_in::Pointer p = child(base, i);
    const auto& o = object(list[i], p, "load");
    if (field(o, "element")) {
      member.push_back(read_member_load(m, o, p));
      continue;
    }
    if (const json* joint_value = field(o, "joint")) {
      JointLoad l;
      l.joint = joint_ref(m, *joint_value, child(p, "joint"));
      const std::string what = "load on joint '" + m.joints[l.joint].id + "'";
      l.coordinate = o.contains("coordinate") ? integer(o["coordinate"], child(p, "coordinate"), what) : 0;
      if (l.coordinate < 0 || l.coordinate >= m.joints[l.joint].coordinates())
        throw InputError(child(p, "coordinate"), what + ": joint '" + m.joints[l.joint].id + "' has " +
                                                     std::to_string(m.joints[l.joint].coordinates()) + " coordinate(s)");
      l.value = number(require(o, p, "value", what), child(p, "value"), "load value");
      expect_keys(o, p, {"joint", "coordinate", "value"});
      joint.push_back(l);
      continue;
    }
    NodalLoad l;
    l.node = node_ref(m, require(o, p, "node", "load"), child(p, "node"));
    const std::string& node = m.nodes[l.node].id;  // "load at node '<id>' force" only in a message
    if (const json* force = field(o, "force")) l.force = vec3(*force, child(p, "force"), What("load at node '", node, "' force"));
    if (const json* moment = field(o, "moment")) l.moment = vec3(*moment, child(p, "moment"), What("load at node '", node, "' moment"));
    expect_keys(o, p, {"node", "force", "moment"});
    nodal.push_back(l);
  }
}
}  // namespace

LoadSet read_load_list(const Model& m, const json& list, const json_in::Pointer& base) {
  LoadSet s;
  append_load_list(m, list, base, s.nodal, s.joint, s.member);
  return s;
}

namespace {
// Calls read(object, pointer, id) for each object of the array doc[key], after checking that its
// "id" is new in `seen` (id -> pointer of its first definition).
template <class Read>
void for_each_identified(const json& doc, const char* key, const std::string& what,
                         std::map<std::string, std::string>& seen, Read&& read) {
  if (!doc.contains(key)) return;
  const std::string root = std::string("/") + key;
  const auto& arr = array(doc[key], root, key);
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const json_in::Pointer p = child(root, i);
    const auto& o = object(arr[i], p, what);
    std::string id = json_in::id(require(o, p, "id", what), child(p, "id"), what);
    if (auto [it, fresh] = seen.emplace(id, p); !fresh)
      throw InputError(child(p, "id"), what + " '" + id + "': the id is defined twice (first at " + it->second + ")");
    read(o, p, std::move(id));
  }
}
}  // namespace

void read_loads_and_cases(const json& doc, Model& m) {
  // The default load case, straight into the model.
  LoadSet& d = m.default_case;
  d.nodal.clear();
  d.joint.clear();
  d.member.clear();
  if (const json* loads = field(doc, "loads")) append_load_list(m, *loads, "/loads", d.nodal, d.joint, d.member);
  d.gravity = Vec3::Zero();
  if (const json* gravity = field(doc, "gravity")) d.gravity = read_gravity(*gravity, "/gravity");

  if (const json* masses = field(doc, "masses")) {
    const auto& arr = array(*masses, "/masses", "masses");
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const json_in::Pointer p = child("/masses", i);
      m.masses.push_back(read_mass(m, object(arr[i], p, "mass"), p));
    }
  }

  // Load cases and combinations share one name space (an analysis's load_case names either).
  std::map<std::string, std::string> seen;  // id -> pointer of its first definition
  for_each_identified(doc, "load_cases", "load case", seen, [&](const json& o, const json_in::Pointer& p, std::string id) {
    LoadCase c;
    c.id = std::move(id);
    if (o.contains("loads")) c.loads = read_load_list(m, o["loads"], child(p, "loads"));
    if (o.contains("gravity")) c.loads.gravity = read_gravity(o["gravity"], child(p, "gravity"));
    expect_keys(o, p, {"id", "loads", "gravity"});
    m.load_cases.push_back(std::move(c));
  });
  for_each_identified(doc, "combinations", "combination", seen, [&](const json& o, const json_in::Pointer& p, std::string id) {
    Combination c;
    c.id = std::move(id);
    const json_in::Pointer fp = child(p, "factors");
    const auto& factors = object(require(o, p, "factors", "combination '" + c.id + "'"), fp, "combination factors");
    for (const auto& [name, v] : factors.items()) {
      const int k = m.find_load_case(name);
      if (k < 0) throw InputError(child(fp, name), "combination '" + c.id + "' names unknown load case '" + name + "'");
      c.factors.emplace_back(k, number(v, child(fp, name), "combination factor"));
    }
    expect_keys(o, p, {"id", "factors"});
    m.add_combination(std::move(c));
  });
}

double read_density(const json* density, const json_in::Pointer& p, const std::string& what) {
  if (!density) return 0.0;
  const double rho = number(*density, child(p, "density"), What(what, " density"));
  if (!(rho >= 0.0)) throw InputError(child(p, "density"), what + ": density must not be negative");
  return rho;
}

std::string read_load_case(const Model& m, const json& spec, const json_in::Pointer& p) {
  const json* value = field(spec, "load_case");
  if (!value) return "";
  std::string id = json_in::id(*value, child(p, "load_case"), "load_case");
  if (!m.find_loads(id))
    throw InputError(child(p, "load_case"), "unknown load case or combination '" + id + "' (known: " + m.known_load_cases() + ")");
  return id;
}

}  // namespace beamfea
