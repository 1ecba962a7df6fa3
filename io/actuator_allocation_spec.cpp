#include "io/actuator_allocation_spec.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "core/errors.hpp"
#include "elements/beam.hpp"
#include "io/json_util.hpp"
#include "io/load_reader.hpp"
#include "io/model_reader.hpp"

namespace beamfea::allocation_spec {

namespace {
using json = nlohmann::json;
using namespace json_in;
// More schemes than this must be listed explicitly ("schemes").
constexpr std::size_t kMaxSchemes = 20000;

// "candidate_joints": joints, or {joint, coordinate} of a joint of several coordinates.
void read_candidates(const Model& model, const json& spec, const json_in::Pointer& p, const std::string& what, Spec& s) {
  auto& o = s.options;
  const json_in::Pointer pc = child(p, "candidate_joints");
  const auto& cands = array(require(spec, p, "candidate_joints", what), pc, what + " candidate_joints");
  if (cands.empty()) throw InputError(pc, what + ": no candidate joints");
  for (std::size_t i = 0; i < cands.size(); ++i) {
    const json_in::Pointer pi = child(pc, i);
    ActuatorCandidate c;
    if (cands[i].is_object()) {
      expect_keys(cands[i], pi, {"joint", "coordinate"});
      c.joint = joint_ref(model, require(cands[i], pi, "joint", "candidate"), child(pi, "joint"));
      if (cands[i].contains("coordinate")) c.coordinate = integer(cands[i]["coordinate"], child(pi, "coordinate"), "coordinate");
      if (c.coordinate < 0 || c.coordinate >= model.joints[c.joint].coordinates())
        throw InputError(child(pi, "coordinate"), "joint '" + model.joints[c.joint].id + "' has " +
                                                      std::to_string(model.joints[c.joint].coordinates()) + " coordinate(s)");
    } else {
      c.joint = joint_ref(model, cands[i], pi);
      if (model.joints[c.joint].coordinates() != 1)
        throw InputError(pi, "joint '" + model.joints[c.joint].id +
                                 "' has several coordinates: name one as {\"joint\": ..., \"coordinate\": k}");
    }
    for (const auto& d : o.candidates)
      if (d.joint == c.joint && d.coordinate == c.coordinate)
        throw InputError(pi, "joint '" + model.joints[c.joint].id + "' is a candidate twice");
    o.candidates.push_back(c);
  }
}

// "actuators": how many of the candidates each scheme actuates.
void read_actuator_count(const json& spec, const json_in::Pointer& p, const std::string& what, Spec& s) {
  const int n_all = static_cast<int>(s.options.candidates.size());
  s.actuators = integer(require(spec, p, "actuators", what), child(p, "actuators"), what + " actuators");
  if (s.actuators < 1) throw InputError(child(p, "actuators"), what + ": the number of actuators must be at least 1");
  if (s.actuators > n_all)
    throw InputError(child(p, "actuators"), fmt::format("{}: {} actuators but only {} candidate joint(s)", what,
                                                        s.actuators, n_all));
}

// "actuator_stiffness": one value for all candidates, or one per candidate.
void read_actuator_stiffness(const json& spec, const json_in::Pointer& p, const std::string& what, Spec& s) {
  auto& o = s.options;
  const int n_all = static_cast<int>(s.options.candidates.size());
  const json_in::Pointer pk = child(p, "actuator_stiffness");
  const auto& k = require(spec, p, "actuator_stiffness", what);
  if (k.is_array()) {
    auto v = numbers(k, pk, what + " actuator_stiffness");
    if (static_cast<int>(v.size()) != n_all)
      throw InputError(pk, fmt::format("{}: expected {} actuator stiffness values (one per candidate)", what, n_all));
    for (std::size_t i = 0; i < v.size(); ++i)
      if (!(v[i] > 0.0)) throw InputError(child(pk, i), what + ": actuator stiffness must be positive");
    o.actuator_stiffness = v;
  } else {
    o.actuator_stiffness.assign(n_all, positive(k, pk, what + " actuator_stiffness"));
  }
}

// "directions": the platform DOFs reported, in order.
void read_directions(const json& spec, const json_in::Pointer& p, const std::string& what, Spec& s) {
  auto& o = s.options;
  const json_in::Pointer pd = child(p, "directions");
  const auto& dirs = array(require(spec, p, "directions", what), pd, what + " directions");
  if (dirs.empty()) throw InputError(pd, what + ": no directions");
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    const int d = dof_name(dirs[i], child(pd, i), "direction", "", "direction");
    for (int e : o.directions)
      if (e == d) throw InputError(child(pd, i), "direction '" + std::string(kDofNames[d]) + "' repeated");
    o.directions.push_back(d);
  }
}

// "structural_terms" (optional): the beam terms of the structural compliance.
void read_structural_terms(const json& spec, const json_in::Pointer& p, const std::string& what, Spec& s) {
  auto& o = s.options;
  if (spec.contains("structural_terms")) {
    const json_in::Pointer pt = child(p, "structural_terms");
    const auto& t = array(spec["structural_terms"], pt, what + " structural_terms");
    if (t.empty()) throw InputError(pt, what + ": no structural terms");
    o.terms.clear();
    for (std::size_t i = 0; i < t.size(); ++i) {
      const std::string name = string(t[i], child(pt, i), "structural term");
      bool found = false;
      for (int q = 0; q < kStructuralTermCount; ++q)
        if (name == to_string(static_cast<StructuralTerm>(q))) {
          o.terms.push_back(static_cast<StructuralTerm>(q));
          found = true;
        }
      if (!found) throw InputError(child(pt, i), "unknown structural term '" + name + "' (expected axial, shear, torsion, bending)");
    }
  }
}

// "poses" (optional; without, one pose "reference", or "pose" for a posed model): node positions,
// each a valid geometry.
void read_poses(const Model& model, const json& spec, const json_in::Pointer& p, const std::string& what, Spec& s) {
  if (spec.contains("poses")) {
    const json_in::Pointer pp = child(p, "poses");
    const auto& poses = array(spec["poses"], pp, what + " poses");
    if (poses.empty()) throw InputError(pp, what + ": empty list of poses");
    for (std::size_t i = 0; i < poses.size(); ++i) {
      const json_in::Pointer pi = child(pp, i);
      const auto& po = object(poses[i], pi, "pose");
      expect_keys(po, pi, {"id", "nodes"});
      Pose pose;
      pose.id = po.contains("id") ? json_in::id(po["id"], child(pi, "id"), "pose") : "pose" + std::to_string(i + 1);
      for (const auto& q : s.poses)
        if (q.id == pose.id) throw InputError(child(pi, "id"), "duplicate pose id '" + pose.id + "'");
      if (po.contains("nodes")) {
        const json_in::Pointer pn = child(pi, "nodes");
        const auto& nodes = array(po["nodes"], pn, "pose '" + pose.id + "' nodes");
        for (std::size_t j = 0; j < nodes.size(); ++j) {
          const json_in::Pointer pj = child(pn, j);
          const auto& nj = object(nodes[j], pj, "pose node");
          expect_keys(nj, pj, {"node", "xyz"});
          const int n = node_ref(model, require(nj, pj, "node", "pose node"), child(pj, "node"));
          pose.nodes.emplace_back(n, vec3(require(nj, pj, "xyz", "pose node"), child(pj, "xyz"), "pose node xyz"));
        }
      }
      // The pose must be a valid geometry (joints coincide, members have a length).
      Model moved = model;
      try {
        apply_node_positions(moved, pose.nodes);
      } catch (const ModelError& e) {
        throw InputError(pi, "pose '" + pose.id + "': " + e.what());
      }
      // Every beam keeps a local frame: the pose must not turn a beam parallel to its orientation.
      for (const auto& el : moved.elements) {
        if (el.type != MemberType::Beam) continue;
        try {
          beam_local_axes(moved.nodes[el.nodes[0]].x, moved.nodes[el.nodes[1]].x, el.orientation);
        } catch (const Error& e) {
          throw InputError(pi, "pose '" + pose.id + "': element '" + el.id + "': " + e.what());
        }
      }
      s.poses.push_back(std::move(pose));
    }
  } else {
    // The model as given: its reference geometry, or the geometry of its top-level "pose".
    s.poses.push_back({model.pose.given ? "pose" : "reference", {}});
  }
}

// "schemes" (optional; every combination of the candidates without).
void read_schemes(const Model& model, const json& spec, const json_in::Pointer& p, const std::string& what, Spec& s) {
  auto& o = s.options;
  const int n_all = static_cast<int>(s.options.candidates.size());
  if (spec.contains("schemes")) {
    const json_in::Pointer ps = child(p, "schemes");
    const auto& sch = array(spec["schemes"], ps, what + " schemes");
    for (std::size_t i = 0; i < sch.size(); ++i) {
      const json_in::Pointer pi = child(ps, i);
      const auto& list = array(sch[i], pi, "scheme");
      if (static_cast<int>(list.size()) != s.actuators)
        throw InputError(pi, fmt::format("scheme has {} joints, expected {} (actuators)", list.size(), s.actuators));
      std::vector<int> idx;
      for (std::size_t j = 0; j < list.size(); ++j) {
        const int jt = joint_ref(model, list[j], child(pi, j));
        int found = -1;
        for (int c = 0; c < n_all; ++c)
          if (o.candidates[c].joint == jt && std::find(idx.begin(), idx.end(), c) == idx.end()) {
            found = c;
            break;
          }
        if (found < 0) throw InputError(child(pi, j), "joint '" + model.joints[jt].id + "' is not a candidate (or repeated)");
        idx.push_back(found);
      }
      std::sort(idx.begin(), idx.end());
      s.schemes.push_back(idx);
    }
  } else {
    // C(n, k) without overflow for the check.
    double count = 1.0;
    for (int i = 0; i < s.actuators; ++i) count = count * (n_all - i) / (i + 1);
    if (count > static_cast<double>(kMaxSchemes))
      throw InputError(child(p, "candidate_joints"), fmt::format("{}: {:.0f} schemes exceed the limit of {}; list "
                                                                 "\"schemes\" explicitly",
                                                                 what, count, kMaxSchemes));
    s.schemes = combinations(n_all, s.actuators);
  }
}

// "rank_by" (optional): the stiffness component and direction that rank the schemes.
void read_ranking(const json& spec, const json_in::Pointer& p, const std::string& what, Spec& s) {
  auto& o = s.options;
  s.rank_direction = 0;
  if (spec.contains("rank_by")) {
    const json_in::Pointer pr = child(p, "rank_by");
    const auto& r = object(spec["rank_by"], pr, what + " rank_by");
    expect_keys(r, pr, {"stiffness", "direction"});
    if (r.contains("stiffness")) {
      const std::string c = string(r["stiffness"], child(pr, "stiffness"), "rank_by stiffness");
      s.rank_component = -1;
      for (int i = 0; i < kComponentCount; ++i)
        if (i != 4 && c == kComponents[i]) s.rank_component = i;
      if (s.rank_component < 0)
        throw InputError(child(pr, "stiffness"), "unknown stiffness '" + c +
                                                     "' (expected actuated, structural, total_eq19, total, loaded_actuated, "
                                                     "loaded_structural, loaded_total)");
      if (s.rank_component >= kUnloadedComponents && s.load_case.empty())
        throw InputError(child(pr, "stiffness"), "rank_by stiffness '" + c + "' needs a \"load_case\"");
    }
    if (r.contains("direction")) {
      const std::string d = string(r["direction"], child(pr, "direction"), "rank_by direction");
      const int di = dof_index(d);
      s.rank_direction = -1;
      for (std::size_t i = 0; i < o.directions.size(); ++i)
        if (o.directions[i] == di) s.rank_direction = static_cast<int>(i);
      if (s.rank_direction < 0) throw InputError(child(pr, "direction"), "rank_by direction '" + d + "' is not among \"directions\"");
    }
  }
}

}  // namespace

Spec read_spec(const Model& model, const json& spec, const json_in::Pointer& p) {
  Spec s;
  s.load_case = read_load_case(model, spec, p);
  const std::string what = "actuator_allocation analysis";
  expect_keys(spec, p, {"id", "type", "description", "platform_node", "candidate_joints", "actuators",
                        "actuator_stiffness", "directions", "structural_terms", "poses", "schemes", "rank_by",
                        "load_case"});
  s.options.platform_node = node_ref(model, require(spec, p, "platform_node", what), child(p, "platform_node"));
  read_candidates(model, spec, p, what, s);
  read_actuator_count(spec, p, what, s);
  read_actuator_stiffness(spec, p, what, s);
  read_directions(spec, p, what, s);
  read_structural_terms(spec, p, what, s);
  read_poses(model, spec, p, what, s);
  read_schemes(model, spec, p, what, s);
  read_ranking(spec, p, what, s);
  s.options.validate(model);
  return s;
}

}  // namespace beamfea::allocation_spec
