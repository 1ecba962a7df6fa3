#include "io/model_check.hpp"

#include <algorithm>
#include <string_view>

#include "core/errors.hpp"
#include "io/json_util.hpp"
#include "solvers/element_factory.hpp"

namespace beamfea {

using json_in::child;

namespace {

// The index of the first support entry that fixes `comp` of `node`, or -1.
int support_fixing(const Model& m, int node, int comp) {
  for (std::size_t s = 0; s < m.supports.size(); ++s)
    if (m.supports[s].node == node && m.supports[s].fixed[comp] && !m.supports[s].skewed) return static_cast<int>(s);
  return -1;
}

}  // namespace

void check_model(const Model& m, const nlohmann::json&) {
  // What carries a load: a member, or a joint with stiffness (a node on springs). Rigid links,
  // passive joints, ties and constraints only carry a load over to something that does.
  const bool springs = std::any_of(m.joints.begin(), m.joints.end(), [](const Joint& j) { return j.has_stiffness(); });
  if (m.members.empty() && !springs)
    throw InputError("/elements", "the model has no elements and no joint with stiffness: nothing carries a load");
  // End releases that leave a member's end segment a mechanism (rx at both ends, ...), offsets
  // that turn the flexible part along its orientation vector: the element says so when made
  // (solvers/element_factory.hpp).
  for (std::size_t i = 0; i < m.members.size(); ++i)
    for (const int e : m.members[i].elements) {
      if (!is_transformed(m.elements[e])) continue;
      try {
        make_frame_element(m, e, Kinematics::Linear);
      } catch (const ModelError& err) {
        const bool releases = std::string_view(err.what()).find("end releases") != std::string_view::npos;
        throw InputError(releases ? child(child("/elements", i), "releases") : child("/elements", i), err.what());
      }
    }
  // A support fixes a DOF at 0; a prescribed value on the same DOF must agree.
  for (std::size_t i = 0; i < m.prescribed.size(); ++i) {
    const auto& p = m.prescribed[i];
    if (p.dof.owner != DofRef::Owner::Node) continue;
    const int s = support_fixing(m, p.dof.index, p.dof.comp);
    if (s >= 0 && p.value != 0.0)
      throw InputError(child("/prescribed", i), m.describe(p.dof) + ": prescribed " + json_in::json(p.value).dump() +
                                                    " but the support at " + child("/supports", s).str() +
                                                    " fixes it at 0; give one of them");
  }
  // A prescribed joint motion moves the coordinate from the pose (the reference geometry without one)
  // by its value: where the joint has limits, the coordinate it reaches must lie within them.
  for (std::size_t i = 0; i < m.prescribed.size(); ++i) {
    const auto& p = m.prescribed[i];
    if (p.dof.owner != DofRef::Owner::Joint) continue;
    const Joint& j = m.joints[p.dof.index];
    if (static_cast<std::size_t>(p.dof.comp) >= j.limits.size()) continue;
    const auto& posed = m.pose.solved;
    const bool from_pose = m.pose.given && static_cast<std::size_t>(p.dof.index) < posed.size() &&
                           p.dof.comp < posed[p.dof.index].size();
    const double start = from_pose ? posed[p.dof.index][p.dof.comp] : 0.0;
    const double reached = start + p.value;
    const auto [lo, hi] = j.limits[p.dof.comp];
    if (reached < lo || reached > hi)
      throw InputError(child(child("/prescribed", i), "value"),
                       m.describe(p.dof) + ": prescribed " + json_in::json(p.value).dump() +
                           (from_pose ? " from the pose's " + json_in::json(start).dump() : std::string()) +
                           " reaches " + json_in::json(reached).dump() + ", outside the joint's limits [" +
                           json_in::json(lo).dump() + ", " + json_in::json(hi).dump() + "]");
  }
  // Supports and prescribed values on one rigid body must agree (DofMap finds the redundant ones).
  // Supports hold at 0: when every prescribed value is 0 as well, all agree whatever the rows, and
  // the map (a third of the check of a small model) is not built.
  const bool all_zero = std::all_of(m.prescribed.begin(), m.prescribed.end(), [](const auto& p) { return p.value == 0.0; });
  // Skewed supports, ties and linear constraints: the map refuses a redundant or contradictory one,
  // naming it (/supports/<i>, /ties/<i>, /constraints/<i>).
  const bool user_rows = !m.ties.empty() || !m.constraints.empty() ||
                         std::any_of(m.supports.begin(), m.supports.end(), [](const Support& s) { return s.skewed; });
  if (all_zero && !user_rows) return;
  const DofMap map(m);
  if (all_zero) return;
  if (std::string conflict = map.check_consistency(map.prescribed_values()); !conflict.empty())
    throw InputError("/prescribed", conflict);
}

std::string why_held(const Model& m, const DofMap& map, int node, int comp) {
  const int raw = map.raw_node(node, comp);
  if (const int p = map.prescribed_index(raw); p >= 0) {
    if (map.prescribed()[p].support) {
      const int s = support_fixing(m, node, comp);
      return "is supported" + (s >= 0 ? " (" + child("/supports", s).str() + ")" : std::string());
    }
    for (std::size_t i = 0; i < m.prescribed.size(); ++i)
      if (m.prescribed[i].dof == DofRef{DofRef::Owner::Node, node, comp})
        return "is prescribed (" + child("/prescribed", i).str() + ")";
    return "is prescribed";
  }
  bool moves = false;
  for (SparseRowMatrix::InnerIterator it(map.T_free(), raw); it; ++it) moves = moves || it.value() != 0.0;
  if (moves) return "";
  if (map.is_slave(node)) {
    // Name the link or joint that carries this node's motion over from its parent.
    for (const auto& e : map.tree_edges()) {
      if (e.child != node) continue;
      const std::string what = e.kind == ConstraintEdge::Kind::Rigid ? "rigid link '" + m.elements[e.index].id + "'"
                                                                     : "joint '" + m.joints[e.index].id + "'";
      return "is held by " + what + " to node '" + m.nodes[e.parent].id + "', which cannot move this way";
    }
  }
  return "is held by constraints (rigid links or joints to supported nodes)";
}

}  // namespace beamfea
