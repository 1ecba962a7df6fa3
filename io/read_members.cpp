// Model reader, part 2: elements (members), meshed into analysis elements by core/meshing.
#include <cmath>

#include "core/errors.hpp"
#include "core/meshing.hpp"
#include "io/json_util.hpp"
#include "io/model_reader.hpp"
#include "io/model_reader_parts.hpp"

namespace beamfea::reader {

using namespace json_in;

namespace {

// Upper bound of "divisions" per member (docs/input-format.md): 10,000 segments resolve any
// beam's deflection far below its discretisation error; more would only exhaust memory.
constexpr int kMaxDivisions = 10000;
// Relative length below which a member's end nodes coincide (times the model's length scale).
constexpr double kZeroLength = 1e-12;
// |sin| of the angle between orientation and member below which they are parallel.
constexpr double kParallelOrientation = 1e-8;

// "releases": {"start": [...], "end": [...]}, local DOF names at each end of the member.
void read_releases(const json& v, const json_in::Pointer& p, const std::string& what, Member& mem) {
  const auto& o = object(v, p, What(what, " releases"));
  const Fields f(o, p, {"start", "end"});
  mem.releases = {};
  for (int end = 0; end < 2; ++end) {
    const char* key = end == 0 ? "start" : "end";
    const json* names = f.get(key);
    if (!names) continue;
    const json_in::Pointer pe = child(p, key);
    array(*names, pe, What(what, " releases ", key));
    const std::string context = what + ": release at the " + key + ": ";
    for (std::size_t k = 0; k < names->size(); ++k) {
      const int d = dof_name((*names)[k], child(pe, k), What(what, " release"), What(context));
      if (mem.releases[end][d])
        throw InputError(child(pe, k), what + ": release '" + kDofNames[d] + "' given twice at the " + key);
      mem.releases[end][d] = true;
    }
  }
}

// "offsets": {"start": [dx, dy, dz], "end": [...]} (global vectors from the nodes to the member's
// ends) and "rigid_ends": [r_start, r_end] (rigid lengths along the axis between those ends):
// something flexible must remain.
void read_arms(const Fields& f, const json_in::Pointer& p, const std::string& what, double length_scale, Member& mem,
               const Vec3& x1, const Vec3& x2) {
  mem.offsets = {Vec3::Zero(), Vec3::Zero()};
  mem.rigid_ends = {0.0, 0.0};
  if (const json* offsets = f.get("offsets")) {
    const json_in::Pointer po = child(p, "offsets");
    const Fields fo(object(*offsets, po, What(what, " offsets")), po, {"start", "end"});
    for (int end = 0; end < 2; ++end) {
      const char* key = end == 0 ? "start" : "end";
      if (const json* o = fo.get(key)) mem.offsets[end] = vec3(*o, child(po, key), What(what, " offset at the ", key));
    }
  }
  const double axis = (x2 + mem.offsets[1] - x1 - mem.offsets[0]).norm();
  if (!(axis > kZeroLength * length_scale))
    throw InputError(child(p, "offsets"), what + ": the offsets bring the member's ends together");
  if (const json* r = f.get("rigid_ends")) {
    const json_in::Pointer pr = child(p, "rigid_ends");
    if (!r->is_array() || r->size() != 2) throw InputError(pr, what + ": rigid_ends must be [r_start, r_end]");
    for (int end = 0; end < 2; ++end) {
      mem.rigid_ends[end] = number((*r)[end], child(pr, end), What(what, " rigid end"));
      if (!(mem.rigid_ends[end] >= 0.0))
        throw InputError(child(pr, end), what + ": a rigid end's length must be >= 0");
    }
    if (!(mem.rigid_ends[0] + mem.rigid_ends[1] < axis * (1.0 - kZeroLength)))
      throw InputError(pr, what + ": the rigid ends (" + json(mem.rigid_ends[0]).dump() + " + " +
                               json(mem.rigid_ends[1]).dump() + ") leave nothing flexible of the member's length " +
                               json(axis).dump());
  }
}

}  // namespace

BeamTheory beam_theory(const std::string& name, const json_in::Pointer& pointer, const std::string& what) {
  if (name == "euler_bernoulli") return BeamTheory::EulerBernoulli;
  if (name == "timoshenko") return BeamTheory::Timoshenko;
  throw InputError(pointer, what + ": unknown theory '" + name + "' (expected euler_bernoulli or timoshenko)");
}

void read_members(ReadState& s) {
  Model& m = s.model;
  const auto& arr = collection(s.doc, "elements", false);
  m.members.reserve(arr.size());
  m.member_index.reserve(arr.size());
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const json_in::Pointer p = child("/elements", i);
    const auto& o = object(arr[i], p, "element");
    const Fields f(o, p, {"id", "type", "nodes", "material", "section", "orientation", "divisions", "theory", "releases", "rigid_ends", "offsets",
                          "behaviour"});
    Member mem = s.item(&Model::members, i);
    id_into(mem.id, f.require("id", "element"), child(p, "id"), "element");
    check_unique(m.find_member(mem.id), "element", "/elements", mem.id, i);  // member i is element i
    const std::string& what = s.what.assign("element '").append(mem.id).append("'");
    const std::string type = string(f.require("type", what), child(p, "type"), what);
    if (type == "beam") mem.type = MemberType::Beam;
    else if (type == "rigid") mem.type = MemberType::Rigid;
    else throw InputError(child(p, "type"), what + ": unknown type '" + type + "' (expected beam or rigid)");
    const auto& nodes = f.require("nodes", what);
    if (!nodes.is_array() || nodes.size() != 2) throw InputError(child(p, "nodes"), what + ": expected two node ids");
    for (int k = 0; k < 2; ++k) mem.nodes[k] = node_ref(m, nodes[k], child(child(p, "nodes"), k));
    const Vec3 x1 = m.nodes[mem.nodes[0]].x, x2 = m.nodes[mem.nodes[1]].x;
    const double L = (x2 - x1).norm();
    if (!(L > kZeroLength * s.length_scale))
      throw InputError(child(p, "nodes"), what + ": zero length (nodes '" + m.nodes[mem.nodes[0]].id + "' and '" +
                                              m.nodes[mem.nodes[1]].id + "' coincide)");
    if (mem.type == MemberType::Beam) {
      const std::string mid = json_in::id(f.require("material", what), child(p, "material"), What(what, " material"));
      mem.material = m.find_material(mid);
      if (mem.material < 0) throw InputError(child(p, "material"), what + ": unknown material '" + mid + "'");
      const std::string sid = json_in::id(f.require("section", what), child(p, "section"), What(what, " section"));
      mem.section = m.find_section(sid);
      if (mem.section < 0) throw InputError(child(p, "section"), what + ": unknown section '" + sid + "'");
      const Vec3 ex = (x2 - x1) / L;
      if (const json* orientation = f.get("orientation")) {
        mem.orientation = vec3(*orientation, child(p, "orientation"), What(what, " orientation"));
        if (mem.orientation.norm() == 0.0 || mem.orientation.normalized().cross(ex).norm() < kParallelOrientation)
          throw InputError(child(p, "orientation"), what + ": orientation is zero or parallel to the member");
      } else {
        // Default: global Z in the local x-z plane; for a vertical member, global X.
        mem.orientation = std::abs(ex.z()) > 1.0 - kParallelOrientation ? Vec3(1, 0, 0) : Vec3(0, 0, 1);
      }
      if (const json* divisions = f.get("divisions"))
        mem.divisions = integer_in(*divisions, child(p, "divisions"), What(what, " divisions"), 1, kMaxDivisions);
      if (const json* theory = f.get("theory")) {
        const json_in::Pointer tp = child(p, "theory");
        mem.theory = beam_theory(string(*theory, tp, What(what, " theory")), tp, what);
        const Section& sec = m.sections[mem.section];
        if (mem.theory == BeamTheory::Timoshenko && !(sec.ky > 0.0 && sec.kz > 0.0))
          throw InputError(tp, what + ": a Timoshenko beam needs the shear factors of section '" + sec.id +
                                   "' (give \"k\" or \"ky\" and \"kz\", or a \"shape\")");
      }
      if (const json* releases = f.get("releases")) read_releases(*releases, child(p, "releases"), what, mem);
      read_arms(f, p, what, s.length_scale, mem, x1, x2);
      if (const json* behaviour = f.get("behaviour")) {
        const json_in::Pointer bp = child(p, "behaviour");
        const std::string b = string(*behaviour, bp, What(what, " behaviour"));
        if (b == "tension_only") mem.behaviour = MemberBehaviour::TensionOnly;
        else if (b == "compression_only") mem.behaviour = MemberBehaviour::CompressionOnly;
        else throw InputError(bp, what + ": unknown behaviour '" + b + "' (expected tension_only or compression_only)");
      }
    } else {
      if (const json* divisions = f.get("divisions"); divisions && *divisions != 1)
        throw InputError(child(p, "divisions"), what + ": a rigid link cannot be divided");
      for (const char* key : {"material", "section", "orientation", "theory", "releases", "rigid_ends", "offsets", "behaviour"})
        if (f.get(key)) throw InputError(child(p, key), what + ": a rigid link has no " + std::string(key));
    }
    if (const std::string taken = taken_internal_node_id(m, mem); !taken.empty())
      throw InputError(child(p, "id"), what + ": internal node id '" + taken + "' is taken");
    add_meshed_member(m, std::move(mem), s.spare);
  }
}

}  // namespace beamfea::reader
