// Model reader, part 4: the pose (docs/poses.md), read after everything it names; the model is then
// moved to it (solvers/pose.hpp).
#include <Eigen/LU>

#include "core/errors.hpp"
#include "io/json_util.hpp"
#include "io/model_reader.hpp"
#include "io/model_reader_parts.hpp"

namespace beamfea::reader {

using namespace json_in;

namespace {

// Largest |R^T R - I| and |det R - 1| of a target rotation: a matrix rounded to a few digits is
// accepted (and orthonormalised), anything further from a rotation is a mistake.
constexpr double kRotationTolerance = 1e-6;

std::string limit_text(const std::array<double, 2>& l) {
  return "[" + json(l[0]).dump() + ", " + json(l[1]).dump() + "]";
}

Eigen::VectorXd read_joint_values(const Joint& jt, const json& v, const Pointer& p, const std::string& what) {
  const int nc = jt.coordinates();
  Eigen::VectorXd q(nc);
  if (v.is_number() && nc == 1) {
    q[0] = number(v, p, what);
  } else {
    if (v.is_number())
      throw InputError(p, what + ": a " + joint_type_name(jt.type) + " joint takes a list of " + std::to_string(nc) + " values");
    const auto values = numbers(v, p, what);
    if (static_cast<int>(values.size()) != nc)
      throw InputError(p, what + ": expected " + std::to_string(nc) + " value(s), one per coordinate");
    for (int k = 0; k < nc; ++k) q[k] = values[k];
  }
  for (std::size_t k = 0; k < jt.limits.size(); ++k) {
    const double x = q[static_cast<int>(k)];
    if (x < jt.limits[k][0] || x > jt.limits[k][1])
      throw InputError(nc == 1 && !v.is_array() ? p : child(p, k),
                       what + ": coordinate " + std::to_string(k) + " = " + json(x).dump() + " is outside its limits " +
                           limit_text(jt.limits[k]));
  }
  return q;
}

PoseTarget read_target(const Model& m, const json& v, const Pointer& p) {
  const auto& o = object(v, p, "pose node target");
  const Fields f(o, p, {"node", "xyz", "rotation"});
  PoseTarget t;
  t.node = node_ref(m, f.require("node", "pose node target"), child(p, "node"));
  const std::string what = "pose target of node '" + m.nodes[t.node].id + "'";
  t.xyz = vec3(f.require("xyz", what), child(p, "xyz"), what);
  if (const json* r = f.get("rotation")) {
    const Pointer rp = child(p, "rotation");
    const auto& rows = array(*r, rp, What(what, " rotation"));
    if (rows.size() != 3) throw InputError(rp, what + ": a rotation is a 3x3 matrix (three rows)");
    for (int i = 0; i < 3; ++i) t.rotation.row(i) = vec3(rows[i], child(rp, i), What(what, " rotation")).transpose();
    if ((t.rotation.transpose() * t.rotation - Mat3::Identity()).cwiseAbs().maxCoeff() > kRotationTolerance ||
        std::abs(t.rotation.determinant() - 1.0) > kRotationTolerance)
      throw InputError(rp, what + ": the rotation must be a proper orthonormal matrix (R^T R = I, det R = 1)");
    t.rotation = orthonormalize(t.rotation);
    t.has_rotation = true;
  }
  return t;
}

}  // namespace

void read_pose(ReadState& s) {
  Model& m = s.model;
  const json* pose = field(s.doc, "pose");
  if (!pose) return;
  const Pointer p("/pose");
  const auto& o = object(*pose, p, "pose");
  const Fields f(o, p, {"joints", "nodes"});
  m.pose.given = true;
  if (const json* joints = f.get("joints")) {
    const Pointer jp = child(p, "joints");
    const auto& jo = object(*joints, jp, "pose joints");
    for (auto it = jo.begin(); it != jo.end(); ++it) {
      const std::string& id = it.key();
      const Pointer vp = child(jp, id);
      const int j = m.find_joint(id);
      if (j < 0) throw InputError(vp, "unknown joint '" + id + "' in the pose");
      m.pose.joints.emplace_back(j, read_joint_values(m.joints[j], it.value(), vp, "joint '" + id + "'"));
    }
  }
  if (const json* nodes = f.get("nodes")) {
    const Pointer np = child(p, "nodes");
    const auto& arr = array(*nodes, np, "pose nodes");
    for (std::size_t i = 0; i < arr.size(); ++i) {
      PoseTarget t = read_target(m, arr[i], child(np, i));
      for (const auto& other : m.pose.nodes)
        if (other.node == t.node)
          throw InputError(child(child(np, i), "node"), "node '" + m.nodes[t.node].id + "' has two targets in the pose");
      m.pose.nodes.push_back(t);
    }
  }
}

}  // namespace beamfea::reader
