// Analyses "linear_static" and "stiffness".
#include <fmt/format.h>

#include "core/errors.hpp"
#include "io/analysis.hpp"
#include "io/json_util.hpp"
#include "io/model_check.hpp"
#include "io/model_reader.hpp"
#include "io/vtk_writer.hpp"
#include "solvers/condensed_stiffness.hpp"
#include "solvers/linear_static.hpp"

namespace beamfea {

namespace {

ojson mechanism_json(const Model& model, const std::vector<ZeroEnergyMode>& modes) {
  ojson out = ojson::array();
  for (const auto& m : modes) {
    ojson o;
    o["description"] = m.description;
    ojson nodes = ojson::array(), elements = ojson::array(), joints = ojson::array(), dofs = ojson::array();
    for (int n : m.nodes) nodes.push_back(model.nodes[n].id);
    for (int e : m.elements) elements.push_back(model.elements[e].id);
    for (int j : m.joints) joints.push_back(model.joints[j].id);
    for (const auto& d : m.dofs) dofs.push_back(model.describe(d));
    o["nodes"] = nodes;
    o["elements"] = elements;
    o["joints"] = joints;
    o["dofs"] = dofs;
    out.push_back(o);
  }
  return out;
}

// Member-level output: a member meshed into several elements reports the forces at its own
// ends (first element's end 1, last element's end 2).
ojson element_json(const Model& model, const std::vector<Vec12>& end_forces) {
  ojson out = ojson::object();
  for (const auto& mem : model.members) {
    const Vec12& first = end_forces[mem.elements.front()];
    const Vec12& last = end_forces[mem.elements.back()];
    Vec12 ends;
    ends << first.head<6>(), last.tail<6>();
    const Vec12 s = section_forces(ends);
    ojson o;
    o["end_forces"] = ojson::array({to_json(Vec6(ends.head<6>())), to_json(Vec6(ends.tail<6>()))});
    o["section_forces"] = ojson::array({to_json(Vec6(s.head<6>())), to_json(Vec6(s.tail<6>()))});
    if (mem.elements.size() > 1) {
      ojson segs = ojson::array();
      for (int e : mem.elements) {
        const Vec12& f = end_forces[e];
        segs.push_back(ojson{{"id", model.elements[e].id},
                             {"end_forces", ojson::array({to_json(Vec6(f.head<6>())), to_json(Vec6(f.tail<6>()))})}});
      }
      o["segments"] = segs;
    }
    out[mem.id] = o;
  }
  return out;
}

void check_linear_static(const Model&, const nlohmann::json& spec, const std::string& p) {
  json_in::expect_keys(spec, p, {"id", "type", "description"});
}

AnalysisOutcome run_linear_static(const AnalysisContext& ctx) {
  const Model& model = ctx.model;
  AnalysisOutcome out;
  const LinearStaticResult r = solve_linear_static(model);
  out.result["type"] = "linear_static";
  out.result["status"] = r.status == SolveStatus::Converged ? "ok" : to_string(r.status);
  out.result["message"] = r.message;
  out.result["free_dofs"] = r.free_dofs;
  out.message = r.message;
  if (r.status != SolveStatus::Converged) {
    out.termination = r.status == SolveStatus::Mechanism ? AnalysisTermination::Mechanism : AnalysisTermination::Failed;
    out.result["mechanism"] = mechanism_json(model, r.modes);
    return out;
  }
  ojson nodes = ojson::object();
  for (std::size_t n = 0; n < model.nodes.size(); ++n) {
    ojson o;
    o["displacement"] = to_json(Vec6(r.u.segment<6>(6 * n)));
    if (r.supported[n]) o["reaction"] = to_json(r.reactions[n]);
    nodes[model.nodes[n].id] = o;
  }
  out.result["nodes"] = nodes;
  out.result["elements"] = element_json(model, r.end_forces);
  ojson joints = ojson::object();
  int offset = 6 * static_cast<int>(model.nodes.size());
  for (std::size_t j = 0; j < model.joints.size(); ++j) {
    const int nc = model.joints[j].coordinates();
    joints[model.joints[j].id] = ojson{{"coordinates", to_json(Eigen::VectorXd(r.u.segment(offset, nc)))},
                                       {"reaction", to_json(r.joint_forces[j])}};
    offset += nc;
  }
  out.result["joints"] = joints;
  out.result["statically_indeterminate"] = r.statically_indeterminate;
  if (!ctx.out_dir.empty() && ctx.write_vtk) {
    VtkFrame f;
    for (std::size_t n = 0; n < model.nodes.size(); ++n) {
      f.displacement.push_back(r.u.segment<3>(6 * n));
      f.rotation.push_back(r.u.segment<3>(6 * n + 3));
    }
    f.end_forces = r.end_forces;
    const std::string file = ctx.id + ".vtu";
    write_vtu((ctx.out_dir / file).string(), model, f);
    out.result["vtk"] = file;
  }
  return out;
}

void check_stiffness(const Model& model, const nlohmann::json& spec, const std::string& p) {
  json_in::expect_keys(spec, p, {"id", "type", "description", "node"});
  node_ref(model, json_in::require(spec, p, "node", "stiffness analysis"), json_in::child(p, "node"));
  // Any node answers (issue 11): where supports, loops or rigid links hold it, its compliance is zero
  // and rigid_directions names the directions (solvers/condensed_stiffness.hpp, node_compliance).
}

AnalysisOutcome run_stiffness(const AnalysisContext& ctx) {
  const Model& model = ctx.model;
  const int node = node_ref(model, ctx.spec.at("node"), json_in::child(ctx.pointer, "node"));
  AnalysisOutcome out;
  const CondensedStiffness k = linear_node_stiffness(model, node);
  out.result["type"] = "stiffness";
  out.result["node"] = model.nodes[node].id;
  out.result["status"] = k.ok ? "ok" : "mechanism";
  out.result["message"] = k.message;
  out.message = k.message;
  if (!k.ok) {
    out.termination = AnalysisTermination::Mechanism;
    out.result["mechanism"] = mechanism_json(model, k.modes);
    return out;
  }
  out.result["matrix"] = to_json(k.K);
  out.result["rank"] = k.rank;
  ojson ns = ojson::array();
  for (const auto& v : k.null_space) ns.push_back(to_json(v));
  out.result["null_space"] = ns;
  out.result["compliance"] = to_json(k.compliance);
  ojson rd = ojson::array();
  for (const auto& v : k.rigid_directions) rd.push_back(to_json(v));
  out.result["rigid_directions"] = rd;
  out.result["statically_indeterminate"] = k.statically_indeterminate;
  out.result["length_scale"] = model.length_scale();
  out.result["scaled_eigenvalues"] = to_json(k.eigenvalues);
  return out;
}

}  // namespace

AnalysisType linear_static_analysis() { return {"linear_static", check_linear_static, run_linear_static}; }
AnalysisType stiffness_analysis() { return {"stiffness", check_stiffness, run_stiffness}; }

}  // namespace beamfea
