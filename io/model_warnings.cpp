#include "io/model_warnings.hpp"

#include <algorithm>
#include <array>

namespace beamfea {

namespace {

// "'a', 'b', 'c'" for the ids of `items` at the positions where `flag` is 0, kMaxIdsPerWarning at
// most ("... and N more"); the count of such items in `count`.
template <class Items>
std::string unflagged_ids(const Items& items, const std::vector<char>& flag, std::size_t& count) {
  std::string s;
  count = 0;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (flag[i]) continue;
    if (count < kMaxIdsPerWarning) s += (count ? ", '" : "'") + items[i].id + "'";
    ++count;
  }
  if (count > kMaxIdsPerWarning) s += " and " + std::to_string(count - kMaxIdsPerWarning) + " more";
  return s;
}

void warn_unused(std::vector<std::string>& out, const char* what, const std::string& ids, std::size_t count) {
  if (count == 0) return;
  out.push_back(std::string(what) + (count == 1 ? " " : "s ") + ids + (count == 1 ? " is" : " are") +
                " defined and never used by a member");
}

void loads_on_supported_nodes(std::vector<std::string>& out, const Model& m, const std::vector<char>& all_supported,
                              const std::string& case_id, const LoadSet& loads) {
  std::vector<char> named(m.nodes.size(), 0);
  std::string ids;
  std::size_t count = 0;
  for (const NodalLoad& l : loads.nodal) {
    if (l.node < 0 || !all_supported[l.node] || named[l.node]) continue;
    if (l.force.isZero(0.0) && l.moment.isZero(0.0)) continue;
    named[l.node] = 1;
    if (count < kMaxIdsPerWarning) ids += (count ? ", '" : "'") + m.nodes[l.node].id + "'";
    ++count;
  }
  if (count == 0) return;
  if (count > kMaxIdsPerWarning) ids += " and " + std::to_string(count - kMaxIdsPerWarning) + " more";
  out.push_back("load case '" + case_id + "': a load on node" + (count == 1 ? " " : "s ") + ids +
                ", whose every DOF is supported: it goes straight into the reactions and loads no member");
}

}  // namespace

std::vector<std::string> model_warnings(const Model& m) {
  std::vector<std::string> out;
  std::vector<char> material_used(m.materials.size(), 0), section_used(m.sections.size(), 0);
  std::vector<char> connected(m.nodes.size(), 0);
  for (const Element& e : m.elements) {
    if (e.material >= 0) material_used[e.material] = 1;
    if (e.section >= 0) section_used[e.section] = 1;
    connected[e.nodes[0]] = connected[e.nodes[1]] = 1;
  }
  for (const Joint& j : m.joints) connected[j.nodes[0]] = connected[j.nodes[1]] = 1;
  for (const Tie& t : m.ties) connected[t.nodes[0]] = connected[t.nodes[1]] = 1;
  for (const LinearConstraint& c : m.constraints) {
    // A constraint connects the nodes it names when it names more than one.
    int first = -1;
    bool several = false;
    for (const ConstraintTerm& t : c.terms)
      if (t.dof.owner == DofRef::Owner::Node) {
        if (first < 0) first = t.dof.index;
        else if (t.dof.index != first) several = true;
      }
    if (several)
      for (const ConstraintTerm& t : c.terms)
        if (t.dof.owner == DofRef::Owner::Node) connected[t.dof.index] = 1;
  }
  std::size_t count = 0;
  std::string ids = unflagged_ids(m.materials, material_used, count);
  warn_unused(out, "material", ids, count);
  ids = unflagged_ids(m.sections, section_used, count);
  warn_unused(out, "section", ids, count);
  ids = unflagged_ids(m.nodes, connected, count);
  if (count)
    out.push_back((count == 1 ? "node " : "nodes ") + ids + (count == 1 ? " is" : " are") +
                  " connected to nothing (no member, joint, tie or constraint)");

  // Every DOF of a node held by a support (the six of a skewed one are six independent
  // directions too) or prescribed.
  std::vector<std::array<bool, 6>> held(m.nodes.size(), std::array<bool, 6>{});
  for (const Support& s : m.supports)
    for (int k = 0; k < 6; ++k) held[s.node][k] = held[s.node][k] || s.fixed[k];
  for (const Prescribed& p : m.prescribed)
    if (p.dof.owner == DofRef::Owner::Node) held[p.dof.index][p.dof.comp] = true;
  std::vector<char> all_supported(m.nodes.size(), 0);
  for (std::size_t n = 0; n < m.nodes.size(); ++n)
    all_supported[n] = std::all_of(held[n].begin(), held[n].end(), [](bool b) { return b; });
  loads_on_supported_nodes(out, m, all_supported, kDefaultLoadCase, m.default_loads());
  for (const LoadCase& c : m.load_cases) loads_on_supported_nodes(out, m, all_supported, c.id, c.loads);
  return out;
}

}  // namespace beamfea
