// Model reader, part 3: joints (revolute, prismatic, universal, spherical, virtual springs).
#include <Eigen/Eigenvalues>

#include "core/errors.hpp"
#include "elements/beam.hpp"
#include "io/json_util.hpp"
#include "io/model_check.hpp"
#include "solvers/condensed_stiffness.hpp"
#include "io/model_reader.hpp"
#include "io/model_reader_parts.hpp"

namespace beamfea::reader {

using namespace json_in;

namespace {

// Relative distance (times the length scale) above which a joint's two nodes do not coincide.
constexpr double kCoincident = 1e-9;
// |sin| of the angle between two axes below which they are parallel.
constexpr double kParallelAxes = 1e-6;
// |cos| above which a virtual spring's axes are not orthogonal.
constexpr double kOrthogonalAxes = 1e-9;
// Link models inside link models ("stiffness_from_model"): deeper nesting than this is taken for a
// model that refers to itself (no real link is a link of links eight levels deep).
constexpr int kMaxLinkNesting = 8;
// Relative asymmetry / negative eigenvalue tolerated in a full stiffness matrix (round-off of
// values the user computed elsewhere).
constexpr double kMatrixTolerance = 1e-9;

JointType joint_type(const std::string& type, const json_in::Pointer& p, const std::string& what) {
  if (type == "revolute") return JointType::Revolute;
  if (type == "universal") return JointType::Universal;
  if (type == "spherical") return JointType::Spherical;
  if (type == "virtual_spring") return JointType::VirtualSpring;
  if (type == "prismatic") return JointType::Prismatic;
  throw InputError(p, what + ": unknown type '" + type + "' (expected revolute, prismatic, universal, spherical, virtual_spring)");
}

void read_axes(Joint& j, const Fields& f, const json_in::Pointer& p, const std::string& what, const std::string& type) {
  const int nc = joint_coordinate_count(j.type);
  // Axes: one per coordinate (a prismatic joint's is its sliding direction); a virtual spring gives its frame (x, y, z), used for its
  // three translations and its three rotations alike.
  const int naxes = j.type == JointType::VirtualSpring ? 3 : nc;
  // Read into j.axes (a recycled joint's storage reused).
  j.axes.clear();
  j.axes.reserve(j.type == JointType::VirtualSpring ? 2 * naxes : naxes);
  if (const json* axes_value = f.get("axes")) {
    const auto& axes = array(*axes_value, child(p, "axes"), What(what, " axes"));
    if (static_cast<int>(axes.size()) != naxes)
      throw InputError(child(p, "axes"), what + ": a " + type + " joint needs " + std::to_string(naxes) + " axes");
    for (std::size_t k = 0; k < axes.size(); ++k) {
      Vec3 a = vec3(axes[k], child(child(p, "axes"), k), What(what, " axis"));
      if (a.norm() == 0.0) throw InputError(child(child(p, "axes"), k), what + ": axis is zero");
      j.axes.push_back(a.normalized());
    }
  } else if (j.type == JointType::Spherical || j.type == JointType::VirtualSpring) {
    j.axes.insert(j.axes.end(), {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()});
  } else {
    throw InputError(child(p, "axes"), what + ": missing field 'axes'");
  }
  const auto& axes_in = j.axes;
  for (int a = 0; a < naxes; ++a)
    for (int b = a + 1; b < naxes; ++b)
      if (axes_in[a].cross(axes_in[b]).norm() < kParallelAxes)
        throw InputError(child(p, "axes"), what + ": axes " + std::to_string(a) + " and " + std::to_string(b) + " are parallel");
  if (j.type == JointType::VirtualSpring) {
    for (int a = 0; a < 3; ++a)
      for (int b = a + 1; b < 3; ++b)
        if (std::abs(axes_in[a].dot(axes_in[b])) > kOrthogonalAxes)
          throw InputError(child(p, "axes"), what + ": the axes of a virtual spring must be orthogonal");
    j.translations = 3;
    for (int a = 0; a < 3; ++a) j.axes.push_back(j.axes[a]);  // room reserved above: no reallocation
  }
  if (j.type == JointType::Prismatic) j.translations = 1;
}

void read_stiffness(Joint& j, const json& st, const json_in::Pointer& sp, const std::string& what) {
  const int nc = joint_coordinate_count(j.type);
  if (st.is_array() && !st.empty() && st[0].is_array()) {
    // A full matrix, symmetric, positive semi-definite.
    if (static_cast<int>(st.size()) != nc)
      throw InputError(sp, what + ": expected a " + std::to_string(nc) + "x" + std::to_string(nc) + " stiffness matrix");
    Eigen::MatrixXd K(nc, nc);
    for (int r = 0; r < nc; ++r) {
      auto row = numbers(st[r], child(sp, r), What(what, " stiffness"));
      if (static_cast<int>(row.size()) != nc)
        throw InputError(child(sp, r), what + ": expected " + std::to_string(nc) + " values in each row");
      for (int c = 0; c < nc; ++c) K(r, c) = row[c];
    }
    if ((K - K.transpose()).cwiseAbs().maxCoeff() > kMatrixTolerance * K.cwiseAbs().maxCoeff())
      throw InputError(sp, what + ": the stiffness matrix must be symmetric");
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(K);
    if (es.eigenvalues().minCoeff() < -kMatrixTolerance * K.cwiseAbs().maxCoeff())
      throw InputError(sp, what + ": the stiffness matrix must be positive semi-definite");
    j.stiffness_matrix = K;
    for (int c = 0; c < nc; ++c) j.stiffness[c] = K(c, c);
  } else {
    // numbers(), without its vector: every value checked, then the count, then the signs.
    if (!st.is_array()) throw InputError(sp, What(what, " stiffness").str() + ": expected an array of numbers");
    for (std::size_t c = 0; c < st.size(); ++c) number(st[c], child(sp, c), What(what, " stiffness"));
    if (static_cast<int>(st.size()) != nc)
      throw InputError(sp, what + ": expected " + std::to_string(nc) + " stiffness value(s)");
    for (int c = 0; c < nc; ++c)
      if (st[c].get<double>() < 0.0) throw InputError(child(sp, c), what + ": stiffness must not be negative");
    for (int c = 0; c < nc; ++c) j.stiffness[c] = st[c].get<double>();
  }
}

// "damping": one non-negative viscous coefficient per coordinate (force per velocity, moment per
// angular velocity), used by the dynamic analyses.
void read_joint_damping(Joint& j, const json& d, const json_in::Pointer& dp, const std::string& what) {
  const int nc = joint_coordinate_count(j.type);
  if (!d.is_array()) throw InputError(dp, what + " damping: expected an array of " + std::to_string(nc) + " number(s)");
  for (std::size_t c = 0; c < d.size(); ++c) number(d[c], child(dp, c), What(what, " damping"));
  if (static_cast<int>(d.size()) != nc)
    throw InputError(dp, what + ": expected " + std::to_string(nc) + " damping value(s), one per coordinate");
  j.damping.resize(static_cast<std::size_t>(nc));
  for (int c = 0; c < nc; ++c) {
    j.damping[static_cast<std::size_t>(c)] = d[c].get<double>();
    if (j.damping[static_cast<std::size_t>(c)] < 0.0) throw InputError(child(dp, c), what + ": damping must not be negative");
  }
}

// "stiffness_from_beam": the tip stiffness of a cantilever (elements/beam.hpp), in the joint
// frame (x along the link).
void read_stiffness_from_beam(Joint& j, const ReadState& s, const Fields& f, const json_in::Pointer& p, const std::string& what) {
  const Model& m = s.model;
  if (j.type != JointType::VirtualSpring)
    throw InputError(child(p, "stiffness_from_beam"), what + ": stiffness_from_beam needs a virtual_spring joint");
  if (f.get("stiffness"))
    throw InputError(child(p, "stiffness_from_beam"), what + ": give \"stiffness\" or \"stiffness_from_beam\", not both");
  const json_in::Pointer bp = child(p, "stiffness_from_beam");
  const auto& b = object(*f.get("stiffness_from_beam"), bp, What(what, " stiffness_from_beam"));
  const Fields fb(b, bp, {"material", "section", "length", "theory"});
  const std::string mid = json_in::id(fb.require("material", what), child(bp, "material"), What(what, " material"));
  const std::string sid = json_in::id(fb.require("section", what), child(bp, "section"), What(what, " section"));
  const int mi = m.find_material(mid);
  const int si = m.find_section(sid);
  if (mi < 0) throw InputError(child(bp, "material"), what + ": unknown material '" + mid + "'");
  if (si < 0) throw InputError(child(bp, "section"), what + ": unknown section '" + sid + "'");
  const double L = positive(fb.require("length", what), child(bp, "length"), What(what, " length"));
  const auto& mat = m.materials[mi];
  const auto& sec = m.sections[si];
  BeamSection bs{mat.E, mat.G, sec.A, sec.Iy, sec.Iz, sec.J};
  if (const json* theory = fb.get("theory")) {
    // A shear-deformable link: the Timoshenko cantilever's tip stiffness (its compliance adds
    // k L/(G A) to the transverse terms).
    const json_in::Pointer tp = child(bp, "theory");
    if (beam_theory(string(*theory, tp, What(what, " theory")), tp, what) == BeamTheory::Timoshenko) {
      if (!(sec.ky > 0.0 && sec.kz > 0.0))
        throw InputError(tp, what + ": a Timoshenko beam needs the shear factors of section '" + sec.id +
                                 "' (give \"k\" or \"ky\" and \"kz\", or a \"shape\")");
      bs.Asy = sec.A / sec.ky;
      bs.Asz = sec.A / sec.kz;
    }
  }
  j.stiffness_matrix = cantilever_tip_stiffness(bs, L);
  for (int c = 0; c < j.coordinates(); ++c) j.stiffness[c] = j.stiffness_matrix(c, c);
}

// "limits": [[lo, hi], ...], one pair per coordinate (docs/poses.md).
void read_limits(Joint& j, const json& v, const json_in::Pointer& lp, const std::string& what) {
  const auto& pairs = array(v, lp, What(what, " limits"));
  if (static_cast<int>(pairs.size()) != j.coordinates())
    throw InputError(lp, what + ": expected " + std::to_string(j.coordinates()) + " limit pair(s) [lo, hi], one per coordinate");
  j.limits.resize(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto pair = numbers(pairs[k], child(lp, k), What(what, " limits"));
    if (pair.size() != 2) throw InputError(child(lp, k), what + ": a limit is a pair [lo, hi]");
    if (!(pair[0] <= pair[1])) throw InputError(child(lp, k), what + ": a limit needs lo <= hi");
    j.limits[k] = {pair[0], pair[1]};
  }
}

// The link models being read on this thread, innermost last: a guard against a link model that
// refers to itself, directly or through others.
thread_local int link_nesting = 0;
struct LinkNesting {
  LinkNesting() { ++link_nesting; }
  ~LinkNesting() { --link_nesting; }
  LinkNesting(const LinkNesting&) = delete;
  LinkNesting& operator=(const LinkNesting&) = delete;
};

// "stiffness_from_model": the FEA-based VJM spring (Pashkevich, Klimchik & Chablat 2010,
// introduction; docs/analyses/superelement.md eq. 8): the stiffness of a link model clamped at
// `base` (all six DOFs, whatever its supports there say), seen at `tip`: the static condensation of solvers/condensed_stiffness.hpp, in the link model's
// axes, which are the joint's frame (translations, then rotations, along/about its axes). A path is
// relative to the folder of the file that names it (read_json_file resolves it), else to the
// working folder.
void read_stiffness_from_model(Joint& j, const Fields& f, const json_in::Pointer& p, const std::string& what) {
  const json_in::Pointer bp = child(p, "stiffness_from_model");
  if (j.type != JointType::VirtualSpring)
    throw InputError(bp, what + ": stiffness_from_model needs a virtual_spring joint");
  if (f.get("stiffness") || f.get("stiffness_from_beam"))
    throw InputError(bp, what + ": give one of \"stiffness\", \"stiffness_from_beam\" and \"stiffness_from_model\"");
  const auto& b = object(*f.get("stiffness_from_model"), bp, What(what, " stiffness_from_model"));
  const Fields fb(b, bp, {"model", "base", "tip"});
  const json_in::Pointer mp = child(bp, "model");
  const json& given = fb.require("model", what);
  if (link_nesting >= kMaxLinkNesting)
    throw InputError(mp, what + ": link models nested more than " + std::to_string(kMaxLinkNesting) +
                             " deep (does a link model refer to itself?)");
  const LinkNesting nesting;
  Model link;
  try {
    if (given.is_string()) {
      const json doc = read_json_file(given.get<std::string>());
      link = read_model(doc);
      check_model(link, doc);
    } else if (given.is_object()) {
      link = read_model(given);
      check_model(link, given);
    } else {
      throw InputError(mp, what + ": expected a file name or a model object");
    }
  } catch (const InputError& e) {
    if (e.pointer() == mp.str()) throw;
    throw InputError(mp, what + ": link model: " + e.what());
  }
  int ends[2];
  const char* names[2] = {"base", "tip"};
  for (int k = 0; k < 2; ++k) {
    const json_in::Pointer np = child(bp, names[k]);
    const std::string nid = json_in::id(fb.require(names[k], what), np, What(what, " ", names[k]));
    ends[k] = link.find_node(nid);
    if (ends[k] < 0) throw InputError(np, what + ": the link model has no node '" + nid + "'");
  }
  if (ends[0] == ends[1]) throw InputError(child(bp, "tip"), what + ": base and tip are one node");
  // Clamped at the base: its supports replaced by a full one.
  std::erase_if(link.supports, [&](const Support& s) { return s.node == ends[0]; });
  Support clamp;
  clamp.node = ends[0];
  clamp.fixed.fill(true);
  link.supports.push_back(clamp);
  const CondensedStiffness c = linear_node_stiffness(link, ends[1]);
  if (!c.ok || c.rank < 6 || !c.rigid_directions.empty())
    throw InputError(bp, what + ": the link clamped at '" + link.nodes[ends[0]].id + "' gives node '" +
                             link.nodes[ends[1]].id + "' a stiffness of rank " + std::to_string(c.rank) +
                             " (a virtual spring needs a link that resists all six motions of its tip)" +
                             (c.message.empty() ? "" : ": " + c.message));
  j.stiffness_matrix = 0.5 * (c.K + c.K.transpose());
  for (int k = 0; k < j.coordinates(); ++k) j.stiffness[k] = j.stiffness_matrix(k, k);
}

}  // namespace

void read_joints(ReadState& s) {
  Model& m = s.model;
  const auto& arr = collection(s.doc, "joints", false);
  m.joint_index.reserve(arr.size());
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const json_in::Pointer p = child("/joints", i);
    const auto& o = object(arr[i], p, "joint");
    const Fields f(o, p, {"id", "type", "nodes", "axes", "stiffness", "stiffness_from_beam", "limits", "stiffness_from_model", "damping"});
    Joint j = s.item(&Model::joints, i);
    id_into(j.id, f.require("id", "joint"), child(p, "id"), "joint");
    check_unique(m.find_joint(j.id), "joint", "/joints", j.id, i);  // joint i is at position i
    const std::string what = "joint '" + j.id + "'";
    const std::string type = string(f.require("type", what), child(p, "type"), what);
    j.type = joint_type(type, child(p, "type"), what);
    const auto& nodes = f.require("nodes", what);
    if (!nodes.is_array() || nodes.size() != 2) throw InputError(child(p, "nodes"), what + ": expected two node ids");
    for (int k = 0; k < 2; ++k) j.nodes[k] = node_ref(m, nodes[k], child(child(p, "nodes"), k));
    if (j.nodes[0] == j.nodes[1]) throw InputError(child(p, "nodes"), what + ": joins a node to itself");
    if ((m.nodes[j.nodes[0]].x - m.nodes[j.nodes[1]].x).norm() > kCoincident * s.length_scale)
      throw InputError(child(p, "nodes"), what + ": nodes '" + m.nodes[j.nodes[0]].id + "' and '" +
                                              m.nodes[j.nodes[1]].id + "' do not coincide");
    read_axes(j, f, p, what, type);
    j.stiffness.assign(joint_coordinate_count(j.type), 0.0);
    if (const json* stiffness = f.get("stiffness")) read_stiffness(j, *stiffness, child(p, "stiffness"), what);
    if (f.get("stiffness_from_beam")) read_stiffness_from_beam(j, s, f, p, what);
    if (const json* limits = f.get("limits")) read_limits(j, *limits, child(p, "limits"), what);
    if (f.get("stiffness_from_model")) read_stiffness_from_model(j, f, p, what);
    if (const json* damping = f.get("damping")) read_joint_damping(j, *damping, child(p, "damping"), what);
    m.add_joint(std::move(j));
  }
}

}  // namespace beamfea::reader
