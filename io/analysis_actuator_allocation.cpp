// Analysis "actuator_allocation": every choice of actuated joints among candidates (W. Bu 2012,
// eq. 20), with the actuated, structural and total stiffness of each at a set of poses, and a
// ranking by a chosen stiffness component, worst case over the poses. docs/analyses/actuator-allocation.md.
//
// {"id": "alloc", "type": "actuator_allocation",
//  "platform_node": "P",
//  "candidate_joints": ["J1", "J2", {"joint": "U1", "coordinate": 1}],
//  "actuators": 3,                         number of actuated candidates per scheme (N_dof)
//  "actuator_stiffness": 1.0,              one number, or one per candidate
//  "directions": ["rz", "ux", "uy"],       platform DOFs reported, in this order
//  "structural_terms": ["bending"],        terms of eq. 12 (axial, shear, torsion, bending); default all
//  "poses": [{"id": "P1", "nodes": [{"node": "J2", "xyz": [x, y, z]}, ...]}],   default: the model as given
//  "schemes": [["J1", "J2", "J3"]],        optional: only these schemes (default: all C(N, n))
//  "rank_by": {"stiffness": "total", "direction": "uy"},
//  "load_case": "payload"}                 optional: efforts, displacement, loaded stiffness per scheme
//     stiffness: actuated (K_A,dd), structural (1/C_S,dd), total_eq19 (eq. 19), total (1/C_dd, C = K_A^-1 + C_S);
//     with a load_case also loaded_actuated, loaded_structural, loaded_total (K + K_g of the case)
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <sstream>

#include "core/errors.hpp"
#include "io/analysis.hpp"
#include "io/actuator_allocation_spec.hpp"
#include "io/actuator_load_case_output.hpp"
#include "io/atomic_file.hpp"
#include "io/result_status.hpp"
#include "solvers/actuator_allocation.hpp"
#include "solvers/scheme_ranking.hpp"

namespace beamfea {

namespace {

using json = nlohmann::json;
using namespace allocation_spec;

// A number for JSON/CSV: NaN for "not available".
ojson num(double v) { return std::isfinite(v) ? ojson(v) : ojson(nullptr); }
std::string csv_num(double v) { return std::isfinite(v) ? fmt::format("{:.10g}", v) : std::string(); }

std::string scheme_name(const Model& model, const AllocationOptions& o, const std::vector<int>& s) {
  std::string n;
  for (int i : s) {
    if (!n.empty()) n += '+';
    n += model.joints[o.candidates[i].joint].id;
    if (model.joints[o.candidates[i].joint].coordinates() > 1) {
      n += ':';
      n += std::to_string(o.candidates[i].coordinate);
    }
  }
  return n;
}

// The analysis's CSV files, row by row.
struct AllocationCsv {
  std::ostringstream stiffness, links, ranking, efforts, load_case;
  AllocationCsv() {
    efforts << kEffortsCsvHeader;
    load_case << kLoadCaseCsvHeader;
    stiffness << "scheme,pose,status,det_J,direction,actuated,structural,total_eq19,total,total_fea,vf_fea_mismatch\n";
    links << "scheme,pose,direction,member,int_N2,int_Qy2,int_Qz2,int_T2,int_My2,int_Mz2,c_axial,c_shear,c_torsion,"
             "c_bending,c_sum\n";
  }
};

// What the result says of the spec: platform, directions, candidates, schemes, ranking, poses.
void write_spec_echo(ojson& res, const Model& model, const Spec& s) {
  const auto& o = s.options;
  res["type"] = "actuator_allocation";
  res["platform_node"] = model.nodes[o.platform_node].id;
  ojson dirs = ojson::array();
  for (int d : o.directions) dirs.push_back(kDofNames[d]);
  res["directions"] = dirs;
  ojson cands = ojson::array();
  for (const auto& c : o.candidates)
    cands.push_back(ojson{{"joint", model.joints[c.joint].id}, {"coordinate", c.coordinate}});
  res["candidate_joints"] = cands;
  res["actuators"] = s.actuators;
  ojson terms = ojson::array();
  for (auto t : o.terms) terms.push_back(to_string(t));
  res["structural_terms"] = terms;
  res["schemes_count"] = s.schemes.size();
  res["rank_by"] = ojson{{"stiffness", kComponents[s.rank_component]}, {"direction", kDofNames[o.directions[s.rank_direction]]}};
  ojson pose_ids = ojson::array();
  for (const auto& p : s.poses) pose_ids.push_back(p.id);
  res["poses"] = pose_ids;
  if (!s.load_case.empty()) res["load_case"] = s.load_case;
}

ojson actuated_json(const ActuatedStiffness& A) {
  ojson ka;
  ka["jacobian_message"] = A.jacobian_message;
  if (A.jacobian_ok) ka["J"] = matrix_to_json(A.J);
  if (A.J.rows() == A.J.cols() && A.jacobian_ok) ka["det_J"] = A.det_J;
  ka["form"] = A.form;
  if (A.ok()) ka["K_jacobian"] = matrix_to_json(A.K_jacobian);
  ka["condensed_message"] = A.condensed_message;
  if (A.condensed_ok) ka["K_condensed"] = matrix_to_json(A.K_condensed);
  if (A.ok() && A.condensed_ok)
    ka["jacobian_vs_condensed"] = (A.K_jacobian - A.K_condensed).cwiseAbs().maxCoeff() /
                                  std::max(A.K_condensed.cwiseAbs().maxCoeff(), 1e-300);
  return ka;
}

// The links' integrals and compliances of a structural stiffness, with their CSV rows.
ojson links_json(const Model& model, const AllocationOptions& o, const StructuralStiffness& S, const std::string& name,
                 const std::string& pose, std::ostringstream& csv) {
  const int nd = static_cast<int>(o.directions.size());
  ojson links = ojson::array();
  for (const auto& li : S.links) {
    ojson lo;
    lo["member"] = model.members[li.member].id;
    ojson raw, comp;
    for (int d = 0; d < nd; ++d) {
      const auto& rw = li.raw[d];
      raw[kDofNames[o.directions[d]]] =
          ojson{{"N2", rw[0]}, {"Qy2", rw[1]}, {"Qz2", rw[2]}, {"T2", rw[3]}, {"My2", rw[4]}, {"Mz2", rw[5]}};
      ojson c;
      for (int t = 0; t < kStructuralTermCount; ++t) c[to_string(static_cast<StructuralTerm>(t))] = li.compliance[d][t];
      comp[kDofNames[o.directions[d]]] = c;
      double sum = 0.0;
      for (auto t : o.terms) sum += li.compliance[d][static_cast<int>(t)];
      csv << fmt::format("{},{},{},{},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g}\n",
                         name, pose, kDofNames[o.directions[d]], model.members[li.member].id, rw[0], rw[1], rw[2], rw[3],
                         rw[4], rw[5], li.compliance[d][0], li.compliance[d][1], li.compliance[d][2], li.compliance[d][3],
                         sum);
    }
    lo["integrals"] = raw;
    lo["compliance"] = comp;
    links.push_back(lo);
  }
  return links;
}

ojson structural_json(const StructuralStiffness& S, const std::vector<int>& directions) {
  ojson ks;
  ks["message"] = S.message;
  if (!S.modes.empty()) {
    ojson modes = ojson::array();
    for (const auto& md : S.modes) modes.push_back(md.description);
    ks["mechanism"] = modes;
  }
  if (S.ok) {
    ks["C_fea"] = matrix_to_json(S.C_fea);
    if (S.K_fea.size()) ks["K_fea"] = matrix_to_json(S.K_fea);
    ojson vf;
    for (int t = 0; t < kStructuralTermCount; ++t) vf[to_string(static_cast<StructuralTerm>(t))] = matrix_to_json(S.C_terms[t]);
    ks["C_virtual_force"] = vf;
    ks["C"] = matrix_to_json(S.C);
    if (S.held.empty()) {
      ks["K"] = matrix_to_json(stiffness_of_compliance(S.C));
    } else {
      // C_S is zero in the held directions: K_S is unbounded there, no matrix.
      ojson held = ojson::array();
      for (int d : S.held) held.push_back(kDofNames[directions[d]]);
      ks["held_directions"] = held;
    }
    ks["virtual_force_vs_fea"] = S.fea_mismatch;
  }
  return ks;
}

ojson total_json(const TotalStiffness& T) {
  ojson tot;
  tot["message"] = T.message;
  if (T.eq19.size()) tot["eq19"] = to_json(T.eq19);
  if (T.ok) tot["K_series"] = matrix_to_json(T.K_series);
  if (T.fea_ok) tot["K_fea"] = matrix_to_json(T.K_fea);
  return tot;
}

// One scheme at one pose: what results.json holds of it, its CSV rows, and its ranking value
// (added to `rank`). `worst_mismatch`: the largest virtual-force/FEA mismatch so far.
ojson scheme_at_pose(const AnalysisContext& ctx, const Spec& s, const Model& m, std::size_t si, std::size_t pi,
                     AllocationCsv& csv, SchemeRank& rank, double& worst_mismatch) {
  const Model& model = ctx.model;
  const auto& o = s.options;
  const auto& sch = s.schemes[si];
  const int nd = static_cast<int>(o.directions.size());
  const std::string name = scheme_name(model, o, sch);
  const std::string& pose = s.poses[pi].id;
  const SchemeResult r = evaluate_scheme(m, o, sch);
  ojson po;
  po["pose"] = pose;
  po["status"] = r.status;
  po["message"] = r.message;
  const auto& A = r.actuated_stiffness;
  po["actuated"] = actuated_json(A);
  const auto& S = r.structural;
  po["structural"] = structural_json(S, o.directions);
  if (S.ok) {
    worst_mismatch = std::max(worst_mismatch, S.fea_mismatch);
    po["structural"]["links"] = links_json(model, o, S, name, pose, csv.links);
  }
  po["total"] = total_json(r.total);
  std::array<Eigen::VectorXd, kComponentCount> comp;
  const auto unloaded = scheme_components(r, nd);
  for (int c = 0; c < kUnloadedComponents; ++c) comp[c] = unloaded[c];
  for (int c = kUnloadedComponents; c < kComponentCount; ++c)
    comp[c] = Eigen::VectorXd::Constant(nd, std::numeric_limits<double>::quiet_NaN());
  if (!s.load_case.empty()) {
    // What the case does to this scheme: efforts, platform displacement, loaded stiffness.
    const SchemeLoadResponse lr = scheme_load_response(m, o, sch, model.loads_for(s.load_case));
    write_load_response(model, o, sch, lr, po);
    const auto lc = loaded_scheme_components(lr, nd);
    for (int c = 0; c < kLoadedSchemeComponents; ++c) comp[kUnloadedComponents + c] = lc[c];
    csv.efforts << efforts_csv_rows(model, o, sch, name, pose, lr);
    csv.load_case << load_case_csv_rows(o, name, pose, lr);
  }
  ojson co;
  for (int c = 0; c < kUnloadedComponents; ++c) {
    ojson v;
    for (int d = 0; d < nd; ++d) v[kDofNames[o.directions[d]]] = num(comp[c][d]);
    co[kComponents[c]] = v;
  }
  po["components"] = co;
  for (int d = 0; d < nd; ++d)
    csv.stiffness << fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", name, pose, r.status,
                                 A.jacobian_ok && A.J.rows() == A.J.cols() ? csv_num(A.det_J) : std::string(),
                                 kDofNames[o.directions[d]], csv_num(comp[0][d]), csv_num(comp[1][d]), csv_num(comp[2][d]),
                                 csv_num(comp[3][d]), csv_num(comp[4][d]), S.ok ? csv_num(S.fea_mismatch) : std::string());
  // Worst case over poses.
  rank.add_pose(r, comp[s.rank_component][s.rank_direction], pose);
  return po;
}

// The ranking (results.json's "ranking" and its CSV), of the sorted ranks.
ojson ranking_json(const Model& model, const Spec& s, const std::vector<SchemeRank>& ranks, std::ostringstream& csv) {
  ojson ranking = ojson::array();
  csv << "rank,scheme,status,worst_value,worst_pose\n";
  for (std::size_t i = 0; i < ranks.size(); ++i) {
    const auto& r = ranks[i];
    const bool ok = r.ranked();
    const std::string name = scheme_name(model, s.options, s.schemes[r.scheme]);
    const std::string status = scheme_rank_status(r, kComponents[s.rank_component]);
    ranking.push_back(ojson{{"rank", ok ? ojson(i + 1) : ojson(nullptr)},
                            {"scheme", name},
                            {"status", status},
                            {"worst_value", ok ? num(r.worst_value) : ojson(nullptr)},
                            {"worst_pose", r.worst_pose}});
    csv << fmt::format("{},{},{},{},{}\n", ok ? std::to_string(i + 1) : std::string(), name, status,
                       ok ? csv_num(r.worst_value) : std::string(), r.worst_pose);
  }
  return ranking;
}

AnalysisOutcome run_actuator_allocation(const AnalysisContext& ctx, const Spec& s) {
  const Model& model = ctx.model;
  const auto& o = s.options;
  AnalysisOutcome out;
  auto& res = out.result;
  write_spec_echo(res, model, s);
  AllocationCsv csv;
  std::vector<Model> pose_models;
  for (const auto& p : s.poses) {
    Model m = model;
    apply_node_positions(m, p.nodes);
    pose_models.push_back(std::move(m));
  }
  std::vector<SchemeRank> ranks;
  ojson schemes = ojson::array();
  int n_valid = 0;
  double worst_mismatch = 0.0;
  for (std::size_t si = 0; si < s.schemes.size(); ++si) {
    const auto& sch = s.schemes[si];
    const std::string name = scheme_name(model, o, sch);
    if (ctx.progress) ctx.progress(fmt::format("scheme {}/{}: {}", si + 1, s.schemes.size(), name));
    ojson so;
    so["scheme"] = name;
    ojson act = ojson::array();
    for (int i : sch) act.push_back(model.joints[o.candidates[i].joint].id);
    so["actuated"] = act;
    SchemeRank rank;
    rank.scheme = si;
    ojson per_pose = ojson::array();
    for (std::size_t pi = 0; pi < s.poses.size(); ++pi)
      per_pose.push_back(scheme_at_pose(ctx, s, pose_models[pi], si, pi, csv, rank, worst_mismatch));
    so["valid"] = rank.ranked();
    if (!rank.ranked()) so["invalid"] = scheme_rank_status(rank, kComponents[s.rank_component]);
    else n_valid++;
    so["poses"] = per_pose;
    schemes.push_back(so);
    ranks.push_back(rank);
  }
  res["schemes"] = schemes;
  rank_schemes(ranks);
  res["ranking"] = ranking_json(model, s, ranks, csv.ranking);
  res["valid_schemes"] = n_valid;
  res["virtual_force_vs_fea_max"] = worst_mismatch;
  if (!ctx.out_dir.empty()) {
    ojson files = ojson::array();
    std::vector<std::pair<std::string, std::string>> f = {{ctx.id + "_stiffness.csv", csv.stiffness.str()},
                                                          {ctx.id + "_links.csv", csv.links.str()},
                                                          {ctx.id + "_ranking.csv", csv.ranking.str()}};
    if (!s.load_case.empty()) {
      f.emplace_back(ctx.id + "_efforts.csv", csv.efforts.str());
      f.emplace_back(ctx.id + "_load_case.csv", csv.load_case.str());
    }
    for (const auto& [file, text] : f) {
      write_text_atomic(ctx.out_dir / file, text);
      files.push_back(file);
    }
    res["files"] = files;
  }
  const bool best = !ranks.empty() && ranks.front().ranked();
  out.message = fmt::format("actuator allocation: {} schemes, {} valid at every pose; best by {} {}: {}", s.schemes.size(),
                            n_valid, kComponents[s.rank_component], kDofNames[o.directions[s.rank_direction]],
                            best ? scheme_name(model, o, s.schemes[ranks.front().scheme]) : std::string("none"));
  res["status"] = allocation_status(n_valid);
  res["message"] = out.message;
  if (n_valid == 0) out.termination = AnalysisTermination::Failed;
  return out;
}

}  // namespace

AnalysisType actuator_allocation_analysis() {
  return register_analysis<Spec>("actuator_allocation", read_spec, run_actuator_allocation, [](const std::string& id) {
    // With a load_case also <id>_efforts.csv and <id>_load_case.csv.
    return AnalysisFiles{{id + "_stiffness.csv", id + "_links.csv", id + "_ranking.csv", id + "_efforts.csv",
                          id + "_load_case.csv"},
                         {}};
  });
}

}  // namespace beamfea
