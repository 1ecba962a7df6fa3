#include "io/lump.hpp"

#include <algorithm>
#include <set>

#include "core/errors.hpp"
#include "io/json_util.hpp"
#include "io/model_reader.hpp"
#include "io/analysis.hpp"
#include "io/model_check.hpp"
#include "solvers/condensed_stiffness.hpp"
#include "solvers/superelement.hpp"

namespace beamfea {

namespace {

using json = nlohmann::json;
using json_in::child;

struct Link {
  std::string id;
  std::vector<int> members;
  int base = -1, tip = -1;
  std::vector<char> node_in;   // per node of the beam model: a node of the link's elements
  Mat6 K = Mat6::Zero();
};

Link read_link(const Model& beam, const json& v, const json_in::Pointer& p, std::vector<int>& member_link, int index) {
  const auto& o = json_in::object(v, p, "link");
  const json_in::Fields f(o, p, {"id", "elements", "base", "tip"});
  Link link;
  link.id = json_in::id(f.require("id", "link"), child(p, "id"), "link");
  const std::string what = "link '" + link.id + "'";
  const json_in::Pointer ep = child(p, "elements");
  const auto& elements = json_in::array(f.require("elements", what), ep, json_in::What(what, " elements"));
  if (elements.empty()) throw InputError(ep, what + ": no elements");
  link.node_in.assign(beam.nodes.size(), 0);
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const std::string id = json_in::id(elements[k], child(ep, k), json_in::What(what, " element"));
    const int mi = beam.find_member(id);
    if (mi < 0) throw InputError(child(ep, k), what + ": unknown element '" + id + "'");
    if (member_link[mi] >= 0)
      throw InputError(child(ep, k), what + ": element '" + id + "' is already in link " +
                                         (member_link[mi] == index ? "this link" : "/links/" + std::to_string(member_link[mi])));
    member_link[mi] = index;
    link.members.push_back(mi);
    for (const int e : beam.members[mi].elements)
      for (const int n : beam.elements[e].nodes) link.node_in[n] = 1;
  }
  const char* names[2] = {"base", "tip"};
  int* ends[2] = {&link.base, &link.tip};
  for (int k = 0; k < 2; ++k) {
    const json_in::Pointer np = child(p, names[k]);
    *ends[k] = node_ref(beam, f.require(names[k], what), np);
    if (!link.node_in[*ends[k]])
      throw InputError(np, what + ": node '" + beam.nodes[*ends[k]].id + "' is not a node of the link's elements");
  }
  if (link.base == link.tip) throw InputError(child(p, "tip"), what + ": base and tip are one node");
  return link;
}

// The link's condensed tip stiffness, clamped at its base.
void condense_link(const Model& beam, Link& link, const json_in::Pointer& p) {
  std::vector<int> node_of;
  Model sub = sub_model(beam, link.members, node_of);
  const int base = node_of[link.base], tip = node_of[link.tip];
  std::erase_if(sub.supports, [&](const Support& s) { return s.node == base; });
  Support clamp;
  clamp.node = base;
  clamp.fixed.fill(true);
  sub.supports.push_back(clamp);
  const CondensedStiffness c = linear_node_stiffness(sub, tip);
  if (!c.ok || c.rank < 6 || !c.rigid_directions.empty())
    throw InputError(p, "link '" + link.id + "': clamped at '" + beam.nodes[link.base].id + "' it gives node '" +
                            beam.nodes[link.tip].id + "' a stiffness of rank " + std::to_string(c.rank) +
                            " (a link must resist all six motions of its tip)" + (c.message.empty() ? "" : ": " + c.message));
  link.K = 0.5 * (c.K + c.K.transpose());
}

// The link that has node n inside it (a node of its elements other than its base and tip), or -1.
std::vector<int> interior_links(const Model& beam, const std::vector<Link>& links) {
  std::vector<int> owner(beam.nodes.size(), -1);
  for (std::size_t l = 0; l < links.size(); ++l)
    for (std::size_t n = 0; n < beam.nodes.size(); ++n)
      if (links[l].node_in[n] && static_cast<int>(n) != links[l].base && static_cast<int>(n) != links[l].tip)
        owner[n] = static_cast<int>(l);
  return owner;
}

// Everything kept that names a node inside a link is bad input.
void check_kept_references(const Model& beam, const std::vector<Link>& links, const std::vector<int>& member_link,
                           const std::vector<char>& absorbed_joint) {
  const std::vector<int> inside = interior_links(beam, links);
  auto check = [&](int node, const std::string& by) {
    const int l = inside[node];
    if (l < 0) return;
    throw InputError(child(child("/links", static_cast<std::size_t>(l)), "elements"),
                     "link '" + links[l].id + "': node '" + beam.nodes[node].id + "' is inside the link, but " + by +
                         " names it (a lumped model keeps only the links' base and tip nodes)");
  };
  for (std::size_t l = 0; l < links.size(); ++l)
    for (std::size_t n = 0; n < beam.nodes.size(); ++n)
      if (links[l].node_in[n] && inside[n] >= 0 && inside[n] != static_cast<int>(l))
        check(static_cast<int>(n), "link '" + links[l].id + "'");
  for (std::size_t e = 0; e < beam.elements.size(); ++e) {
    const Element& el = beam.elements[e];
    if (el.member >= 0 && member_link[el.member] >= 0) continue;
    for (const int n : el.nodes) check(n, "element '" + (el.member >= 0 ? beam.members[el.member].id : el.id) + "'");
  }
  for (std::size_t j = 0; j < beam.joints.size(); ++j)
    if (!absorbed_joint[j])
      for (const int n : beam.joints[j].nodes) check(n, "joint '" + beam.joints[j].id + "'");
  for (const auto& s : beam.supports) check(s.node, "a support");
  for (const auto& m : beam.masses) check(m.node, "a point mass");
  for (const auto& t : beam.ties) check(t.nodes[0], "a tie"), check(t.nodes[1], "a tie");
  for (const auto& c : beam.constraints)
    for (const auto& term : c.terms)
      if (term.dof.owner == DofRef::Owner::Node) check(term.dof.index, "a constraint");
  for (const auto& pr : beam.prescribed)
    if (pr.dof.owner == DofRef::Owner::Node) check(pr.dof.index, "a prescribed DOF");
    else if (absorbed_joint[pr.dof.index]) check(beam.joints[pr.dof.index].nodes[0], "a prescribed DOF of joint '" + beam.joints[pr.dof.index].id + "'");
  auto check_loads = [&](const LoadSet& loads, const std::string& where) {
    for (const auto& l : loads.nodal) check(l.node, "a load" + where);
    for (const auto& l : loads.joint)
      if (absorbed_joint[l.joint]) check(beam.joints[l.joint].nodes[0], "a load" + where + " on joint '" + beam.joints[l.joint].id + "'");
    for (const auto& l : loads.member)
      if (member_link[l.member] >= 0)
        throw InputError(child(child("/links", static_cast<std::size_t>(member_link[l.member])), "elements"),
                         "link '" + links[member_link[l.member]].id + "': element '" + beam.members[l.member].id +
                             "' carries a member load" + where + " (a lumped model has no beams to carry it)");
  };
  check_loads(beam.default_case, "");
  for (const auto& c : beam.load_cases) check_loads(c.loads, " of load case '" + c.id + "'");
}

// An id not yet used in the collection `key` of the document.
std::string fresh_id(const json& doc, const char* key, const std::string& id, const json_in::Pointer& p) {
  if (const auto it = doc.find(key); it != doc.end() && it->is_array())
    for (const auto& item : *it)
      if (item.is_object() && item.contains("id") && item["id"] == id)
        throw InputError(p, "the generated id '" + id + "' is already used in \"" + key + "\" (rename the link)");
  return id;
}

}  // namespace

namespace {
// A model document read and checked as `beamfea check` does, its analyses (when it has any) too.
Model checked_model(const json& doc) {
  Model m = read_model(doc);
  check_model(m, doc);
  if (doc.is_object() && doc.contains("analyses")) check_analyses(m, doc);
  return m;
}
}  // namespace

json lump_model(const json& model_doc, const json& links_doc) {
  const Model beam = checked_model(model_doc);
  json_in::expect_keys(links_doc, "", {"links"});
  if (!links_doc.is_object()) throw InputError("", "the links file must be a JSON object {\"links\": [...]}");
  const auto& arr = json_in::array(json_in::require(links_doc, "", "links", "links file"), child("", "links"), "links");
  if (arr.empty()) throw InputError("/links", "no links");
  std::vector<Link> links;
  std::vector<int> member_link(beam.members.size(), -1);
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const json_in::Pointer p = child("/links", i);
    links.push_back(read_link(beam, arr[i], p, member_link, static_cast<int>(i)));
    for (std::size_t k = 0; k < i; ++k)
      if (links[k].id == links.back().id) throw InputError(child(p, "id"), "duplicate link id '" + links.back().id + "'");
  }
  // Joints whose two nodes are nodes of one link belong to it.
  std::vector<char> absorbed(beam.joints.size(), 0);
  for (std::size_t j = 0; j < beam.joints.size(); ++j)
    for (const auto& l : links)
      if (l.node_in[beam.joints[j].nodes[0]] && l.node_in[beam.joints[j].nodes[1]]) absorbed[j] = 1;
  check_kept_references(beam, links, member_link, absorbed);
  for (std::size_t i = 0; i < links.size(); ++i) condense_link(beam, links[i], child("/links", i));

  // The lumped document: the beam model's, without the links' elements, inner nodes and joints.
  const std::vector<int> inside = interior_links(beam, links);
  json out = model_doc;
  auto keep_if = [&](const char* key, auto&& keep) {
    const auto it = out.find(key);
    if (it == out.end() || !it->is_array()) return;
    json kept = json::array();
    for (auto& item : *it)
      if (keep(item)) kept.push_back(std::move(item));
    *it = std::move(kept);
  };
  keep_if("nodes", [&](const json& n) {
    const int k = beam.find_node(n.at("id").is_string() ? n.at("id").get<std::string>() : n.at("id").dump());
    return k < 0 || inside[k] < 0;
  });
  keep_if("elements", [&](const json& e) {
    const int k = beam.find_member(e.at("id").is_string() ? e.at("id").get<std::string>() : e.at("id").dump());
    return k < 0 || member_link[k] < 0;
  });
  keep_if("joints", [&](const json& j) {
    const int k = beam.find_joint(j.at("id").is_string() ? j.at("id").get<std::string>() : j.at("id").dump());
    return k < 0 || !absorbed[k];
  });
  for (const char* key : {"nodes", "elements", "joints"})
    if (!out.contains(key)) out[key] = json::array();
  for (std::size_t i = 0; i < links.size(); ++i) {
    const Link& l = links[i];
    const json_in::Pointer p = child(child("/links", i), "id");
    const std::string node = fresh_id(model_doc, "nodes", l.id + "_spring", p);
    const std::string rigid = fresh_id(model_doc, "elements", l.id + "_rigid", p);
    const std::string spring = fresh_id(model_doc, "joints", l.id + "_spring", p);
    const Vec3& x = beam.nodes[l.tip].x;
    out["nodes"].push_back({{"id", node}, {"xyz", {x.x(), x.y(), x.z()}}});
    out["elements"].push_back({{"id", rigid}, {"type", "rigid"}, {"nodes", {beam.nodes[l.base].id, node}}});
    json K = json::array();
    for (int r = 0; r < 6; ++r) K.push_back({l.K(r, 0), l.K(r, 1), l.K(r, 2), l.K(r, 3), l.K(r, 4), l.K(r, 5)});
    out["joints"].push_back({{"id", spring}, {"type", "virtual_spring"}, {"nodes", {node, beam.nodes[l.tip].id}}, {"stiffness", K}});
  }
  try {
    checked_model(out);
  } catch (const InputError& e) {
    throw InputError("", std::string("the lumped model is not valid: ") + e.what());
  }
  return out;
}

}  // namespace beamfea
