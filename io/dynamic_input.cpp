#include "io/dynamic_input.hpp"

#include "core/errors.hpp"
#include "io/json_util.hpp"
#include "io/model_reader_parts.hpp"
#include "solvers/dynamic_system.hpp"

namespace beamfea {

void check_dynamic_mass(const Model& model, const json_in::Pointer& p, const std::string& type) {
  for (const Element& e : model.elements)
    if (e.type == MemberType::Beam && e.material >= 0 && model.materials[static_cast<std::size_t>(e.material)].density > 0.0) return;
  for (const PointMass& m : model.masses)
    if (m.mass > 0.0 || m.inertia.cwiseAbs().maxCoeff() > 0.0) return;
  throw InputError(p, type + ": the model has no mass (give a material a \"density\" or add \"masses\"): a dynamic analysis needs masses");
}

DofRef read_dynamic_dof(const Model& model, const nlohmann::json& v, const json_in::Pointer& p, const std::string& what,
                        const DofMap* map) {
  using namespace json_in;
  object(v, p, what);
  expect_keys(v, p, {"node", "dof", "joint", "coordinate"});
  if (field(v, "joint") && (field(v, "node") || field(v, "dof")))
    throw InputError(p, what + ": give {\"node\", \"dof\"} or {\"joint\", \"coordinate\"}, not both");
  const DofRef d = reader::read_dof_target(model, v, p, what);
  if (map && !raw_dof_moves(*map, map->raw_index(d)))
    throw InputError(p, what + ": " + model.describe(d) + " is held (a support or a prescribed value): it does not move");
  return d;
}

std::string dof_label(const Model& model, const DofRef& d) {
  if (d.owner == DofRef::Owner::Node) return model.nodes[static_cast<std::size_t>(d.index)].id + "." + kDofNames[static_cast<std::size_t>(d.comp)];
  return model.joints[static_cast<std::size_t>(d.index)].id + ".q" + std::to_string(d.comp);
}

void reject_modal_damping(const Model& model, const json_in::Pointer& p, const std::string& why) {
  if (model.damping.kind == Damping::Kind::Modal)
    throw InputError("/damping/modal", "modal damping (a ratio per mode) " + why + " (analysis at " + p.str() +
                                           "); give \"damping\": {\"rayleigh\": {\"alpha\", \"beta\"}}");
}

TimeFunction read_time_function(const nlohmann::json& v, const json_in::Pointer& p) {
  using namespace json_in;
  const Fields f(object(v, p, "time_function"), p, {"type", "duration", "frequency", "phase_deg", "points"});
  TimeFunction g;
  const json_in::Pointer tp = child(p, "type");
  const std::string type = string(f.require("type", "time_function"), tp, "time_function type");
  const auto only = [&](std::initializer_list<std::string_view> allowed) {
    for (const char* key : {"duration", "frequency", "phase_deg", "points"}) {
      bool ok = false;
      for (std::string_view a : allowed) ok = ok || a == key;
      if (!ok && f.get(key))
        throw InputError(child(p, key), "time_function: \"" + std::string(key) + "\" does not apply to a " + type + " function");
    }
  };
  if (type == "step") {
    g.kind = TimeFunction::Kind::Step;
    only({});
  } else if (type == "ramp") {
    g.kind = TimeFunction::Kind::Ramp;
    only({"duration"});
    g.duration = positive(f.require("duration", "ramp time_function"), child(p, "duration"), "ramp duration");
  } else if (type == "sine") {
    g.kind = TimeFunction::Kind::Sine;
    only({"frequency", "phase_deg"});
    g.frequency = positive(f.require("frequency", "sine time_function"), child(p, "frequency"), "sine frequency");
    if (const json* ph = f.get("phase_deg")) g.phase_deg = number(*ph, child(p, "phase_deg"), "sine phase_deg");
  } else if (type == "table") {
    g.kind = TimeFunction::Kind::Table;
    only({"points"});
    const json_in::Pointer pp = child(p, "points");
    const json& pts = array(f.require("points", "table time_function"), pp, "table points");
    if (pts.empty()) throw InputError(pp, "table points: expected at least one [t, value] pair");
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const std::vector<double> tv = numbers(pts[i], child(pp, i), "table point");
      if (tv.size() != 2) throw InputError(child(pp, i), "table point: expected [t, value]");
      if (!g.points.empty() && !(tv[0] > g.points.back()[0]))
        throw InputError(child(child(pp, i), 0), "table points: the times must increase");
      g.points.push_back({tv[0], tv[1]});
    }
  } else {
    throw InputError(tp, "unknown time_function type '" + type + "' (expected step, ramp, sine or table)");
  }
  return g;
}

}  // namespace beamfea
