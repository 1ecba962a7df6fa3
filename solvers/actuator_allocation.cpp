#include "solvers/actuator_allocation.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <fmt/format.h>
#include <set>

#include "core/assembly.hpp"
#include "core/errors.hpp"
#include "solvers/condensed_stiffness.hpp"
#include "solvers/condensation.hpp"
#include "solvers/linear_solver.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

const char* to_string(StructuralTerm t) {
  switch (t) {
    case StructuralTerm::Axial: return "axial";
    case StructuralTerm::Shear: return "shear";
    case StructuralTerm::Torsion: return "torsion";
    case StructuralTerm::Bending: return "bending";
  }
  return "?";
}

void AllocationOptions::validate(const Model& model) const {
  if (platform_node < 0 || platform_node >= static_cast<int>(model.nodes.size()))
    throw Error("AllocationOptions: platform_node out of range");
  if (directions.empty()) throw Error("AllocationOptions: no directions");
  std::set<int> seen;
  for (int d : directions) {
    if (d < 0 || d > 5) throw Error("AllocationOptions: direction out of range");
    if (!seen.insert(d).second) throw Error("AllocationOptions: direction repeated");
  }
  if (candidates.empty()) throw Error("AllocationOptions: no candidate joints");
  if (actuator_stiffness.size() != candidates.size())
    throw Error("AllocationOptions: one actuator stiffness per candidate expected");
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const auto& c = candidates[i];
    if (c.joint < 0 || c.joint >= static_cast<int>(model.joints.size()) || c.coordinate < 0 ||
        c.coordinate >= model.joints[c.joint].coordinates())
      throw Error("AllocationOptions: candidate out of range");
    if (!(actuator_stiffness[i] > 0.0)) throw Error("AllocationOptions: actuator stiffness must be positive");
  }
  if (terms.empty()) throw Error("AllocationOptions: no structural terms");
  if (!(singular_tolerance > 0.0 && singular_tolerance < 1.0))
    throw Error("AllocationOptions: singular_tolerance must be in (0, 1)");
}

std::vector<std::vector<int>> combinations(int n, int k) {
  std::vector<std::vector<int>> out;
  if (k < 0 || k > n) return out;
  std::vector<int> c(k);
  for (int i = 0; i < k; ++i) c[i] = i;
  while (true) {
    out.push_back(c);
    int i = k - 1;
    while (i >= 0 && c[i] == n - k + i) --i;
    if (i < 0) break;
    ++c[i];
    for (int j = i + 1; j < k; ++j) c[j] = c[j - 1] + 1;
  }
  return out;
}

DirectionalStiffness condense_to_directions(const Model& model, const DofMap& map, const SparseMatrix& K, int node,
                                            const std::vector<int>& dirs) {
  DirectionalStiffness out;
  std::vector<int> raw;
  for (int d : dirs) raw.push_back(map.raw_node(node, d));
  const Condensation c = condense(map, K, raw);
  switch (c.outcome) {
    case Condensation::Outcome::HeldDof:
      out.message = "node '" + model.nodes[node].id + "' dof " + kDofNames[dirs[c.held]] +
                    " is held rigidly (supported, prescribed or fixed by rigid constraints): its stiffness is unbounded";
      return out;
    case Condensation::Outcome::NotConverged:  // the iterative route is not used here
    case Condensation::Outcome::Mechanism:
      out.message = "holding node '" + model.nodes[node].id +
                    "' in the requested directions leaves a mechanism, or a direction is not independent of the "
                    "constraints";
      return out;
    case Condensation::Outcome::Succeeded:
      break;
  }
  out.K = c.K;
  out.ok = true;
  return out;
}

void apply_node_positions(Model& model, const std::vector<std::pair<int, Vec3>>& positions) {
  const int nn = static_cast<int>(model.nodes.size());
  std::vector<char> set(nn, 0);
  for (const auto& [n, x] : positions) {
    model.nodes.at(n).x = x;
    set[n] = 1;
  }
  // Joint partners follow (transitively) unless overridden themselves.
  bool changed = true;
  while (changed) {
    changed = false;
    for (const auto& j : model.joints) {
      for (int s = 0; s < 2; ++s) {
        const int a = j.nodes[s], b = j.nodes[1 - s];
        if (set[a] && !set[b]) {
          model.nodes[b].x = model.nodes[a].x;
          set[b] = 1;
          changed = true;
        }
      }
    }
  }
  for (const auto& mem : model.members) {
    const Vec3 x1 = model.nodes[mem.nodes[0]].x, x2 = model.nodes[mem.nodes[1]].x;
    if (!((x2 - x1).norm() > 1e-12 * model.length_scale()))
      throw ModelError("element '" + mem.id + "'", "zero length in this pose");
    for (std::size_t k = 0; k + 1 < mem.elements.size(); ++k) {
      const int inner = model.elements[mem.elements[k]].nodes[1];
      model.nodes[inner].x = x1 + (x2 - x1) * (static_cast<double>(k + 1) / static_cast<double>(mem.elements.size()));
    }
  }
  for (const auto& j : model.joints)
    if ((model.nodes[j.nodes[0]].x - model.nodes[j.nodes[1]].x).norm() > 1e-9 * model.length_scale())
      throw ModelError("joint '" + j.id + "'", "nodes '" + model.nodes[j.nodes[0]].id + "' and '" +
                                                   model.nodes[j.nodes[1]].id + "' do not coincide in this pose");
}

Model scheme_model(const Model& model, const AllocationOptions& o, const std::vector<int>& actuated, SchemeLinks links,
                   SchemeActuators role, const LoadSet& loads) {
  Model m = model;
  m.set_default_loads(loads);
  for (auto& p : m.prescribed) p.value = 0.0;
  if (links == SchemeLinks::Rigid) {
    for (auto& e : m.elements) e.type = MemberType::Rigid;
    for (auto& mem : m.members) mem.type = MemberType::Rigid;
  }
  for (const auto& c : o.candidates) m.joints[c.joint].stiffness[c.coordinate] = 0.0;
  for (int i : actuated) {
    const auto& c = o.candidates[i];
    if (role == SchemeActuators::Springs) {
      m.joints[c.joint].stiffness[c.coordinate] = o.actuator_stiffness[i];
    } else {
      // Drop any user prescription of the same coordinate: it is frozen at zero here.
      const DofRef d{DofRef::Owner::Joint, c.joint, c.coordinate};
      std::erase_if(m.prescribed, [&](const Prescribed& p) { return p.dof == d; });
      m.prescribed.push_back({d, 0.0});
    }
  }
  return m;
}

namespace {

SparseMatrix assemble_K(const Model& m, const DofMap& map) {
  const LinearStructure structure(m);
  SystemAssembler assembler(map);
  assembler.begin();
  structure.assemble(map, assembler);
  assembler.end();
  return assembler.K_ff();
}

std::string actuator_names(const Model& m, const AllocationOptions& o, const std::vector<int>& actuated) {
  std::string s;
  for (int i : actuated) {
    const auto& c = o.candidates[i];
    if (!s.empty()) s += ", ";
    s += m.joints[c.joint].id;
    if (m.joints[c.joint].coordinates() > 1) {
      s += ':';
      s += std::to_string(c.coordinate);
    }
  }
  return s;
}

// Integral over [0, L] of the product of two linear functions (a1..b1) and (a2..b2).
double linear_product(double L, double a1, double b1, double a2, double b2) {
  return L / 6.0 * (2.0 * a1 * a2 + a1 * b2 + b1 * a2 + 2.0 * b1 * b2);
}

// The Jacobian J of eqs. 1-10 (out.J, out.jacobian_ok, or out.jacobian_message why not): rigid links,
// actuated coordinates prescribed (one at 1, the others locked at 0).
void actuation_jacobian(const Model& model, const AllocationOptions& o, const std::vector<int>& actuated,
                        ActuatedStiffness& out) {
  const int nd = static_cast<int>(o.directions.size());
  const int na = static_cast<int>(actuated.size());
  const int P = o.platform_node;
  const double L = model.length_scale();
  {
    const Model m = scheme_model(model, o, actuated, SchemeLinks::Rigid, SchemeActuators::Frozen);
    const DofMap map(m);
    // Which prescribed values are the actuators.
    std::vector<int> pidx(na, -1);
    for (int k = 0; k < na; ++k) {
      const auto& c = o.candidates[actuated[k]];
      pidx[k] = map.prescribed_index(map.raw_joint(c.joint, c.coordinate));
    }
    // A free DOF that moves the platform: the actuators do not determine the platform's motion.
    std::string loose;
    for (int d : o.directions) {
      const int raw = map.raw_node(P, d);
      const double scale = d < 3 ? L : 1.0;  // translation per radian of a joint coordinate
      for (SparseRowMatrix::InnerIterator it(map.T_free(), raw); it; ++it) {
        const DofRef f = map.free_dofs()[it.col()];
        const double s = (f.owner == DofRef::Owner::Node && f.comp < 3) ? 1.0 : scale;
        if (std::abs(it.value()) > 1e-9 * s) {
          const std::string name = m.describe(f);
          if (loose.find(name) != std::string::npos) continue;
          if (!loose.empty()) loose += ", ";
          loose += name;
        }
      }
    }
    if (!loose.empty()) {
      out.jacobian_message = "with the actuators (" + actuator_names(model, o, actuated) +
                             ") locked the platform can still move: free " + loose;
    } else {
      out.J.resize(nd, na);
      const Eigen::VectorXd uf = Eigen::VectorXd::Zero(map.free_size());
      std::string conflict;
      for (int k = 0; k < na && conflict.empty(); ++k) {
        Eigen::VectorXd up = Eigen::VectorXd::Zero(map.prescribed_size());
        up[pidx[k]] = 1.0;
        conflict = map.check_consistency(up);
        const Eigen::VectorXd u = map.expand(uf, up);
        for (int i = 0; i < nd; ++i) out.J(i, k) = u[map.raw_node(P, o.directions[i])];
      }
      if (!conflict.empty()) {
        out.jacobian_message = "redundant actuation: the actuators (" + actuator_names(model, o, actuated) +
                               ") cannot move one at a time (" + conflict + "); J is not defined";
        out.J.resize(0, 0);
      } else {
        out.jacobian_ok = true;
      }
    }
  }
}

// K_A from J (eq. 10, or its forms for a J that is not square), where J could be formed.
void stiffness_from_jacobian(const AllocationOptions& o, const std::vector<int>& actuated, ActuatedStiffness& out) {
  const int nd = static_cast<int>(o.directions.size());
  const int na = static_cast<int>(actuated.size());
  if (!out.jacobian_ok) return;
  {
    Eigen::VectorXd kI(na);
    for (int k = 0; k < na; ++k) kI[k] = o.actuator_stiffness[actuated[k]];
    const Eigen::MatrixXd& J = out.J;
    if (nd == na) {
      out.det_J = J.determinant();
      double norms = 1.0;
      for (int k = 0; k < na; ++k) norms *= J.col(k).norm();
      if (!(std::abs(out.det_J) > o.singular_tolerance * norms)) {
        out.jacobian_message = fmt::format(
            "J is singular (det J = {:.3g}): the actuators cannot move the platform in every requested direction", out.det_J);
      } else {
        const Eigen::MatrixXd Ji = J.inverse();
        out.K_jacobian = Ji.transpose() * kI.asDiagonal() * Ji;  // eq. 10
        out.form = "eq10";
        out.jacobian_message = "K_A = J^-T K_I J^-1 (eq. 10)";
      }
    } else {
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(J);
      const auto& s = svd.singularValues();
      const int rank = static_cast<int>((s.array() > o.singular_tolerance * s[0]).count());
      if (s.size() == 0 || s[0] == 0.0 || rank < std::min(nd, na)) {
        out.jacobian_message = fmt::format("J ({}x{}) is rank deficient (rank {})", nd, na, rank);
      } else if (nd < na) {
        // More actuators than requested directions: the actuated compliance J K_I^-1 J^T
        // restricted to the directions, inverted (equals eq. 10 when J is square).
        const Eigen::MatrixXd C = J * kI.cwiseInverse().asDiagonal() * J.transpose();
        out.K_jacobian = C.inverse();
        out.form = "compliance_restricted";
        out.jacobian_message = fmt::format(
            "J is {}x{} (fewer directions than actuators): K_A = (J K_I^-1 J^T)^-1, the actuated compliance restricted "
            "to the requested directions",
            nd, na);
      } else {
        // Lower mobility in the requested directions: eq. 9 in its pseudo-inverse form.
        const Eigen::MatrixXd Jp = (J.transpose() * J).inverse() * J.transpose();
        out.K_jacobian = Jp.transpose() * kI.asDiagonal() * Jp;
        out.form = "eq9_pseudo_inverse";
        out.jacobian_message = fmt::format(
            "J is {}x{} (not square): eq. 10 does not apply; K_A = J^+T K_I J^+ (eq. 9, pseudo-inverse form), the "
            "stiffness within the range of J; directions outside it are held by the mechanism's constraints",
            nd, na);
      }
    }
  }
}

}  // namespace

ActuatedStiffness actuated_stiffness(const Model& model, const AllocationOptions& o, const std::vector<int>& actuated) {
  ActuatedStiffness out;
  const int P = o.platform_node;
  actuation_jacobian(model, o, actuated, out);  // (a)
  stiffness_from_jacobian(o, actuated, out);
  // (b) Condensed stiffness of the rigid model with actuator springs.
  {
    const Model m = scheme_model(model, o, actuated, SchemeLinks::Rigid, SchemeActuators::Springs);
    const DofMap map(m);
    const SparseMatrix K = assemble_K(m, map);
    DirectionalStiffness ds = condense_to_directions(m, map, K, P, o.directions);
    out.condensed_ok = ds.ok;
    out.condensed_message = ds.ok ? "condensed stiffness of the rigid model with actuator springs" : ds.message;
    if (ds.ok) out.K_condensed = ds.K;
  }
  return out;
}

namespace {

// The virtual-force compliance of eq. 12 (out.C_terms, out.links) for the unit-load end forces
// f[i][e] of each direction i and element e; section forces: start = -f1, end = f2 (N, Qy, Qz, T
// constant, My, Mz linear along a beam without member loads).
void virtual_force(const Model& m, const LinearStructure& structure, const std::vector<std::vector<Vec12>>& f,
                   StructuralStiffness& out) {
  const int nd = static_cast<int>(f.size());
  const int ne = static_cast<int>(m.elements.size());
  for (auto& c : out.C_terms) c = Eigen::MatrixXd::Zero(nd, nd);
  std::vector<int> member_row(m.members.size(), -1);
  for (int e = 0; e < ne; ++e) {
    const auto& beam = structure.beam(e);
    if (!beam) continue;
    const auto& el = m.elements[e];
    const auto& mat = m.materials[el.material];
    const auto& sec = m.sections[el.section];
    const double Le = beam->length();
    // Shear factor k of eq. 12: the section's (default by shape), 1 when none was given.
    const double ky = sec.ky > 0.0 ? sec.ky : 1.0, kz = sec.kz > 0.0 ? sec.kz : 1.0;
    const double flex[6] = {Le / (mat.E * sec.A), ky * Le / (mat.G * sec.A), kz * Le / (mat.G * sec.A),
                            Le / (mat.G * sec.J), 1.0 / (mat.E * sec.Iy), 1.0 / (mat.E * sec.Iz)};
    int row = -1;
    if (el.member >= 0) {
      if (member_row[el.member] < 0) {
        member_row[el.member] = static_cast<int>(out.links.size());
        LinkIntegrals li;
        li.member = el.member;
        li.raw.assign(nd, {});
        li.compliance.assign(nd, {});
        out.links.push_back(li);
      }
      row = member_row[el.member];
    }
    for (int i = 0; i < nd; ++i) {
      const Vec12& fi = f[i][e];
      for (int j = 0; j < nd; ++j) {
        const Vec12& fj = f[j][e];
        double I[6];
        for (int k = 0; k < 4; ++k) I[k] = fi[6 + k] * fj[6 + k];  // constant: (-f1)(-f1) = f2 f2
        I[4] = linear_product(Le, -fi[4], fi[10], -fj[4], fj[10]);
        I[5] = linear_product(Le, -fi[5], fi[11], -fj[5], fj[11]);
        double c[6];
        for (int k = 0; k < 6; ++k) c[k] = I[k] * flex[k];
        const double term[kStructuralTermCount] = {c[0], c[1] + c[2], c[3], c[4] + c[5]};
        for (int t = 0; t < kStructuralTermCount; ++t) out.C_terms[t](i, j) += term[t];
        if (i == j && row >= 0) {
          auto& li = out.links[row];
          for (int k = 0; k < 4; ++k) li.raw[i][k] += I[k] * Le;  // integral of a constant
          li.raw[i][4] += I[4];
          li.raw[i][5] += I[5];
          for (int t = 0; t < kStructuralTermCount; ++t) li.compliance[i][t] += term[t];
        }
      }
    }
  }
}

}  // namespace

StructuralStiffness structural_stiffness(const Model& model, const AllocationOptions& o, const std::vector<int>& actuated) {
  StructuralStiffness out;
  const int nd = static_cast<int>(o.directions.size());
  const int P = o.platform_node;
  const Model m = scheme_model(model, o, actuated, SchemeLinks::Flexible, SchemeActuators::Frozen);
  const DofMap map(m);
  const LinearStructure structure(m);
  SystemAssembler assembler(map);
  assembler.begin();
  structure.assemble(map, assembler);
  assembler.end();
  const SparseMatrix& K = assembler.K_ff();
  const std::unique_ptr<LinearSolver> factor = make_linear_solver();
  const bool has_free = map.free_size() > 0;  // none: every DOF rigidly held (rigid links, frozen actuators)
  const FactorStatus fs = has_free ? factor->compute(K) : FactorStatus::Succeeded;
  if (fs != FactorStatus::Succeeded) {
    out.modes = zero_energy_modes(m, map, K, 12);
    if (!out.modes.empty()) {
      out.message = "with " + actuator_names(model, o, actuated) + " frozen, " + describe_mechanism(out.modes);
      return out;
    }
    if (fs == FactorStatus::Singular || !factor->usable()) {
      out.message = "the frozen structure's stiffness matrix could not be factorised";
      return out;
    }
  }
  // A direction no free DOF moves is held rigidly (through rigid links and frozen actuators): the
  // unit load there meets no elastic DOF, its displacements and end forces are zero, C_S = 0.
  std::string held;
  for (int i = 0; i < nd; ++i) {
    bool any = false;
    for (SparseRowMatrix::InnerIterator it(map.T_free(), map.raw_node(P, o.directions[i])); it; ++it)
      any = any || it.value() != 0.0;
    if (!any) {
      out.held.push_back(i);
      held += std::string(held.empty() ? "" : " ") + kDofNames[o.directions[i]];
    }
  }
  // Unit loads (eq. 11): one solve per direction; displacements and element end forces.
  const Eigen::VectorXd up = Eigen::VectorXd::Zero(map.prescribed_size());
  out.C_fea = Eigen::MatrixXd::Zero(nd, nd);
  const int ne = static_cast<int>(m.elements.size());
  std::vector<std::vector<Vec12>> f(nd, std::vector<Vec12>(ne, Vec12::Zero()));
  for (int i = 0; i < nd; ++i) {
    Eigen::VectorXd f_raw = Eigen::VectorXd::Zero(map.raw_size());
    f_raw[map.raw_node(P, o.directions[i])] = 1.0;
    const Eigen::VectorXd uf =
        has_free ? Eigen::VectorXd(factor->solve(map.reduce(f_raw))) : Eigen::VectorXd::Zero(0);
    const Eigen::VectorXd u = map.expand(uf, up);
    for (int j = 0; j < nd; ++j) out.C_fea(j, i) = u[map.raw_node(P, o.directions[j])];
    for (int e = 0; e < ne; ++e) f[i][e] = structure.end_forces(map, e, u);
  }
  out.C_fea = 0.5 * (out.C_fea + out.C_fea.transpose());
  virtual_force(m, structure, f, out);
  out.C = Eigen::MatrixXd::Zero(nd, nd);
  for (auto t : o.terms) out.C += out.C_terms[static_cast<int>(t)];
  const Eigen::MatrixXd C_eb = out.C_terms[0] + out.C_terms[2] + out.C_terms[3];
  out.fea_mismatch = (C_eb - out.C_fea).cwiseAbs().maxCoeff() / std::max(out.C_fea.cwiseAbs().maxCoeff(), 1e-300);
  if (out.held.empty()) {
    const DirectionalStiffness ds = condense_to_directions(m, map, K, P, o.directions);
    if (ds.ok) out.K_fea = ds.K;
  }
  out.ok = true;
  out.message = fmt::format("frozen structure stable; virtual force vs FEA: {:.2e}", out.fea_mismatch);
  if (!held.empty())
    out.message += "; node '" + m.nodes[P].id + "' is held rigidly in " + held +
                   " by the frozen structure (rigid links): C_S = 0 there, the total stiffness is the actuated one";
  return out;
}

SchemeResult evaluate_scheme(const Model& model, const AllocationOptions& o, const std::vector<int>& actuated) {
  o.validate(model);
  SchemeResult r;
  r.actuated = actuated;
  r.structural = structural_stiffness(model, o, actuated);
  r.actuated_stiffness = actuated_stiffness(model, o, actuated);
  const auto& A = r.actuated_stiffness;
  if (!r.structural.ok) {
    r.status = "mechanism";
    r.message = r.structural.message;
  } else if (!A.ok()) {
    r.status = A.jacobian_message.rfind("redundant", 0) == 0 ? "redundant" : "singular";
    r.message = A.jacobian_message;
  } else {
    r.status = "ok";
    r.valid = true;
    r.message = A.jacobian_message + "; " + r.structural.message;
  }
  if (!r.structural.ok || !(A.ok() || A.condensed_ok)) return r;

  // Totals (eq. 19 and the consistent matrix form).
  const int nd = static_cast<int>(o.directions.size());
  const Eigen::MatrixXd& KA = A.K();
  const Eigen::MatrixXd& CS = r.structural.C;
  auto& T = r.total;
  T.eq19.resize(nd);
  for (int d = 0; d < nd; ++d) {
    // Compliances in series: 1/K_d = 1/K_A,dd + C_S,dd (K_A,dd alone where C_S,dd = 0).
    const double ka = KA(d, d);
    T.eq19[d] = ka / (1.0 + ka * CS(d, d));
  }
  Eigen::FullPivLU<Eigen::MatrixXd> lu(KA);
  if (lu.isInvertible()) {
    T.K_series = (lu.inverse() + CS).inverse();
    T.ok = true;
    T.message = "C = K_A^-1 + C_S";
  } else {
    T.message = "K_A is singular: no compliance in series";
  }
  const Model m = scheme_model(model, o, actuated, SchemeLinks::Flexible, SchemeActuators::Springs);
  const DofMap map(m);
  const SparseMatrix K = assemble_K(m, map);
  const DirectionalStiffness ds = condense_to_directions(m, map, K, o.platform_node, o.directions);
  T.fea_ok = ds.ok;
  if (ds.ok) T.K_fea = ds.K;
  return r;
}

}  // namespace beamfea
