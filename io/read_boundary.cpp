// Model reader, part 4: supports, loads, prescribed values.
#include <map>

#include "core/errors.hpp"
#include "io/json_util.hpp"
#include "io/load_reader.hpp"
#include "io/model_reader.hpp"
#include "io/model_reader_parts.hpp"

namespace beamfea::reader {

using namespace json_in;

void read_supports(ReadState& s) {
  Model& m = s.model;
  const auto& arr = collection(s.doc, "supports", false);
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const json_in::Pointer p = child("/supports", i);
    const auto& o = object(arr[i], p, "support");
    const Fields f(o, p, {"node", "fix"});
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
    m.supports.push_back(sup);
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
