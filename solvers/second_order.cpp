#include "solvers/second_order.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/assembly.hpp"
#include "core/errors.hpp"
#include "solvers/buckling.hpp"
#include "solvers/initial_stress.hpp"
#include "solvers/member_loading.hpp"
#include "solvers/nonlinear_structure.hpp"
#include "solvers/sparse_factor.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

void SecondOrderOptions::validate() const {
  if (!(tolerance > 0.0 && tolerance < 1.0)) throw Error("SecondOrderOptions: tolerance must be in (0, 1)");
  if (max_iterations < 1) throw Error("SecondOrderOptions: max_iterations must be at least 1");
  if (!(singular_rcond > 0.0 && singular_rcond < 1.0)) throw Error("SecondOrderOptions: singular_rcond must be in (0, 1)");
}

const char* to_string(SecondOrderStatus s) {
  switch (s) {
    case SecondOrderStatus::Converged: return "converged";
    case SecondOrderStatus::Diverged: return "diverged";
    case SecondOrderStatus::NotConverged: return "not converged";
    case SecondOrderStatus::Mechanism: return "mechanism";
    case SecondOrderStatus::Failed: return "failed";
  }
  return "?";
}

bool has_behaviour_members(const Model& model) {
  return std::any_of(model.members.begin(), model.members.end(),
                     [](const Member& m) { return m.behaviour != MemberBehaviour::Both; });
}

double max_translation(const Model& model, const Eigen::VectorXd& u) {
  double best[2] = {0.0, 0.0};  // translations, rotations
  for (std::size_t n = 0; n < model.nodes.size(); ++n)
    for (int c = 0; c < 6; ++c) best[c / 3] = std::max(best[c / 3], std::abs(u[static_cast<Eigen::Index>(6 * n + c)]));
  return best[0] > 0.0 ? best[0] : best[1];
}

namespace {

// Local components of a global 12-vector (rows of R are the local axes).
Vec12 to_local(const Mat3& R, const Vec12& g) {
  Vec12 l;
  for (int b = 0; b < 4; ++b) l.segment<3>(3 * b) = R * g.segment<3>(3 * b);
  return l;
}

Vec12 gather(const std::array<int, 12>& dofs, const Eigen::VectorXd& u) {
  Vec12 ue;
  for (int k = 0; k < 12; ++k) ue[k] = u[dofs[k]];
  return ue;
}

// The members that carry one sign of axial force, and which of them are active.
class ActiveSet {
 public:
  explicit ActiveSet(const Model& model) : model_(model), active_(model.members.size(), 1) {}
  bool element_active(int e) const {
    const int m = model_.elements[e].member;
    return m < 0 || active_[m];
  }
  bool member_active(int m) const { return active_[m]; }
  std::vector<int> inactive() const {
    std::vector<int> out;
    for (std::size_t m = 0; m < active_.size(); ++m)
      if (!active_[m]) out.push_back(static_cast<int>(m));
    return out;
  }
  // Switches members by the signs of their forces (active) or chord elongations (inactive) at the
  // state u with element end forces f; true when the set changed.
  bool update(const Eigen::VectorXd& u, const std::vector<Vec12>& f) {
    double n_scale = 0.0, u_scale = max_translation(model_, u);
    for (const auto& fe : f) n_scale = std::max(n_scale, std::abs(0.5 * (fe[6] - fe[0])));
    bool changed = false;
    for (std::size_t m = 0; m < model_.members.size(); ++m) {
      const Member& mem = model_.members[m];
      if (mem.behaviour == MemberBehaviour::Both || mem.elements.empty()) continue;
      const double sign = mem.behaviour == MemberBehaviour::TensionOnly ? 1.0 : -1.0;
      if (active_[m]) {
        double N = 0.0;
        for (const int e : mem.elements) N += 0.5 * (f[e][6] - f[e][0]);
        N /= static_cast<double>(mem.elements.size());
        if (sign * N < -kSlackRelative * n_scale) active_[m] = 0, changed = true;
      } else {
        const Vec3 a = model_.nodes[mem.nodes[0]].x, b = model_.nodes[mem.nodes[1]].x;
        const Vec3 ua = u.segment<3>(6 * mem.nodes[0]), ub = u.segment<3>(6 * mem.nodes[1]);
        const double elongation = (ub - ua).dot((b - a).normalized());
        if (sign * elongation > kSlackRelative * u_scale) active_[m] = 1, changed = true;
      }
    }
    return changed;
  }
  // The interior nodes of inactive meshed members follow the chord between the member's ends.
  void draw_along_chords(Eigen::VectorXd& u) const {
    for (std::size_t m = 0; m < model_.members.size(); ++m) {
      const Member& mem = model_.members[m];
      if (active_[m] || mem.elements.size() < 2) continue;
      const Vec3 a = model_.nodes[mem.nodes[0]].x;
      const double L = (model_.nodes[mem.nodes[1]].x - a).norm();
      const Vec6 ua = u.segment<6>(6 * mem.nodes[0]), ub = u.segment<6>(6 * mem.nodes[1]);
      for (std::size_t k = 1; k < mem.elements.size(); ++k) {
        const int n = model_.elements[mem.elements[k]].nodes[0];
        const double t = (model_.nodes[n].x - a).norm() / L;
        u.segment<6>(6 * n) = (1.0 - t) * ua + t * ub;
      }
    }
  }

 private:
  const Model& model_;
  std::vector<char> active_;
};

// What changes between solves: K_t = K + A, A = sum over beams of K_g,e (active) or of H_e - K_e
// (inactive: its stiffness out, H_e holding the member's interior nodes by K_e's diagonal there).
// One add per beam in every pass, so the pattern (K's blocks) and the positions are reused.
class Increment {
 public:
  // `geometric`: K_g will be asked for (the rigid links' and joints' part needs their structure).
  Increment(const Model& model, const DofMap& map, const LinearStructure& structure, bool geometric)
      : model_(model), map_(map), structure_(structure), a_(map) {
    const bool constrained = std::any_of(model.elements.begin(), model.elements.end(),
                                         [](const Element& e) { return e.type == MemberType::Rigid; }) ||
                             !model.joints.empty();
    if (geometric && constrained) ns_.emplace(model);
  }
  // A for the active set, with K_g of the end forces f (none when f is null).
  void assemble(const ActiveSet& set, const std::vector<Vec12>* f, GeometricStiffness kind) {
    a_.begin();
    for (std::size_t e = 0; e < model_.elements.size(); ++e) {
      const FrameElement* beam = structure_.beam(static_cast<int>(e));
      if (!beam) continue;
      const auto dofs = structure_.element_dofs(map_, static_cast<int>(e));
      if (set.element_active(static_cast<int>(e))) {
        a_.add(dofs, f ? beam->geometric_stiffness((*f)[e], kind) : Mat12::Zero());
        continue;
      }
      const Mat12 k = beam->stiffness();
      Mat12 h = -k;
      const Element& el = model_.elements[e];
      for (int j = 0; j < 2; ++j)
        if (model_.nodes[el.nodes[j]].member == el.member)
          for (int c = 6 * j; c < 6 * j + 6; ++c) h(c, c) += k(c, c);
      a_.add(dofs, h);
    }
    a_.end();
  }
  const SystemAssembler& matrices() const { return a_; }
  // Whether K_g has a rigid links' and joints' part.
  bool has_constraints() const { return ns_.has_value(); }
  // The rigid links' and joints' part of K_g for the raw residual r (symmetrised), or null.
  std::optional<SparseMatrix> constraints(const Eigen::VectorXd& r) const {
    if (!ns_) return std::nullopt;
    const SparseMatrix G = constraint_geometric_stiffness(*ns_, map_, r);
    if (G.nonZeros() == 0) return std::nullopt;
    return SparseMatrix(0.5 * (G + SparseMatrix(G.transpose())));
  }

 private:
  const Model& model_;
  const DofMap& map_;
  const LinearStructure& structure_;
  SystemAssembler a_;
  std::optional<NonlinearStructure> ns_;
};

// One iterate: displacements, end forces (K_g u included), reactions, joint forces.
struct StateWriter {
  const Model& model;
  const DofMap& map;
  const LinearStructure& structure;

  // `kg_forces`: the end forces K_g was made of (null: no K_g). f_raw the external force; r is
  // written over with the raw residual f_int - f_ext (the reactions).
  void write(const ActiveSet& set, const std::vector<Vec12>* kg_forces, GeometricStiffness kind,
             const Eigen::VectorXd& f_raw, const std::vector<ElementLoads>& loads, LinearStaticResult& res,
             Eigen::VectorXd& r) const {
    res.free_dofs = map.free_size();
    res.element_loads = loads;
    res.end_forces.assign(model.elements.size(), Vec12::Zero());
    r.setZero(map.raw_size());
    for (std::size_t e = 0; e < model.elements.size(); ++e) {
      const FrameElement* beam = structure.beam(static_cast<int>(e));
      if (!beam || !set.element_active(static_cast<int>(e))) continue;
      const auto dofs = structure.element_dofs(map, static_cast<int>(e));
      const Vec12 ue = gather(dofs, res.u);
      Vec12 fg = beam->stiffness() * ue;
      res.end_forces[e] = beam->local_end_forces(ue);
      if (kg_forces) {
        const Vec12 fk = beam->geometric_stiffness((*kg_forces)[e], kind) * ue;
        fg += fk;
        res.end_forces[e] += to_local(beam->axes(), fk);
      }
      for (int k = 0; k < 12; ++k) r[dofs[k]] += fg[k];
      if (!loads[e].empty()) res.end_forces[e] -= beam->equivalent_loads(loads[e]);
    }
    for (std::size_t j = 0; j < model.joints.size(); ++j) {
      const auto& jt = model.joints[j];
      if (!jt.has_stiffness()) continue;
      const int q = map.raw_joint(static_cast<int>(j), 0);
      r.segment(q, jt.coordinates()) += jt.stiffness_as_matrix() * res.u.segment(q, jt.coordinates());
    }
    r -= f_raw;
    const DofMap::ConstraintForces cf = map.constraint_forces(r);
    set_constraint_results(model, map, cf, res);
    res.joint_forces = cf.joint;
    res.statically_indeterminate = map.redundant_constraints();
    res.modes.clear();
    res.status = SolveStatus::Succeeded;
  }
};

double max_axial_change(const std::vector<Vec12>& a, const std::vector<Vec12>& b, double& scale) {
  double change = 0.0;
  scale = 0.0;
  for (std::size_t e = 0; e < a.size(); ++e) {
    const double na = 0.5 * (a[e][6] - a[e][0]), nb = 0.5 * (b[e][6] - b[e][0]);
    change = std::max(change, std::abs(na - nb));
    scale = std::max(scale, std::abs(na));
  }
  return change;
}

std::string member_names(const Model& model, const std::vector<int>& members) {
  std::string out;
  for (const int m : members) out += (out.empty() ? "'" : ", '") + model.members[m].id + "'";
  return out;
}

}  // namespace

SecondOrderResult solve_second_order(const Model& model, const LoadSet& loads, const SecondOrderOptions& options) {
  options.validate();
  SecondOrderResult res;
  const DofMap map(model);
  const Eigen::VectorXd up = map.prescribed_values();
  if (auto conflict = map.check_consistency(up); !conflict.empty()) throw ModelError("supports and prescribed values", conflict);
  const LinearStructure structure(model);
  SystemAssembler ka(map);
  structure.assemble_stiffness(map, ka);
  const SparseMatrix& K = ka.K_ff();
  Increment increment(model, map, structure, options.geometric);
  ActiveSet set(model);
  const StateWriter writer{model, map, structure};
  FactorOptions fo;
  fo.singular_rcond = options.singular_rcond;
  SparseFactor factor(fo);
  PatternMemory pattern;

  std::vector<ElementLoads> eloads;
  Eigen::VectorXd f_raw, f, u_free(map.free_size()), residual, kg_residual;
  // The end forces K_g is made of: the last iterate's (zero before the linear step).
  std::vector<Vec12> kg_forces(model.elements.size(), Vec12::Zero());
  LinearStaticResult& sol = res.solution;
  std::optional<SparseMatrix> constraint_kg;
  const auto fail = [&](SecondOrderStatus status, std::string message) {
    res.status = status;
    res.message = std::move(message);
    sol.status = status == SecondOrderStatus::Mechanism ? SolveStatus::Mechanism : SolveStatus::Failed;
    sol.message = res.message;
    res.inactive_members = set.inactive();
    return res;
  };

  // The linear phase solves without K_g until the slack members settle (one solve without them):
  // its last solution is the linear step, linear statics' answer. K_g joins after it.
  bool linear_phase = true;
  for (int k = 0;; ++k) {
    const bool geometric = options.geometric && !linear_phase;
    increment.assemble(set, geometric ? &kg_forces : nullptr, options.kind);
    SparseMatrix Kt = K + increment.matrices().K_ff();
    if (geometric && constraint_kg) Kt += *constraint_kg;
    element_loads(model, loads, eloads);
    for (std::size_t e = 0; e < eloads.size(); ++e)
      if (!set.element_active(static_cast<int>(e))) eloads[e] = ElementLoads{};
    external_force(model, map, loads, eloads, f_raw);
    map.reduce(f_raw, f);
    if (map.prescribed_size() > 0) f -= (ka.K_fp() + increment.matrices().K_fp()) * up;

    if (!pattern.same_or_remember(Kt)) ++res.symbolic_analyses;
    const FactorStatus fs = factor.factorize(Kt, fo);
    ++res.factorizations;
    if (fs == FactorStatus::TooLarge)
      return fail(SecondOrderStatus::Failed,
                  fmt::format("the factorisation of {} free DOFs is too large for CHOLMOD's symbolic analysis", map.free_size()));
    if (fs != FactorStatus::Succeeded) {
      // Without K_g: a mechanism, or an ill-conditioned stiffness that stands (as linear statics).
      // With K_g: a mechanism of the members left, or a load above the critical load.
      SparseMatrix K_active = Kt;  // the stiffness of the active members, without K_g
      if (geometric) {
        increment.assemble(set, nullptr, options.kind);
        K_active = K + increment.matrices().K_ff();
      }
      sol.modes = zero_energy_modes(model, map, K_active, 12, options.zero_energy_tolerance);
      if (!sol.modes.empty()) {
        const std::vector<int> slack = set.inactive();
        return fail(SecondOrderStatus::Mechanism,
                    slack.empty() ? describe_mechanism(sol.modes)
                                  : fmt::format("without the slack members {} the structure is a {}", member_names(model, slack),
                                                describe_mechanism(sol.modes)));
      }
      if (geometric) {
        BucklingOptions bo;
        bo.modes = 1;
        bo.geometric_stiffness = options.kind;
        const BucklingResult b = solve_buckling(model, loads, bo);
        res.critical_load_factor =
            b.status == BucklingStatus::Succeeded ? b.load_factors[0] : std::numeric_limits<double>::quiet_NaN();
        return fail(SecondOrderStatus::Diverged,
                    fmt::format("second-order analysis diverged: load above the critical load factor {:.6g}",
                                res.critical_load_factor));
      }
      if (fs == FactorStatus::Singular || !factor.usable())
        return fail(SecondOrderStatus::Failed, "the stiffness matrix could not be factorised");
    }
    factor.solve(f, u_free);
    map.expand(u_free, up, sol.u);
    writer.write(set, geometric ? &kg_forces : nullptr, options.kind, f_raw, eloads, sol, residual);
    res.iterations = k;

    // Converged: the active set stays, and (second order) the axial forces stopped changing
    // (the linear step's, against zero: converged only when there are none).
    const bool changed = set.update(sol.u, sol.end_forces);
    if (linear_phase && !changed) {
      res.linear = sol;
      set.draw_along_chords(res.linear.u);
    }
    // Where rigid links or joints transmit forces (their part of K_g), those forces too: the raw
    // residual f_int - f_ext that their curvature is made of.
    bool converged = !changed;
    if (options.geometric && converged) {
      double scale = 0.0;
      const double change = max_axial_change(sol.end_forces, linear_phase ? sol.end_forces : kg_forces, scale);
      converged = scale == 0.0 || (!linear_phase && change <= options.tolerance * scale);
      if (increment.has_constraints()) {
        const double r_scale = residual.cwiseAbs().maxCoeff();
        const double r_change = linear_phase ? r_scale : (residual - kg_residual).cwiseAbs().maxCoeff();
        converged = converged && (r_scale == 0.0 || (!linear_phase && r_change <= options.tolerance * r_scale));
      }
    }
    linear_phase = linear_phase && changed;
    kg_forces = sol.end_forces;
    kg_residual = residual;
    if (options.geometric) constraint_kg = increment.constraints(residual);
    if (converged) break;
    if (k == options.max_iterations) {
      sol.status = SolveStatus::Failed;
      return fail(SecondOrderStatus::NotConverged,
                  fmt::format("{} did not converge in {} iterations{}", options.geometric ? "second-order analysis" : "linear static",
                              options.max_iterations, changed ? " (the set of slack members kept changing)" : ""));
    }
  }

  res.inactive_members = set.inactive();
  set.draw_along_chords(sol.u);
  const double lin = max_translation(model, res.linear.u), now = max_translation(model, sol.u);
  res.amplification = lin > 0.0 ? now / lin : 1.0;
  if (options.geometric) {
    increment.assemble(set, &kg_forces, options.kind);
    res.tangent = K + increment.matrices().K_ff();
    if (constraint_kg) res.tangent += *constraint_kg;
  }
  res.status = SecondOrderStatus::Converged;
  const std::string slack =
      res.inactive_members.empty() ? "" : fmt::format(", slack members {}", member_names(model, res.inactive_members));
  res.message = options.geometric
                    ? fmt::format("second order: {} free DOFs, {} iterations, amplification {:.6g}, max |u| = {:.6g}{}",
                                  map.free_size(), res.iterations, res.amplification, now, slack)
                    : fmt::format("linear static: {} free DOFs, max |u| = {:.6g}, {} solves{}", map.free_size(), now,
                                  res.iterations + 1, slack);
  sol.message = res.message;
  return res;
}

std::optional<SparseMatrix> loaded_tangent(const Model& model, const DofMap& map, const LinearStructure& structure,
                                           const SparseMatrix& K, const LoadSet& loads, const PreloadOptions& options,
                                           std::string& message) {
  if (options.about == Equilibrium::SecondOrder) {
    SecondOrderOptions so;
    so.kind = options.geometric_stiffness;
    SecondOrderResult r = solve_second_order(model, loads, so);
    if (r.status != SecondOrderStatus::Converged) {
      message = "the second-order equilibrium of the preload failed: " + r.message;
      return std::nullopt;
    }
    return std::move(r.tangent);
  }
  const LinearStaticResult lin = LinearSystem(model).solve(loads);
  if (lin.status != SolveStatus::Succeeded) {
    message = "the linear static solution of the preload failed: " + lin.message;
    return std::nullopt;
  }
  const SparseMatrix Kg = geometric_stiffness(model, map, structure, lin, loads, options.geometric_stiffness);
  // Symmetric part: the skew part from applied moments is dropped, as in buckling.
  return SparseMatrix(K + SparseMatrix(0.5 * (Kg + SparseMatrix(Kg.transpose()))));
}

}  // namespace beamfea
