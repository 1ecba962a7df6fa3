#include "solvers/nonlinear_structure.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <map>
#include <set>

#include "core/errors.hpp"
#include "solvers/element_factory.hpp"
#include "solvers/member_loading.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

Mat3 joint_product(const Joint& j, const Eigen::VectorXd& q) {
  Mat3 P = Mat3::Identity();
  for (int k = j.translations; k < j.coordinates(); ++k) P = P * exp_so3(q[k] * j.axes[k]);
  return P;
}

Vec3 joint_offset(const Joint& j, const Eigen::VectorXd& q) {
  Vec3 t = Vec3::Zero();
  for (int k = 0; k < j.translations; ++k) t += q[k] * j.axes[k];
  return t;
}

namespace {

Mat3 spherical_axes(const Joint& j) {
  Mat3 A;
  for (int k = 0; k < 3; ++k) A.col(k) = j.axes[k];
  return A;
}

}  // namespace

Configuration configuration_of(const Model& model, const NonlinearState& s) {
  Configuration c;
  c.x = s.x;
  c.R = s.R;
  c.joint_axes.resize(model.joints.size());
  for (std::size_t jj = 0; jj < model.joints.size(); ++jj) {
    const auto& j = model.joints[jj];
    const Mat3& R0 = s.R[j.nodes[0]];
    auto& axes = c.joint_axes[jj];
    axes.resize(j.coordinates());
    if (j.type == JointType::Spherical) {
      for (int k = 0; k < 3; ++k) axes[k] = R0 * j.axes[k];
      continue;
    }
    Mat3 M = R0;
    for (int k = 0; k < j.coordinates(); ++k) {
      axes[k] = M * j.axes[k];
      if (!j.is_translation(k)) M = M * exp_so3(s.q[jj][k] * j.axes[k]);
    }
  }
  return c;
}

NonlinearStructure::NonlinearStructure(const Model& model, const LoadSet& loads) : model_(&model), map_(model), L_(model.length_scale()) {
  for (std::size_t j = 0; j < model.joints.size(); ++j) {
    if (model.joints[j].type == JointType::Spherical && model.joints[j].has_stiffness())
      throw ModelError("joint '" + model.joints[j].id + "'",
                       "springs on spherical joints are not supported by nonlinear analyses; use a virtual_spring");
  }

  raw_to_gen_.assign(map_.raw_size(), -1);
  int group = 0;
  const int nn = static_cast<int>(model.nodes.size());
  for (int n = 0; n < nn; ++n) {
    if (map_.is_slave(n)) continue;
    for (int k = 0; k < 3; ++k) add_gen({GenKind::NodeTranslation, n, k, group, map_.raw_node(n, k)});
    ++group;
    for (int k = 0; k < 3; ++k) add_gen({GenKind::NodeSpin, n, k, group, map_.raw_node(n, 3 + k)});
    ++group;
  }
  std::vector<char> backward(model.joints.size(), 0);
  for (const auto& e : map_.tree_edges())
    if (e.kind == ConstraintEdge::Kind::Joint && !e.forward) backward[e.index] = 1;
  for (int j = 0; j < static_cast<int>(model.joints.size()); ++j) {
    const auto& jt = model.joints[j];
    const bool sph = jt.type == JointType::Spherical;
    for (int k = 0; k < jt.coordinates(); ++k) {
      add_gen({sph ? GenKind::JointSpherical : GenKind::JointScalar, j, k, group, map_.raw_joint(j, k),
               sph && backward[j] != 0});
      if (!sph) ++group;
    }
    if (sph) ++group;
  }

  chain_.assign(nn, {});
  for (int n = 0; n < nn; ++n)
    if (!map_.is_slave(n))
      for (int k = 0; k < 6; ++k) chain_[n].push_back(raw_to_gen_[map_.raw_node(n, k)]);
  for (int ei : map_.tree_order()) {
    const auto& e = map_.tree_edges()[ei];
    auto c = chain_[e.parent];
    if (e.kind == ConstraintEdge::Kind::Joint) {
      const auto& jt = model.joints[e.index];
      std::vector<int> g;
      for (int k = 0; k < jt.coordinates(); ++k) g.push_back(raw_to_gen_[map_.raw_joint(e.index, k)]);
      if (!e.forward) std::reverse(g.begin(), g.end());  // inverse: rotations (last first), then translations
      c.insert(c.end(), g.begin(), g.end());
    }
    chain_[e.child] = std::move(c);
  }

  build_closures();
  beams_.resize(model.elements.size());
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const auto& el = model.elements[e];
    if (el.type != MemberType::Beam) continue;
    beams_[e] = make_frame_element(model, static_cast<int>(e), Kinematics::Corotational);
  }
  dead_ = element_dead_loads(model, loads);
  dead_ref_.assign(model.elements.size(), Vec12::Zero());
  for (std::size_t e = 0; e < dead_.size(); ++e)
    if (!dead_[e].empty()) {
      const auto& el = model.elements[e];
      dead_ref_[e] = dead_load_vector(dead_[e], (model.nodes[el.nodes[1]].x - model.nodes[el.nodes[0]].x).normalized());
    }
}

Eigen::VectorXd NonlinearStructure::dead_load_change(const NonlinearState& s) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(map_.raw_size());
  for (std::size_t e = 0; e < dead_.size(); ++e) {
    if (dead_[e].empty()) continue;
    const int a = model_->elements[e].nodes[0], b = model_->elements[e].nodes[1];
    const Vec12 d = dead_load_vector(dead_[e], (s.x[b] - s.x[a]).normalized()) - dead_ref_[e];
    f.segment<6>(6 * a) += d.head<6>();
    f.segment<6>(6 * b) += d.tail<6>();
  }
  return f;
}

void NonlinearStructure::add_gen(Gen g) {
  raw_to_gen_[g.raw] = static_cast<int>(gens_.size());
  gens_.push_back(g);
}

bool NonlinearStructure::is_rotation(int i) const {
  const Gen& g = gens_[i];
  switch (g.kind) {
    case GenKind::NodeTranslation: return false;
    case GenKind::NodeSpin: return true;
    case GenKind::JointSpherical: return true;
    case GenKind::JointScalar: return !model_->joints[g.owner].is_translation(g.comp);
  }
  return false;
}

NonlinearState NonlinearStructure::reference_state() const {
  NonlinearState s;
  for (const auto& n : model_->nodes) s.x.push_back(n.x);
  s.R.assign(model_->nodes.size(), Mat3::Identity());
  for (const auto& j : model_->joints) s.q.push_back(Eigen::VectorXd::Zero(j.coordinates()));
  s.Q.assign(model_->joints.size(), Mat3::Identity());
  return s;
}

void NonlinearStructure::complete(NonlinearState& s) const {
  for (int ei : map_.tree_order()) {
    const auto& e = map_.tree_edges()[ei];
    const int p = e.parent, c = e.child;
    if (e.kind == ConstraintEdge::Kind::Rigid) {
      s.R[c] = s.R[p];
      s.x[c] = s.x[p] + s.R[p] * (model_->nodes[c].x - model_->nodes[p].x);
      continue;
    }
    const auto& j = model_->joints[e.index];
    const Mat3 P = j.type == JointType::Spherical ? s.Q[e.index] : joint_product(j, s.q[e.index]);
    const Vec3 t = joint_offset(j, s.q[e.index]);
    if (e.forward) {
      s.R[c] = s.R[p] * P;
      s.x[c] = s.x[p] + s.R[p] * t;
    } else {
      s.R[c] = s.R[p] * P.transpose();
      s.x[c] = s.x[p] - s.R[c] * t;
    }
  }
  for (std::size_t j = 0; j < model_->joints.size(); ++j)
    if (model_->joints[j].type == JointType::Spherical)
      s.q[j] = spherical_axes(model_->joints[j]).inverse() * log_so3(s.Q[j]);
}

NonlinearState NonlinearStructure::retract(const NonlinearState& base, const Eigen::VectorXd& d) const {
  NonlinearState s = base;
  std::map<int, Vec3> spin, sph;
  for (int i = 0; i < size(); ++i) {
    const Gen& g = gens_[i];
    if (d[i] == 0.0) continue;
    switch (g.kind) {
      case GenKind::NodeTranslation: s.x[g.owner][g.comp] += d[i]; break;
      case GenKind::NodeSpin: spin.try_emplace(g.owner, Vec3::Zero()).first->second += d[i] * Vec3::Unit(g.comp); break;
      case GenKind::JointScalar: s.q[g.owner][g.comp] += d[i]; break;
      case GenKind::JointSpherical:
        sph.try_emplace(g.owner, Vec3::Zero()).first->second += d[i] * model_->joints[g.owner].axes[g.comp];
        break;
    }
  }
  for (auto& [n, w] : spin) s.R[n] = orthonormalize(exp_so3(w) * s.R[n]);
  for (auto& [j, w] : sph) s.Q[j] = orthonormalize(exp_so3(w) * s.Q[j]);
  complete(s);
  return s;
}

SparseMatrix NonlinearStructure::retraction_jacobian(const Eigen::VectorXd& d) const {
  std::vector<Eigen::Triplet<double>> t;
  std::map<int, std::vector<int>> spin, sph;  // owner -> gens (3)
  for (int i = 0; i < size(); ++i) {
    const Gen& g = gens_[i];
    if (g.kind == GenKind::NodeSpin) spin[g.owner].push_back(i);
    else if (g.kind == GenKind::JointSpherical) sph[g.owner].push_back(i);
    else t.emplace_back(i, i, 1.0);
  }
  for (auto& [n, gi] : spin) {
    const Vec3 w(d[gi[0]], d[gi[1]], d[gi[2]]);
    const Mat3 T = tangent_so3(w);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) t.emplace_back(gi[a], gi[b], T(a, b));
  }
  for (auto& [j, gi] : sph) {
    const Mat3 A = spherical_axes(model_->joints[j]);
    const Vec3 dq(d[gi[0]], d[gi[1]], d[gi[2]]);
    const Mat3 T = A.inverse() * tangent_so3(A * dq) * A;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) t.emplace_back(gi[a], gi[b], T(a, b));
  }
  SparseMatrix D(size(), size());
  D.setFromTriplets(t.begin(), t.end());
  return D;
}

std::vector<Twist> NonlinearStructure::twists(const NonlinearState& s) const {
  std::vector<Twist> tw(gens_.size());
  std::vector<int> forward(model_->joints.size(), 1);
  for (const auto& e : map_.tree_edges())
    if (e.kind == ConstraintEdge::Kind::Joint) forward[e.index] = e.forward ? 1 : 0;
  for (int i = 0; i < size(); ++i) {
    const Gen& g = gens_[i];
    if (g.kind == GenKind::NodeTranslation) {
      tw[i].v = Vec3::Unit(g.comp);
    } else if (g.kind == GenKind::NodeSpin) {
      tw[i].w = Vec3::Unit(g.comp);
      tw[i].v = s.x[g.owner].cross(tw[i].w);
    }
  }
  for (int jj = 0; jj < static_cast<int>(model_->joints.size()); ++jj) {
    const auto& j = model_->joints[jj];
    const double sign = forward[jj] ? 1.0 : -1.0;
    const Mat3& R0 = s.R[j.nodes[0]];
    // The point the joint's rotations turn about: nodes[1], or for a joint that closes a loop the
    // position of its virtual body (nodes[0]'s side).
    const Vec3 x1 = loop_joint_.empty() || !loop_joint_[jj] ? s.x[j.nodes[1]]
                                                           : Vec3(s.x[j.nodes[0]] + R0 * joint_offset(j, s.q[jj]));
    Mat3 M = R0;
    for (int k = 0; k < j.coordinates(); ++k) {
      const int gi = raw_to_gen_[map_.raw_joint(jj, k)];
      const Vec3 c = M * j.axes[k];
      if (j.is_translation(k)) {
        tw[gi].v = sign * c;
      } else {
        tw[gi].w = sign * c;
        tw[gi].v = sign * x1.cross(c);
        if (j.type != JointType::Spherical) M = M * exp_so3(s.q[jj][k] * j.axes[k]);
      }
    }
  }
  return tw;
}

std::vector<std::pair<int, double>> NonlinearStructure::raw_row(const NonlinearState& s, const std::vector<Twist>& tw,
                                                                int node, int comp) const {
  std::vector<std::pair<int, double>> row;
  for (int i : chain_[node]) {
    const double v = comp < 3 ? (tw[i].v + tw[i].w.cross(s.x[node]))[comp] : tw[i].w[comp - 3];
    if (v != 0.0) row.emplace_back(i, v);
  }
  return row;
}

void NonlinearStructure::add_point_curvature(const Vec3& x, const Vec3& f, const Vec3& m, const std::vector<int>& c,
                                             const std::vector<Twist>& tw, std::vector<Eigen::Triplet<double>>& t) const {
  for (std::size_t a = 0; a < c.size(); ++a) {
    const Twist& xi = tw[c[a]];
    for (std::size_t b = 0; b < c.size(); ++b) {
      const Twist& xj = tw[c[b]];
      double val = f.dot(xi.w.cross(xj.v + xj.w.cross(x)));
      const bool same = gens_[c[a]].group == gens_[c[b]].group;
      if ((b < a && !same) || (same && a != b && gens_[c[a]].mutual)) {
        const Vec3 bv = xj.w.cross(xi.v) - xi.w.cross(xj.v);
        const Vec3 bw = xj.w.cross(xi.w);
        val += f.dot(bv + bw.cross(x)) + m.dot(bw);
      }
      t.emplace_back(c[a], c[b], val);  // zeros too: the pattern is the same at every state
    }
  }
}

SparseMatrix NonlinearStructure::constraint_curvature(const NonlinearState& s, const std::vector<Twist>& tw,
                                                      const Eigen::VectorXd& f_raw) const {
  std::vector<Eigen::Triplet<double>> t;
  for (int n = 0; n < static_cast<int>(model_->nodes.size()); ++n) {
    if (!map_.is_slave(n)) continue;
    const Vec3 f = f_raw.segment<3>(6 * n), m = f_raw.segment<3>(6 * n + 3);
    add_point_curvature(s.x[n], f, m, chain_[n], tw, t);
  }
  SparseMatrix G(size(), size());
  G.setFromTriplets(t.begin(), t.end());
  return G;
}

NonlinearStructure::Evaluation NonlinearStructure::evaluate(const NonlinearState& s, const Eigen::VectorXd& f_app_in,
                                                            bool with_tangent, const Eigen::VectorXd& mu,
                                                            double dead_load_factor) const {
  const bool dead = dead_load_factor != 0.0 && std::any_of(dead_.begin(), dead_.end(), [](const auto& d) { return !d.empty(); });
  const Eigen::VectorXd f_app = dead ? Eigen::VectorXd(f_app_in + dead_load_factor * dead_load_change(s)) : f_app_in;
  Evaluation ev;
  const int nraw = map_.raw_size();
  ev.f_int_raw = Eigen::VectorXd::Zero(nraw);
  ev.end_forces.assign(model_->elements.size(), Vec12::Zero());
  const std::vector<Twist> tw = twists(s);
  std::vector<Eigen::Triplet<double>> trip;

  // Dense Jacobian of a node's 6 raw DOFs over its chain.
  auto node_T = [&](int n) {
    const auto& c = chain_[n];
    Eigen::Matrix<double, 6, Eigen::Dynamic> T(6, c.size());
    for (std::size_t a = 0; a < c.size(); ++a) {
      T.block<3, 1>(0, a) = tw[c[a]].v + tw[c[a]].w.cross(s.x[n]);
      T.block<3, 1>(3, a) = tw[c[a]].w;
    }
    return T;
  };

  for (std::size_t e = 0; e < beams_.size(); ++e) {
    if (!beams_[e]) continue;
    const auto& el = model_->elements[e];
    const int a = el.nodes[0], b = el.nodes[1];
    const ElementResponse r = [&] {
      try {
        return beams_[e]->respond({s.x[a], s.x[b], s.R[a], s.R[b]}, with_tangent ? Evaluate::ForceAndTangent : Evaluate::Force);
      } catch (const Error& err) {  // the element's own error, named here
        throw ModelError("element '" + el.id + "'", err.what());
      }
    }();
    ev.end_forces[e] = r.local_end_forces;
    ev.energy += r.energy;
    ev.f_int_raw.segment<6>(6 * a) += r.force.head<6>();
    ev.f_int_raw.segment<6>(6 * b) += r.force.tail<6>();
    if (!with_tangent) continue;
    // Columns: union of the two chains.
    std::vector<int> cols = chain_[a];
    std::map<int, int> pos;
    for (std::size_t k = 0; k < cols.size(); ++k) pos[cols[k]] = static_cast<int>(k);
    for (int g : chain_[b])
      if (!pos.count(g)) {
        pos[g] = static_cast<int>(cols.size());
        cols.push_back(g);
      }
    Eigen::MatrixXd Te = Eigen::MatrixXd::Zero(12, cols.size());
    const auto Ta = node_T(a), Tb = node_T(b);
    for (std::size_t k = 0; k < chain_[a].size(); ++k) Te.block<6, 1>(0, pos[chain_[a][k]]) += Ta.col(k);
    for (std::size_t k = 0; k < chain_[b].size(); ++k) Te.block<6, 1>(6, pos[chain_[b][k]]) += Tb.col(k);
    Eigen::MatrixXd Ke = Te.transpose() * r.tangent * Te;
    if (dead && !dead_[e].empty()) {
      // Load stiffness of the dead loads: -d(f_app)/dx, f depending on the chord x_b - x_a.
      const Vec3 d = s.x[b] - s.x[a];
      const auto D = dead_load_derivative(dead_[e], d.normalized(), d.norm());
      Mat12 KL = Mat12::Zero();
      KL.block<12, 3>(0, 0) = dead_load_factor * D;
      KL.block<12, 3>(0, 6) = -dead_load_factor * D;
      Ke += Te.transpose() * KL * Te;
    }
    for (std::size_t i = 0; i < cols.size(); ++i)
      for (std::size_t k = 0; k < cols.size(); ++k) trip.emplace_back(cols[i], cols[k], Ke(i, k));
  }
  for (std::size_t jj = 0; jj < model_->joints.size(); ++jj) {
    const auto& j = model_->joints[jj];
    if (!j.has_stiffness()) continue;
    const Eigen::MatrixXd K = j.stiffness_as_matrix();
    const int r0 = map_.raw_joint(static_cast<int>(jj), 0);
    ev.f_int_raw.segment(r0, j.coordinates()) += K * s.q[jj];
    ev.energy += 0.5 * s.q[jj].dot(K * s.q[jj]);
    if (!with_tangent) continue;
    for (int a = 0; a < j.coordinates(); ++a)
      for (int b = 0; b < j.coordinates(); ++b)
        trip.emplace_back(raw_to_gen_[r0 + a], raw_to_gen_[r0 + b], K(a, b));
  }

  const Eigen::VectorXd f = ev.f_int_raw - f_app;
  ev.residual = reduce(s, tw, f);
  const bool closed = mu.size() > 0 && !closures_.empty();
  if (closed) ev.residual += closure_force_rows(s, tw).transpose() * mu;
  if (with_tangent) {
    ev.tangent.resize(size(), size());
    ev.tangent.setFromTriplets(trip.begin(), trip.end());
    ev.tangent += constraint_curvature(s, tw, f);
    if (closed) ev.tangent += closure_curvature(s, tw, mu);
    // Keep every diagonal entry stored, so that the pattern is the same at every state.
    SparseMatrix I(size(), size());
    I.setIdentity();
    ev.tangent += 0.0 * I;
  }
  return ev;
}

Eigen::VectorXd NonlinearStructure::reduce(const NonlinearState& s, const std::vector<Twist>& tw,
                                           const Eigen::VectorXd& f) const {
  Eigen::VectorXd r = Eigen::VectorXd::Zero(size());
  const int nn = static_cast<int>(model_->nodes.size());
  for (int n = 0; n < nn; ++n) {
    const Vec6 fn = f.segment<6>(6 * n);
    if (fn.isZero(0.0)) continue;
    for (int i : chain_[n]) r[i] += (tw[i].v + tw[i].w.cross(s.x[n])).dot(fn.head<3>()) + tw[i].w.dot(fn.tail<3>());
  }
  for (int k = 6 * nn; k < map_.raw_size(); ++k) r[raw_to_gen_[k]] += f[k];
  return r;
}

Vec6 NonlinearStructure::node_displacement(const NonlinearState& s, int n) const {
  Vec6 d;
  d << s.x[n] - model_->nodes[n].x, log_so3(s.R[n]);
  return d;
}

Vec3 NonlinearStructure::beam_shape(const NonlinearState& s, int e, double xi) const {
  const auto& el = model_->elements[e];
  const int a = el.nodes[0], b = el.nodes[1];
  const Vec3 X = (1.0 - xi) * model_->nodes[a].x + xi * model_->nodes[b].x;
  if (!beams_[e]) return (1.0 - xi) * s.x[a] + xi * s.x[b] - X;
  return beams_[e]->displacement_at({s.x[a], s.x[b], s.R[a], s.R[b]}, xi);
}

}  // namespace beamfea
