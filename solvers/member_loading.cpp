#include "solvers/member_loading.hpp"

#include <algorithm>
#include <cmath>

#include "elements/beam.hpp"
#include "elements/corotational_beam.hpp"
#include "solvers/element_factory.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

namespace {

// Positions closer than this fraction of a member's length are the same station.
constexpr double kSamePosition = 1e-12;
// Section forces that agree to this fraction of their largest component are the same (round-off).
constexpr double kSameForce = 1e-9;

Vec3 self_weight(const Model& m, const Element& el, const Vec3& g) {
  if (el.type != MemberType::Beam) return Vec3::Zero();
  return m.materials[el.material].density * m.sections[el.section].A * g;
}

// Calls f(element index, s0, Le, R) for each segment of a member (s0: distance of its flexible
// start from the member's flexible start; Le and R the segment's flexible part: between its
// nodes unless rigid arms move its ends, core/model.hpp flexible_end).
template <class F>
void for_segments(const Model& m, const Member& mem, F&& f) {
  double s0 = 0.0;
  for (int e : mem.elements) {
    const auto& el = m.elements[e];
    const Vec3 xa = flexible_end(m, el, 0), xb = flexible_end(m, el, 1);
    const double Le = (xb - xa).norm();
    f(e, s0, Le, beam_local_axes(xa, xb, el.orientation));
    s0 += Le;
  }
}

// The length of a member's flexible part (node to node without rigid arms).
double member_length(const Model& m, const Member& mem) {
  return (flexible_end(m, m.elements[mem.elements.back()], 1) - flexible_end(m, m.elements[mem.elements.front()], 0)).norm();
}

// Calls dist(e, Le, R, a, b, q_a, q_b) for the pieces of a distributed member load (local element
// positions, components as given), and point(e, Le, R, a) for a point load.
template <class D, class P>
void split_member_load(const Model& m, const MemberLoad& l, D&& dist, P&& point) {
  const Member& mem = m.members[l.member];
  if (mem.type != MemberType::Beam || l.kind == MemberLoad::Kind::Temperature) return;
  const double L = member_length(m, mem);
  const int nseg = static_cast<int>(mem.elements.size());
  int k = 0;
  for_segments(m, mem, [&](int e, double s0, double Le, const Mat3& R) {
    const bool last = ++k == nseg;
    if (l.kind == MemberLoad::Kind::Distributed) {
      const double A = l.from * L, B = l.to * L;
      const double lo = std::max(A, s0), hi = std::min(B, s0 + Le);
      if (!(hi > lo) || !(B > A)) return;
      auto q = [&](double s) { return l.q_from + (l.q_to - l.q_from) * ((s - A) / (B - A)); };
      dist(e, Le, R, lo - s0, hi - s0, q(lo), q(hi));
    } else {
      const double a = l.at * L;
      const bool inside = a >= s0 - kSamePosition * L && (a < s0 + Le - kSamePosition * L || last);
      if (inside) point(e, Le, R, std::clamp(a - s0, 0.0, Le));
    }
  });
}

}  // namespace

std::vector<ElementLoads> element_loads(const Model& m, const LoadSet& loads) {
  std::vector<ElementLoads> out;
  element_loads(m, loads, out);
  return out;
}

void element_loads(const Model& m, const LoadSet& loads, std::vector<ElementLoads>& out) {
  out.resize(m.elements.size());
  for (auto& e : out) {
    e.distributed.clear();
    e.points.clear();
    e.temperature = Temperature{};
  }
  for (const auto& l : loads.member) {
    if (l.kind == MemberLoad::Kind::Temperature) {
      // The whole member, segment by segment; temperature changes add.
      const Member& mem = m.members[l.member];
      for (const int e : mem.elements) {
        Temperature& t = out[e].temperature;
        t.expansion = m.materials[mem.material].alpha;
        t.uniform += l.uniform;
        t.gradient_y += l.gradient_y;
        t.gradient_z += l.gradient_z;
      }
      continue;
    }
    split_member_load(
        m, l,
        [&](int e, double, const Mat3& R, double a, double b, const Vec3& qa, const Vec3& qb) {
          out[e].distributed.push_back(l.local ? LocalDistributedLoad{a, b, qa, qb} : LocalDistributedLoad{a, b, R * qa, R * qb});
        },
        [&](int e, double, const Mat3& R, double a) {
          out[e].points.push_back(l.local ? LocalPointLoad{a, l.force, l.moment} : LocalPointLoad{a, R * l.force, R * l.moment});
        });
  }
  if (!loads.gravity.isZero(0.0)) {
    for (std::size_t e = 0; e < m.elements.size(); ++e) {
      const auto& el = m.elements[e];
      const Vec3 q = self_weight(m, el, loads.gravity);
      if (q.isZero(0.0)) continue;
      const Vec3 xa = flexible_end(m, el, 0), xb = flexible_end(m, el, 1);  // rigid arms weigh nothing
      const Mat3 R = beam_local_axes(xa, xb, el.orientation);
      out[e].distributed.push_back({0.0, (xb - xa).norm(), R * q, R * q});
    }
  }
}

Eigen::VectorXd external_force(const Model& m, const DofMap& map, const LoadSet& loads) {
  return external_force(m, map, loads, element_loads(m, loads));
}

Eigen::VectorXd external_force(const Model& m, const DofMap& map, const LoadSet& loads, const std::vector<ElementLoads>& el) {
  Eigen::VectorXd f;
  external_force(m, map, loads, el, f);
  return f;
}

void external_force(const Model& m, const DofMap& map, const LoadSet& loads, const std::vector<ElementLoads>& el,
                    Eigen::VectorXd& f) {
  f.setZero(map.raw_size());
  for (const auto& l : loads.nodal) {
    f.segment<3>(map.raw_node(l.node, 0)) += l.force;
    f.segment<3>(map.raw_node(l.node, 3)) += l.moment;
  }
  for (const auto& l : loads.joint) f[map.raw_joint(l.joint, l.coordinate)] += l.value;
  for (std::size_t e = 0; e < m.elements.size(); ++e) {
    if (el[e].empty()) continue;
    const auto& E = m.elements[e];
    const Vec3 xa = flexible_end(m, E, 0), xb = flexible_end(m, E, 1);
    const Mat3 R = beam_local_axes(xa, xb, E.orientation);
    // A wrapped element (end releases, rigid arms) carries its loads to the nodes (temperature
    // included: the element's equivalent_loads); a plain beam's are the span's and its thermal loads.
    Vec12 fl;
    if (is_transformed(E)) {
      fl = make_frame_element(m, static_cast<int>(e), Kinematics::Linear)->equivalent_loads(el[e]);
    } else {
      fl = equivalent_nodal_loads((xb - xa).norm(), el[e]);
      if (el[e].has_temperature()) fl += beam_thermal_loads(beam_section(m, E), el[e].temperature);
    }
    const Vec12 fe = beam_transformation(R).transpose() * fl;
    f.segment<6>(map.raw_node(E.nodes[0], 0)) += fe.head<6>();
    f.segment<6>(map.raw_node(E.nodes[1], 0)) += fe.tail<6>();
  }
  for (const auto& pm : m.masses) f.segment<3>(map.raw_node(pm.node, 0)) += pm.mass * loads.gravity;
}

std::vector<std::vector<DeadLoadTerm>> element_dead_loads(const Model& m, const LoadSet& loads) {
  std::vector<std::vector<DeadLoadTerm>> out(m.elements.size());
  auto append = [](std::vector<DeadLoadTerm>& to, const std::vector<DeadLoadTerm>& t) { to.insert(to.end(), t.begin(), t.end()); };
  for (const auto& l : loads.member) {
    // Local components are turned to global with the reference axes: the direction stays fixed.
    split_member_load(
        m, l,
        [&](int e, double Le, const Mat3& R, double a, double b, const Vec3& qa, const Vec3& qb) {
          append(out[e], l.local ? dead_load_terms(Le, a, b, R.transpose() * qa, R.transpose() * qb)
                                 : dead_load_terms(Le, a, b, qa, qb));
        },
        [&](int e, double Le, const Mat3& R, double a) {
          append(out[e], l.local ? dead_load_terms(Le, a, R.transpose() * l.force, R.transpose() * l.moment)
                                 : dead_load_terms(Le, a, l.force, l.moment));
        });
  }
  if (!loads.gravity.isZero(0.0))
    for (std::size_t e = 0; e < m.elements.size(); ++e) {
      const Vec3 q = self_weight(m, m.elements[e], loads.gravity);
      if (q.isZero(0.0)) continue;
      const double Le = (flexible_end(m, m.elements[e], 1) - flexible_end(m, m.elements[e], 0)).norm();
      append(out[e], dead_load_terms(Le, 0.0, Le, q, q));
    }
  return out;
}

std::vector<Vec12> corotated_fixed_end_forces(const Model& model, const LoadSet& loads, const std::vector<Vec3>& x,
                                              const std::vector<Mat3>& R, double factor) {
  std::vector<Vec12> out(model.elements.size(), Vec12::Zero());
  if (factor == 0.0) return out;
  const std::vector<ElementLoads> ref = element_loads(model, loads);  // reference local axes
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const auto& el = model.elements[e];
    if (el.type != MemberType::Beam || ref[e].empty()) continue;
    const int a = el.nodes[0], b = el.nodes[1];
    const auto beam = make_frame_element(model, static_cast<int>(e), Kinematics::Corotational);
    out[e] = factor * beam->fixed_end_forces_at({x[a], x[b], R[a], R[b]}, ref[e]);
  }
  return out;
}

std::vector<Station> member_stations(const Model& m, int member, const std::vector<Vec12>& end_forces,
                                     const std::vector<ElementLoads>& loads, int interior) {
  std::vector<Station> out;
  std::vector<double> xs;
  member_stations(m, member, end_forces, loads, interior, out, xs);
  return out;
}

void member_stations(const Model& m, int member, const std::vector<Vec12>& end_forces,
                     const std::vector<ElementLoads>& loads, int interior, std::vector<Station>& out,
                     std::vector<double>& xs) {
  const Member& mem = m.members[member];
  out.clear();
  if (mem.type != MemberType::Beam) return;
  const double L = member_length(m, mem);
  const double tol = kSamePosition * L;
  for_segments(m, mem, [&](int e, double s0, double Le, const Mat3&) {
    const ElementLoads& el = loads[e];
    xs.assign({0.0, Le});
    for (double x : load_discontinuities(Le, el)) xs.push_back(x);
    for (int k = 1; k <= interior; ++k) {
      const double x = L * k / (interior + 1.0) - s0;
      if (x > tol && x < Le - tol) xs.push_back(x);
    }
    std::sort(xs.begin(), xs.end());
    xs.erase(std::unique(xs.begin(), xs.end(), [&](double a, double b) { return std::abs(a - b) <= tol; }), xs.end());
    for (double x : xs) {
      const bool jump = x > tol && x < Le - tol && std::any_of(el.points.begin(), el.points.end(), [&](const LocalPointLoad& p) {
        return std::abs(p.a - x) <= tol;
      });
      if (jump) out.push_back({s0 + x, section_forces_at(x, end_forces[e], el, CutSide::Before)});
      Station st{s0 + x, section_forces_at(x, end_forces[e], el, CutSide::After)};
      // A segment's end coincides with the next segment's start: one station there unless a load
      // at that node makes a jump.
      if (!out.empty() && std::abs(out.back().x - st.x) <= tol &&
          (out.back().forces - st.forces).cwiseAbs().maxCoeff() <= kSameForce * st.forces.cwiseAbs().maxCoeff())
        continue;
      out.push_back(st);
    }
  });
}

}  // namespace beamfea
