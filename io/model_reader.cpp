#include "io/model_reader.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

#include "core/errors.hpp"
#include "elements/beam.hpp"
#include "io/json_util.hpp"

namespace beamfea {

using json = nlohmann::json;
using namespace json_in;

json parse_json_text(const std::string& text, const std::string& source) {
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    throw InputError("", source + ": malformed JSON at byte " + std::to_string(e.byte) + ": " + e.what());
  }
}

json read_json_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("", "cannot read file '" + path + "'");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_json_text(ss.str(), path);
}

int node_ref(const Model& m, const json& v, const std::string& pointer) {
  const std::string id = json_in::id(v, pointer, "node reference");
  const int n = m.find_node(id);
  if (n < 0) throw InputError(pointer, "unknown node '" + id + "'");
  return n;
}

int joint_ref(const Model& m, const json& v, const std::string& pointer) {
  const std::string id = json_in::id(v, pointer, "joint reference");
  const int j = m.find_joint(id);
  if (j < 0) throw InputError(pointer, "unknown joint '" + id + "'");
  return j;
}

namespace {

void warn_unknown_keys(const json& obj, const std::string& pointer, std::initializer_list<const char*> known) {
  if (!obj.is_object()) return;
  for (const auto& [k, v] : obj.items()) {
    if (k.empty() || k[0] == '_' || k == "comment" || k == "description") continue;
    bool found = false;
    for (const char* n : known) found = found || k == n;
    if (!found) std::cerr << "beamfea: warning: " << child(pointer, k) << ": unknown field '" << k << "' ignored\n";
  }
}

const json& section_array(const json& doc, const char* key, bool required) {
  static const json empty = json::array();
  auto it = doc.find(key);
  if (it == doc.end()) {
    if (required) throw InputError(std::string("/") + key, std::string("missing '") + key + "'");
    return empty;
  }
  return array(*it, std::string("/") + key, key);
}

template <class V>
void check_unique(const V& items, const std::string& kind, const std::string& base, const std::string& id, std::size_t i,
                  std::map<std::string, std::size_t>& seen) {
  (void)items;
  auto [it, inserted] = seen.emplace(id, i);
  if (!inserted)
    throw InputError(child(child(base, i), "id"), "duplicate " + kind + " id '" + id + "' (first at " +
                                                      child(base, it->second) + ")");
}

Section read_section(const json& s, const std::string& p, const std::string& id) {
  Section sec;
  sec.id = id;
  const std::string what = "section '" + id + "'";
  if (s.contains("shape")) {
    const std::string shape = string(s["shape"], child(p, "shape"), what);
    if (shape == "rectangle") {
      // b along local y, h along local z.
      const double b = positive(require(s, p, "b", what), child(p, "b"), what + " b");
      const double h = positive(require(s, p, "h", what), child(p, "h"), what + " h");
      sec.A = b * h;
      sec.Iz = h * b * b * b / 12.0;
      sec.Iy = b * h * h * h / 12.0;
      // Saint-Venant torsion constant of a rectangle (Roark's Formulas for Stress and Strain,
      // 7th ed., Table 10.7 case 4): J = a c^3 [1/3 - 0.21 (c/a) (1 - (c/a)^4 / 12)], a >= c.
      const double a = std::max(b, h), c = std::min(b, h), r = c / a;
      sec.J = a * c * c * c * (1.0 / 3.0 - 0.21 * r * (1.0 - std::pow(r, 4) / 12.0));
      sec.ky = sec.kz = 6.0 / 5.0;
    } else if (shape == "circle") {
      double r;
      if (s.contains("d")) r = 0.5 * positive(s["d"], child(p, "d"), what + " d");
      else r = positive(require(s, p, "r", what), child(p, "r"), what + " r");
      sec.A = std::numbers::pi * r * r;
      sec.Iy = sec.Iz = std::numbers::pi * std::pow(r, 4) / 4.0;
      sec.J = std::numbers::pi * std::pow(r, 4) / 2.0;
      sec.ky = sec.kz = 10.0 / 9.0;
    } else if (shape == "tube") {
      const double ro = 0.5 * positive(require(s, p, "d", what), child(p, "d"), what + " d");
      const double t = positive(require(s, p, "t", what), child(p, "t"), what + " t");
      if (!(t < ro)) throw InputError(child(p, "t"), what + ": wall thickness must be below the radius");
      const double ri = ro - t;
      sec.A = std::numbers::pi * (ro * ro - ri * ri);
      sec.Iy = sec.Iz = std::numbers::pi * (std::pow(ro, 4) - std::pow(ri, 4)) / 4.0;
      sec.J = 2.0 * sec.Iy;
      sec.ky = sec.kz = 2.0;
    } else {
      throw InputError(child(p, "shape"), what + ": unknown shape '" + shape + "' (expected rectangle, circle, tube)");
    }
    // Explicit properties override the shape's.
  }
  auto prop = [&](const char* key, double& out, bool required) {
    if (s.contains(key)) out = positive(s[key], child(p, key), what + " " + key);
    else if (required && !s.contains("shape")) throw InputError(child(p, key), what + ": missing field '" + std::string(key) + "'");
  };
  prop("A", sec.A, true);
  prop("Iy", sec.Iy, true);
  prop("Iz", sec.Iz, true);
  prop("J", sec.J, true);
  if (s.contains("k")) sec.ky = sec.kz = positive(s["k"], child(p, "k"), what + " k");
  prop("ky", sec.ky, false);
  prop("kz", sec.kz, false);
  warn_unknown_keys(s, p, {"id", "shape", "b", "h", "d", "r", "t", "A", "Iy", "Iz", "J", "k", "ky", "kz"});
  return sec;
}

DofRef read_dof_target(const Model& m, const json& e, const std::string& p, const std::string& what) {
  if (e.contains("joint")) {
    const int j = joint_ref(m, e["joint"], child(p, "joint"));
    int c = e.contains("coordinate") ? integer(e["coordinate"], child(p, "coordinate"), what) : 0;
    if (c < 0 || c >= m.joints[j].coordinates())
      throw InputError(child(p, "coordinate"), what + ": joint '" + m.joints[j].id + "' has " +
                                                   std::to_string(m.joints[j].coordinates()) + " coordinate(s)");
    return {DofRef::Owner::Joint, j, c};
  }
  const int n = node_ref(m, require(e, p, "node", what), child(p, "node"));
  const std::string name = string(require(e, p, "dof", what), child(p, "dof"), what);
  const int k = dof_index(name);
  if (k < 0) throw InputError(child(p, "dof"), what + " at node '" + m.nodes[n].id + "': unknown DOF '" + name + "' (expected ux uy uz rx ry rz)");
  return {DofRef::Owner::Node, n, k};
}

}  // namespace

Model read_model(const json& doc) {
  if (!doc.is_object()) throw InputError("", "the model must be a JSON object");
  warn_unknown_keys(doc, "", {"nodes", "materials", "sections", "elements", "joints", "supports", "loads",
                              "prescribed", "analyses", "units", "title", "name"});
  Model m;

  // Nodes
  {
    const auto& arr = section_array(doc, "nodes", true);
    std::map<std::string, std::size_t> seen;
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const std::string p = child("/nodes", i);
      const auto& n = object(arr[i], p, "node");
      Node node;
      node.id = json_in::id(require(n, p, "id", "node"), child(p, "id"), "node");
      check_unique(m.nodes, "node", "/nodes", node.id, i, seen);
      node.x = vec3(require(n, p, "xyz", "node '" + node.id + "'"), child(p, "xyz"), "node '" + node.id + "' xyz");
      warn_unknown_keys(n, p, {"id", "xyz"});
      m.nodes.push_back(node);
    }
  }
  // Materials
  {
    const auto& arr = section_array(doc, "materials", false);
    std::map<std::string, std::size_t> seen;
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const std::string p = child("/materials", i);
      const auto& o = object(arr[i], p, "material");
      Material mat;
      mat.id = json_in::id(require(o, p, "id", "material"), child(p, "id"), "material");
      check_unique(m.materials, "material", "/materials", mat.id, i, seen);
      const std::string what = "material '" + mat.id + "'";
      mat.E = positive(require(o, p, "E", what), child(p, "E"), what + " E");
      if (o.contains("G")) {
        mat.G = positive(o["G"], child(p, "G"), what + " G");
      } else if (o.contains("nu")) {
        const double nu = number(o["nu"], child(p, "nu"), what + " nu");
        if (!(nu > -1.0 && nu < 0.5)) throw InputError(child(p, "nu"), what + ": nu must lie in (-1, 0.5)");
        mat.G = mat.E / (2.0 * (1.0 + nu));
      } else {
        throw InputError(child(p, "G"), what + ": missing field 'G' (or 'nu')");
      }
      warn_unknown_keys(o, p, {"id", "E", "G", "nu"});
      m.materials.push_back(mat);
    }
  }
  // Sections
  {
    const auto& arr = section_array(doc, "sections", false);
    std::map<std::string, std::size_t> seen;
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const std::string p = child("/sections", i);
      const auto& o = object(arr[i], p, "section");
      const std::string id = json_in::id(require(o, p, "id", "section"), child(p, "id"), "section");
      check_unique(m.sections, "section", "/sections", id, i, seen);
      m.sections.push_back(read_section(o, p, id));
    }
  }
  auto find = [](const auto& v, const std::string& id) {
    for (std::size_t i = 0; i < v.size(); ++i)
      if (v[i].id == id) return static_cast<int>(i);
    return -1;
  };
  // Elements (members), meshed into analysis elements.
  {
    const auto& arr = section_array(doc, "elements", false);
    std::map<std::string, std::size_t> seen;
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const std::string p = child("/elements", i);
      const auto& o = object(arr[i], p, "element");
      Member mem;
      mem.id = json_in::id(require(o, p, "id", "element"), child(p, "id"), "element");
      check_unique(m.members, "element", "/elements", mem.id, i, seen);
      const std::string what = "element '" + mem.id + "'";
      const std::string type = string(require(o, p, "type", what), child(p, "type"), what);
      if (type == "beam") mem.type = MemberType::Beam;
      else if (type == "rigid") mem.type = MemberType::Rigid;
      else throw InputError(child(p, "type"), what + ": unknown type '" + type + "' (expected beam or rigid)");
      const auto& nodes = require(o, p, "nodes", what);
      if (!nodes.is_array() || nodes.size() != 2) throw InputError(child(p, "nodes"), what + ": expected two node ids");
      for (int k = 0; k < 2; ++k) mem.nodes[k] = node_ref(m, nodes[k], child(child(p, "nodes"), k));
      const Vec3 x1 = m.nodes[mem.nodes[0]].x, x2 = m.nodes[mem.nodes[1]].x;
      const double L = (x2 - x1).norm();
      if (!(L > 1e-12 * m.length_scale()))
        throw InputError(child(p, "nodes"), what + ": zero length (nodes '" + m.nodes[mem.nodes[0]].id + "' and '" +
                                                m.nodes[mem.nodes[1]].id + "' coincide)");
      if (mem.type == MemberType::Beam) {
        const std::string mid = json_in::id(require(o, p, "material", what), child(p, "material"), what + " material");
        mem.material = find(m.materials, mid);
        if (mem.material < 0) throw InputError(child(p, "material"), what + ": unknown material '" + mid + "'");
        const std::string sid = json_in::id(require(o, p, "section", what), child(p, "section"), what + " section");
        mem.section = find(m.sections, sid);
        if (mem.section < 0) throw InputError(child(p, "section"), what + ": unknown section '" + sid + "'");
        const Vec3 ex = (x2 - x1) / L;
        if (o.contains("orientation")) {
          mem.orientation = vec3(o["orientation"], child(p, "orientation"), what + " orientation");
          if (mem.orientation.norm() == 0.0 || mem.orientation.normalized().cross(ex).norm() < 1e-8)
            throw InputError(child(p, "orientation"), what + ": orientation is zero or parallel to the member");
        } else {
          // Default: global Z in the local x-z plane; for a vertical member, global X.
          mem.orientation = std::abs(ex.z()) > 1.0 - 1e-8 ? Vec3(1, 0, 0) : Vec3(0, 0, 1);
        }
        if (o.contains("divisions")) {
          mem.divisions = integer(o["divisions"], child(p, "divisions"), what + " divisions");
          if (mem.divisions < 1) throw InputError(child(p, "divisions"), what + ": divisions must be at least 1");
        }
      } else if (o.contains("divisions") && o["divisions"] != 1) {
        throw InputError(child(p, "divisions"), what + ": a rigid link cannot be divided");
      }
      warn_unknown_keys(o, p, {"id", "type", "nodes", "material", "section", "orientation", "divisions"});
      const int mi = static_cast<int>(m.members.size());
      int prev = mem.nodes[0];
      for (int k = 0; k < mem.divisions; ++k) {
        int next = mem.nodes[1];
        if (k + 1 < mem.divisions) {
          Node n;
          n.id = mem.id + "#" + std::to_string(k + 1);
          if (m.find_node(n.id) >= 0) throw InputError(child(p, "id"), what + ": internal node id '" + n.id + "' is taken");
          n.x = x1 + (x2 - x1) * (static_cast<double>(k + 1) / mem.divisions);
          n.member = mi;
          next = static_cast<int>(m.nodes.size());
          m.nodes.push_back(n);
        }
        Element e;
        e.id = mem.divisions == 1 ? mem.id : mem.id + "#" + std::to_string(k + 1);
        e.type = mem.type;
        e.nodes = {prev, next};
        e.material = mem.material;
        e.section = mem.section;
        e.orientation = mem.orientation;
        e.member = mi;
        mem.elements.push_back(static_cast<int>(m.elements.size()));
        m.elements.push_back(e);
        prev = next;
      }
      m.members.push_back(mem);
    }
  }
  // Joints
  {
    const auto& arr = section_array(doc, "joints", false);
    std::map<std::string, std::size_t> seen;
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const std::string p = child("/joints", i);
      const auto& o = object(arr[i], p, "joint");
      Joint j;
      j.id = json_in::id(require(o, p, "id", "joint"), child(p, "id"), "joint");
      check_unique(m.joints, "joint", "/joints", j.id, i, seen);
      const std::string what = "joint '" + j.id + "'";
      const std::string type = string(require(o, p, "type", what), child(p, "type"), what);
      if (type == "revolute") j.type = JointType::Revolute;
      else if (type == "universal") j.type = JointType::Universal;
      else if (type == "spherical") j.type = JointType::Spherical;
      else if (type == "virtual_spring") j.type = JointType::VirtualSpring;
      else throw InputError(child(p, "type"), what + ": unknown type '" + type + "' (expected revolute, universal, spherical, virtual_spring)");
      const auto& nodes = require(o, p, "nodes", what);
      if (!nodes.is_array() || nodes.size() != 2) throw InputError(child(p, "nodes"), what + ": expected two node ids");
      for (int k = 0; k < 2; ++k) j.nodes[k] = node_ref(m, nodes[k], child(child(p, "nodes"), k));
      if (j.nodes[0] == j.nodes[1]) throw InputError(child(p, "nodes"), what + ": joins a node to itself");
      if ((m.nodes[j.nodes[0]].x - m.nodes[j.nodes[1]].x).norm() > 1e-9 * m.length_scale())
        throw InputError(child(p, "nodes"), what + ": nodes '" + m.nodes[j.nodes[0]].id + "' and '" +
                                                m.nodes[j.nodes[1]].id + "' do not coincide");
      const int nc = joint_coordinate_count(j.type);
      // Axes: one per rotation coordinate; a virtual spring gives its frame (x, y, z), used for
      // its three translations and its three rotations alike.
      const int naxes = j.type == JointType::VirtualSpring ? 3 : nc;
      std::vector<Vec3> axes_in;
      if (o.contains("axes")) {
        const auto& axes = array(o["axes"], child(p, "axes"), what + " axes");
        if (static_cast<int>(axes.size()) != naxes)
          throw InputError(child(p, "axes"), what + ": a " + type + " joint needs " + std::to_string(naxes) + " axes");
        for (std::size_t k = 0; k < axes.size(); ++k) {
          Vec3 a = vec3(axes[k], child(child(p, "axes"), k), what + " axis");
          if (a.norm() == 0.0) throw InputError(child(child(p, "axes"), k), what + ": axis is zero");
          axes_in.push_back(a.normalized());
        }
      } else if (j.type == JointType::Spherical || j.type == JointType::VirtualSpring) {
        axes_in = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
      } else {
        throw InputError(child(p, "axes"), what + ": missing field 'axes'");
      }
      for (int a = 0; a < naxes; ++a)
        for (int b = a + 1; b < naxes; ++b)
          if (axes_in[a].cross(axes_in[b]).norm() < 1e-6)
            throw InputError(child(p, "axes"), what + ": axes " + std::to_string(a) + " and " + std::to_string(b) + " are parallel");
      if (j.type == JointType::VirtualSpring) {
        for (int a = 0; a < 3; ++a)
          for (int b = a + 1; b < 3; ++b)
            if (std::abs(axes_in[a].dot(axes_in[b])) > 1e-9)
              throw InputError(child(p, "axes"), what + ": the axes of a virtual spring must be orthogonal");
        j.translations = 3;
        j.axes = axes_in;
        j.axes.insert(j.axes.end(), axes_in.begin(), axes_in.end());
      } else {
        j.axes = axes_in;
      }
      j.stiffness.assign(nc, 0.0);
      if (o.contains("stiffness")) {
        const auto& st = o["stiffness"];
        const std::string sp = child(p, "stiffness");
        if (st.is_array() && !st.empty() && st[0].is_array()) {
          // A full matrix, symmetric, positive semi-definite.
          if (static_cast<int>(st.size()) != nc)
            throw InputError(sp, what + ": expected a " + std::to_string(nc) + "x" + std::to_string(nc) + " stiffness matrix");
          Eigen::MatrixXd K(nc, nc);
          for (int r = 0; r < nc; ++r) {
            auto row = numbers(st[r], child(sp, r), what + " stiffness");
            if (static_cast<int>(row.size()) != nc)
              throw InputError(child(sp, r), what + ": expected " + std::to_string(nc) + " values in each row");
            for (int c = 0; c < nc; ++c) K(r, c) = row[c];
          }
          if ((K - K.transpose()).cwiseAbs().maxCoeff() > 1e-9 * K.cwiseAbs().maxCoeff())
            throw InputError(sp, what + ": the stiffness matrix must be symmetric");
          Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(K);
          if (es.eigenvalues().minCoeff() < -1e-9 * K.cwiseAbs().maxCoeff())
            throw InputError(sp, what + ": the stiffness matrix must be positive semi-definite");
          j.stiffness_matrix = K;
          for (int c = 0; c < nc; ++c) j.stiffness[c] = K(c, c);
        } else {
          auto k = numbers(st, sp, what + " stiffness");
          if (static_cast<int>(k.size()) != nc)
            throw InputError(sp, what + ": expected " + std::to_string(nc) + " stiffness value(s)");
          for (int c = 0; c < nc; ++c)
            if (k[c] < 0.0) throw InputError(child(sp, c), what + ": stiffness must not be negative");
          j.stiffness = k;
        }
      }
      if (o.contains("stiffness_from_beam")) {
        // The tip stiffness of a cantilever of the given section and length, in the joint frame
        // (x along the link): Pashkevich et al. (2010) eq. 39 = the end-2 block of the beam matrix.
        if (j.type != JointType::VirtualSpring)
          throw InputError(child(p, "stiffness_from_beam"), what + ": stiffness_from_beam needs a virtual_spring joint");
        const std::string bp = child(p, "stiffness_from_beam");
        const auto& b = object(o["stiffness_from_beam"], bp, what + " stiffness_from_beam");
        const std::string mid = json_in::id(require(b, bp, "material", what), child(bp, "material"), what + " material");
        const std::string sid = json_in::id(require(b, bp, "section", what), child(bp, "section"), what + " section");
        int mi = -1, si = -1;
        for (std::size_t k = 0; k < m.materials.size(); ++k) if (m.materials[k].id == mid) mi = static_cast<int>(k);
        for (std::size_t k = 0; k < m.sections.size(); ++k) if (m.sections[k].id == sid) si = static_cast<int>(k);
        if (mi < 0) throw InputError(child(bp, "material"), what + ": unknown material '" + mid + "'");
        if (si < 0) throw InputError(child(bp, "section"), what + ": unknown section '" + sid + "'");
        const double L = positive(require(b, bp, "length", what), child(bp, "length"), what + " length");
        const auto& mat = m.materials[mi];
        const auto& sec = m.sections[si];
        const BeamSection bs{mat.E, mat.G, sec.A, sec.Iy, sec.Iz, sec.J};
        j.stiffness_matrix = beam_local_stiffness(bs, L).bottomRightCorner<6, 6>();
        for (int c = 0; c < nc; ++c) j.stiffness[c] = j.stiffness_matrix(c, c);
      }
      warn_unknown_keys(o, p, {"id", "type", "nodes", "axes", "stiffness", "stiffness_from_beam"});
      m.joints.push_back(j);
    }
  }
  // Supports
  {
    const auto& arr = section_array(doc, "supports", false);
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const std::string p = child("/supports", i);
      const auto& o = object(arr[i], p, "support");
      Support s;
      s.node = node_ref(m, require(o, p, "node", "support"), child(p, "node"));
      const std::string what = "support at node '" + m.nodes[s.node].id + "'";
      const auto& fix = require(o, p, "fix", what);
      if (fix.is_string() && fix.get<std::string>() == "all") {
        s.fixed.fill(true);
      } else {
        array(fix, child(p, "fix"), what);
        for (std::size_t k = 0; k < fix.size(); ++k) {
          const std::string name = string(fix[k], child(child(p, "fix"), k), what);
          const int d = dof_index(name);
          if (d < 0) throw InputError(child(child(p, "fix"), k), what + ": unknown DOF '" + name + "' (expected ux uy uz rx ry rz)");
          s.fixed[d] = true;
        }
      }
      warn_unknown_keys(o, p, {"node", "fix"});
      m.supports.push_back(s);
    }
  }
  // Loads
  {
    const auto& arr = section_array(doc, "loads", false);
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const std::string p = child("/loads", i);
      const auto& o = object(arr[i], p, "load");
      if (o.contains("joint")) {
        JointLoad l;
        const DofRef d = read_dof_target(m, o, p, "load");
        l.joint = d.index;
        l.coordinate = d.comp;
        l.value = number(require(o, p, "value", "load on joint '" + m.joints[l.joint].id + "'"), child(p, "value"), "load value");
        warn_unknown_keys(o, p, {"joint", "coordinate", "value"});
        m.joint_loads.push_back(l);
        continue;
      }
      NodalLoad l;
      l.node = node_ref(m, require(o, p, "node", "load"), child(p, "node"));
      const std::string what = "load at node '" + m.nodes[l.node].id + "'";
      if (o.contains("force")) l.force = vec3(o["force"], child(p, "force"), what + " force");
      if (o.contains("moment")) l.moment = vec3(o["moment"], child(p, "moment"), what + " moment");
      warn_unknown_keys(o, p, {"node", "force", "moment"});
      m.loads.push_back(l);
    }
  }
  // Prescribed values
  {
    const auto& arr = section_array(doc, "prescribed", false);
    std::set<std::pair<int, int>> seen;
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const std::string p = child("/prescribed", i);
      const auto& o = object(arr[i], p, "prescribed value");
      Prescribed pr;
      pr.dof = read_dof_target(m, o, p, "prescribed value");
      pr.value = number(require(o, p, "value", "prescribed " + m.describe(pr.dof)), child(p, "value"), "prescribed value");
      if (!seen.insert({pr.dof.owner == DofRef::Owner::Node ? pr.dof.index : -1 - pr.dof.index, pr.dof.comp}).second)
        throw InputError(p, m.describe(pr.dof) + " is prescribed twice");
      warn_unknown_keys(o, p, {"node", "dof", "joint", "coordinate", "value"});
      m.prescribed.push_back(pr);
    }
  }
  return m;
}

}  // namespace beamfea
