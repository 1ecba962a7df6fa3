// Analysis "superelement": the stiffness and mass of a structure reduced onto interface nodes
// (Guyan), optionally with fixed-interface modes (Craig-Bampton): solvers/superelement.hpp.
//   {"id": "s", "type": "superelement", "interface": ["A", "B"], "elements": ["e1", ...],
//    "modes": 0, "mass": "consistent" | "lumped"}
// Result analyses.<id>: type, status, message, interface (node ids), elements (when given),
// free_dofs, dofs (the reduced coordinates' names), stiffness and mass ((6n + m) square; mass only
// when the structure has mass), frequencies (Hz, fixed-interface modes), rigid_body_modes (vectors
// of the reduced size), held_dofs, files. Files DIR/<id>_superelement.json (this object) and
// DIR/<id>_superelement.npz (arrays stiffness, mass).
#include <set>

#include "core/errors.hpp"
#include "io/analysis.hpp"
#include "io/atomic_file.hpp"
#include "io/json_util.hpp"
#include "io/model_reader.hpp"
#include "io/npz_writer.hpp"
#include "io/result_status.hpp"
#include "solvers/superelement.hpp"

namespace beamfea {

namespace {

struct SuperelementSpec {
  std::vector<int> interface;   // node indices of the model
  std::vector<int> members;     // member indices; empty: the whole model
  bool subset = false;
  SuperelementOptions options;
};

SuperelementSpec check_superelement(const Model& model, const nlohmann::json& spec, const json_in::Pointer& p) {
  SuperelementSpec s;
  json_in::expect_keys(spec, p, {"id", "type", "description", "interface", "elements", "modes", "mass"});
  const json_in::Pointer ip = json_in::child(p, "interface");
  const auto& interface = json_in::array(json_in::require(spec, p, "interface", "superelement"), ip, "superelement interface");
  if (interface.empty()) throw InputError(ip, "superelement: the interface needs at least one node");
  for (std::size_t k = 0; k < interface.size(); ++k) {
    const int n = node_ref(model, interface[k], json_in::child(ip, k));
    if (std::find(s.interface.begin(), s.interface.end(), n) != s.interface.end())
      throw InputError(json_in::child(ip, k), "superelement: node '" + model.nodes[n].id + "' is twice in the interface");
    s.interface.push_back(n);
  }
  std::vector<char> node_in(model.nodes.size(), 0);
  if (const nlohmann::json* elements = json_in::field(spec, "elements")) {
    s.subset = true;
    const json_in::Pointer ep = json_in::child(p, "elements");
    const auto& arr = json_in::array(*elements, ep, "superelement elements");
    if (arr.empty()) throw InputError(ep, "superelement: the element list is empty (leave it out for the whole model)");
    for (std::size_t k = 0; k < arr.size(); ++k) {
      const std::string id = json_in::id(arr[k], json_in::child(ep, k), "superelement element");
      const int mi = model.find_member(id);
      if (mi < 0) throw InputError(json_in::child(ep, k), "superelement: unknown element '" + id + "'");
      if (std::find(s.members.begin(), s.members.end(), mi) != s.members.end())
        throw InputError(json_in::child(ep, k), "superelement: element '" + id + "' is twice in the list");
      s.members.push_back(mi);
      for (const int e : model.members[mi].elements)
        for (const int n : model.elements[e].nodes) node_in[n] = 1;
    }
    for (std::size_t k = 0; k < s.interface.size(); ++k)
      if (!node_in[s.interface[k]])
        throw InputError(json_in::child(ip, k), "superelement: interface node '" + model.nodes[s.interface[k]].id +
                                                    "' is not a node of the listed elements");
  }
  if (const nlohmann::json* modes = json_in::field(spec, "modes"))
    s.options.modes = json_in::integer_in(*modes, json_in::child(p, "modes"), "superelement modes", 0, kMaxModes);
  if (const nlohmann::json* mass = json_in::field(spec, "mass"))
    s.options.mass = json_in::mass_kind(*mass, json_in::child(p, "mass"), "superelement mass", "superelement");
  return s;
}

const char* superelement_status(SuperelementStatus s) {
  return s == SuperelementStatus::Succeeded ? "ok" : to_string(s);
}

AnalysisOutcome run_superelement(const AnalysisContext& ctx, const SuperelementSpec& spec) {
  const Model& model = ctx.model;
  std::vector<int> interface = spec.interface;
  std::optional<Model> sub;
  if (spec.subset) {
    std::vector<int> node_of;
    sub.emplace(sub_model(model, spec.members, node_of));
    for (int& n : interface) n = node_of[n];
  }
  const SuperelementResult r = reduce_superelement(sub ? *sub : model, interface, spec.options);
  AnalysisOutcome out;
  out.result = object_with_capacity(16);
  out.result["type"] = "superelement";
  out.result["status"] = superelement_status(r.status);
  out.result["message"] = r.message;
  ojson ids = ojson::array();
  for (const int n : spec.interface) ids.push_back(model.nodes[n].id);
  out.result["interface"] = std::move(ids);
  if (spec.subset) {
    ojson members = ojson::array();
    for (const int m : spec.members) members.push_back(model.members[m].id);
    out.result["elements"] = std::move(members);
  }
  out.result["free_dofs"] = r.free_dofs;
  out.result["modes"] = spec.options.modes;
  out.message = r.message;
  if (r.status != SuperelementStatus::Succeeded) {
    out.termination = r.status == SuperelementStatus::Mechanism ? AnalysisTermination::Mechanism
                      : r.status == SuperelementStatus::Failed  ? AnalysisTermination::NotConverged
                                                                : AnalysisTermination::Failed;
    return out;
  }
  ojson dofs = ojson::array();
  for (const int n : spec.interface)
    for (const char* d : kDofNames) dofs.push_back(model.nodes[n].id + "." + d);
  for (Eigen::Index j = 0; j < r.frequencies.size(); ++j) dofs.push_back("mode" + std::to_string(j + 1));
  out.result["dofs"] = std::move(dofs);
  out.result["stiffness"] = matrix_to_json(r.stiffness);
  if (r.has_mass) out.result["mass"] = matrix_to_json(r.mass);
  out.result["frequencies"] = to_json(r.frequencies);
  ojson rigid = ojson::array();
  for (const auto& v : r.rigid_body_modes) rigid.push_back(to_json(v));
  out.result["rigid_body_modes"] = std::move(rigid);
  ojson held = ojson::array();
  for (const auto& h : r.held_dofs) held.push_back(h);
  out.result["held_dofs"] = std::move(held);
  if (!ctx.out_dir.empty()) {
    out.result["files"] = ojson::array({ctx.id + "_superelement.json", ctx.id + "_superelement.npz"});
    write_text_atomic(ctx.out_dir / (ctx.id + "_superelement.json"), out.result.dump(2) + "\n");
    std::vector<std::pair<std::string, const Eigen::MatrixXd*>> arrays{{"stiffness", &r.stiffness}};
    if (r.has_mass) arrays.emplace_back("mass", &r.mass);
    write_npz(ctx.out_dir / (ctx.id + "_superelement.npz"), arrays);
  }
  return out;
}

}  // namespace

AnalysisType superelement_analysis() {
  return register_analysis<SuperelementSpec>("superelement", check_superelement, run_superelement, [](const std::string& id) {
    return AnalysisFiles{{id + "_superelement.json", id + "_superelement.npz"}, {}};
  });
}

}  // namespace beamfea
