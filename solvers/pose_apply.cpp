// Moving a model to a solved pose (solvers/pose.hpp).
#include "solvers/pose.hpp"

namespace beamfea {

void apply_pose(Model& m, const PoseSolution& s) {
  const auto body = [&](int node) { return s.body_of_node[node]; };
  for (std::size_t n = 0; n < m.nodes.size(); ++n) m.nodes[n].x = s.R[body(n)] * m.nodes[n].x + s.t[body(n)];
  for (auto& el : m.elements) {
    el.orientation = s.R[body(el.nodes[0])] * el.orientation;
    for (int k = 0; k < 2; ++k) el.offsets[k] = s.R[body(el.nodes[k])] * el.offsets[k];
  }
  for (auto& mb : m.members) {
    mb.orientation = s.R[body(mb.nodes[0])] * mb.orientation;
    for (int k = 0; k < 2; ++k) mb.offsets[k] = s.R[body(mb.nodes[k])] * mb.offsets[k];
  }
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    auto& jt = m.joints[j];
    const Mat3& RA = s.R[body(jt.nodes[0])];
    const Eigen::VectorXd& q = s.q[j];
    if (jt.type == JointType::Spherical) {
      for (auto& a : jt.axes) a = RA * a;  // fixed in the body of nodes[0]
      continue;
    }
    Mat3 M = RA;  // each axis where the coordinates before it carry it
    for (int k = 0; k < jt.coordinates(); ++k) {
      const Vec3 a = jt.axes[k];
      jt.axes[k] = M * a;
      if (!jt.is_translation(k)) M = M * exp_so3(q[k] * a);
    }
  }
  for (auto& sp : m.supports) {
    const Mat3& R = s.R[body(sp.node)];
    if (R.isIdentity(0.0)) continue;
    sp.axes = sp.axes * R.transpose();  // rows: the frame's axes, turned with the body
    sp.skewed = true;
  }
  for (auto& pm : m.masses) {
    const Mat3& R = s.R[body(pm.node)];
    pm.inertia = R * pm.inertia * R.transpose();
  }
}

void pose_model(Model& model, const PoseOptions& options) {
  if (!model.pose.given) return;
  const PoseSolution s = solve_pose(model, model.pose, options);
  apply_pose(model, s);
  model.pose.solved = s.q;
}

}  // namespace beamfea
