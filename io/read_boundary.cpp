// Model reader, part 4: supports, loads, prescribed values.
#include <algorithm>
#include <cmath>
#include <map>

#include "core/errors.hpp"
#include "io/json_util.hpp"
#include "io/load_reader.hpp"
#include "io/model_reader.hpp"
#include "io/model_reader_parts.hpp"

namespace beamfea::reader {

using namespace json_in;

namespace {

// |A A^T - I| (largest entry) above which a support's axes are not an orthonormal frame: axes the
// user computed elsewhere to 9 or more digits pass, a frame off by a visible angle does not.
constexpr double kOrthonormalTolerance = 1e-6;

// A skewed support's frame: three rows, the frame's axes in global components, orthonormal and
// right-handed.
Mat3 support_axes(const json& v, const json_in::Pointer& p, const What& what) {
  const auto& rows = array(v, p, what);
  if (rows.size() != 3) throw InputError(p, what.str() + ": 'axes' needs three axes (rows), got " + std::to_string(rows.size()));
  Mat3 A;
  for (std::size_t k = 0; k < 3; ++k) A.row(static_cast<Eigen::Index>(k)) = vec3(rows[k], child(p, k), what).transpose();
  const double off = (A * A.transpose() - Mat3::Identity()).cwiseAbs().maxCoeff();
  if (off > kOrthonormalTolerance)
    throw InputError(p, what.str() + ": the axes are not orthonormal (|A A^T - I| = " + json_in::json(off).dump() +
                            "; give three unit vectors at right angles)");
  if (A.determinant() < 0.0) throw InputError(p, what.str() + ": the axes are left-handed (give x, y, z = x cross y)");
  return A;
}

// DOF names (ux ... rz) listed at `v` as a mask.
std::array<bool, 6> dof_mask(const json& v, const json_in::Pointer& p, const What& what, const What& context) {
  std::array<bool, 6> mask{};
  array(v, p, what);
  for (std::size_t k = 0; k < v.size(); ++k) {
    const int d = dof_name(v[k], child(p, k), what, context);
    if (mask[d]) throw InputError(child(p, k), what.str() + ": DOF '" + kDofNames[d] + "' listed twice");
    mask[d] = true;
  }
  return mask;
}

}  // namespace

void read_supports(ReadState& s) {
  Model& m = s.model;
  const auto& arr = collection(s.doc, "supports", false);
  bool any_skewed = false;
  std::vector<int> first_support;  // per node, its first support entry (made at the first skewed one)
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const json_in::Pointer p = child("/supports", i);
    const auto& o = object(arr[i], p, "support");
    const Fields f(o, p, {"node", "fix", "axes"});
    Support sup;
    sup.node = node_ref(m, f.require("node", "support"), child(p, "node"));
    const What what("support at node '", m.nodes[sup.node].id, "'");  // a string only in a message
    const auto& fix = f.require("fix", what);
    if (fix.is_string() && fix.get_ref<const std::string&>() == "all") {
      sup.fixed.fill(true);
    } else {
      array(fix, child(p, "fix"), what);
      for (std::size_t k = 0; k < fix.size(); ++k) {
        sup.fixed[dof_name(fix[k], child(child(p, "fix"), k), what, What("support at node '", m.nodes[sup.node].id, "': "))] = true;
      }
    }
    if (const json* axes = f.get("axes")) {
      sup.skewed = true;
      sup.axes = support_axes(*axes, child(p, "axes"), what);
    }
    // A skewed support is the node's only support entry: its reaction is reported in its axes.
    if (sup.skewed || any_skewed) {
      if (first_support.empty()) {
        first_support.assign(m.nodes.size(), -1);
        for (std::size_t j = 0; j < m.supports.size(); ++j)
          if (first_support[m.supports[j].node] < 0) first_support[m.supports[j].node] = static_cast<int>(j);
      }
      const int j = first_support[sup.node];
      if (j >= 0 && (sup.skewed || m.supports[j].skewed))
        throw InputError(p, what.str() + ": the node has a support already (" + child("/supports", j).str() +
                                ") and one of them has 'axes': give one support per node with axes");
      if (j < 0) first_support[sup.node] = static_cast<int>(m.supports.size());
    }
    any_skewed = any_skewed || sup.skewed;
    m.supports.push_back(sup);
  }
}

void read_ties(ReadState& s) {
  Model& m = s.model;
  const auto& arr = collection(s.doc, "ties", false);
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const json_in::Pointer p = child("/ties", i);
    const auto& o = object(arr[i], p, "tie");
    const Fields f(o, p, {"nodes", "dofs"});
    const auto& nodes = array(f.require("nodes", "tie"), child(p, "nodes"), "tie nodes");
    if (nodes.size() != 2) throw InputError(child(p, "nodes"), "a tie joins two nodes: [a, b] (b's DOFs equal a's)");
    Tie t;
    for (std::size_t k = 0; k < 2; ++k) t.nodes[k] = node_ref(m, nodes[k], child(child(p, "nodes"), k));
    if (t.nodes[0] == t.nodes[1])
      throw InputError(child(p, "nodes"), "a tie joins two different nodes (node '" + m.nodes[t.nodes[0]].id + "' twice)");
    const What what("tie of node '", m.nodes[t.nodes[1]].id, "'");
    t.dofs = dof_mask(f.require("dofs", what), child(p, "dofs"), what, What("tie of node '", m.nodes[t.nodes[1]].id, "': "));
    m.ties.push_back(t);
  }
}

void read_constraints(ReadState& s) {
  Model& m = s.model;
  const auto& arr = collection(s.doc, "constraints", false);
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const json_in::Pointer p = child("/constraints", i);
    const auto& o = object(arr[i], p, "linear constraint");
    const Fields f(o, p, {"terms", "value"});
    const auto& terms = array(f.require("terms", "linear constraint"), child(p, "terms"), "constraint terms");
    if (terms.empty()) throw InputError(child(p, "terms"), "a linear constraint needs at least one term");
    LinearConstraint c;
    for (std::size_t k = 0; k < terms.size(); ++k) {
      const json_in::Pointer pt = child(child(p, "terms"), k);
      const auto& t = object(terms[k], pt, "constraint term");
      const Fields tf(t, pt, {"node", "dof", "coefficient"});
      ConstraintTerm term;
      const int n = node_ref(m, tf.require("node", "constraint term"), child(pt, "node"));
      const int d = dof_name(tf.require("dof", "constraint term"), child(pt, "dof"), "constraint term",
                             What("constraint term at node '", m.nodes[n].id, "': "));
      term.dof = {DofRef::Owner::Node, n, d};
      term.coefficient = number(tf.require("coefficient", "constraint term"), child(pt, "coefficient"), "constraint coefficient");
      c.terms.push_back(term);
    }
    double norm = 0.0;
    for (const auto& t : c.terms) norm = std::max(norm, std::abs(t.coefficient));
    if (norm == 0.0) throw InputError(child(p, "terms"), "a linear constraint needs a nonzero coefficient");
    if (const json* v = f.get("value")) c.value = number(*v, child(p, "value"), "constraint value");
    m.constraints.push_back(std::move(c));
  }
}

void read_loads(ReadState& s) {
  // Nodal, joint and member loads, gravity, masses, load cases and combinations: io/load_reader.cpp.
  read_loads_and_cases(s.doc, s.model);
}

void read_prescribed(ReadState& s) {
  Model& m = s.model;
  const auto& arr = collection(s.doc, "prescribed", false);
  std::map<std::pair<int, int>, std::size_t> seen;  // (owner-coded index, component) -> entry
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const json_in::Pointer p = child("/prescribed", i);
    const auto& o = object(arr[i], p, "prescribed value");
    expect_keys(o, p, {"node", "dof", "joint", "coordinate", "value"});
    // A node DOF (node, dof) or a joint coordinate (joint, coordinate): never a mix of both.
    if (o.contains("joint")) {
      for (const char* key : {"node", "dof"})
        if (o.contains(key))
          throw InputError(child(p, key), std::string("prescribed value: '") + key +
                                              "' beside 'joint': give a joint and its coordinate, or a node and its dof");
    } else if (o.contains("coordinate")) {
      throw InputError(child(p, "coordinate"), "prescribed value: 'coordinate' without 'joint': a node's DOF is given by 'dof'");
    }
    Prescribed pr;
    pr.dof = read_dof_target(m, o, p, "prescribed value");
    pr.value = number(require(o, p, "value", "prescribed " + m.describe(pr.dof)), child(p, "value"), "prescribed value");
    const std::pair<int, int> key{pr.dof.owner == DofRef::Owner::Node ? pr.dof.index : -1 - pr.dof.index, pr.dof.comp};
    if (auto [first, fresh] = seen.emplace(key, i); !fresh)
      throw InputError(p, m.describe(pr.dof) + " is prescribed twice (first at " + child("/prescribed", first->second).str() + ")");
    m.prescribed.push_back(pr);
  }
}

}  // namespace beamfea::reader
