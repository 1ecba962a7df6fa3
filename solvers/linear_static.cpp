#include "solvers/linear_static.hpp"

#include <fmt/format.h>

#include <iterator>
#include <limits>

#include "core/assembly.hpp"
#include "core/errors.hpp"
#include "solvers/member_loading.hpp"
#include "solvers/near_null_space.hpp"
#include "solvers/sparse_factor.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

const char* to_string(SolveStatus s) {
  switch (s) {
    case SolveStatus::Succeeded: return "converged";
    case SolveStatus::Mechanism: return "mechanism";
    case SolveStatus::Failed: return "failed";
    case SolveStatus::NotConverged: return "not converged";
  }
  return "?";
}

void LinearStaticOptions::validate() const {
  if (!(singular_rcond > 0.0 && singular_rcond < 1.0)) throw Error("LinearStaticOptions: singular_rcond must be in (0, 1)");
  if (!(zero_energy_tolerance > 0.0)) throw Error("LinearStaticOptions: zero_energy_tolerance must be positive");
}

namespace {
// Free DOFs from which the element matrices and the pattern's analysis run on two threads when the
// caller gives them (LinearStaticOptions::parallel); below, both together take a few
// milliseconds, and a second thread would gain little.
constexpr int kParallelMinDofs = 2000;
}  // namespace

struct LinearSystem::Impl {
  explicit Impl(const Model& m) : map(m), assembler(map, SystemAssembler::Passes::One) {}
  DofMap map;
  LinearStructure structure;
  SystemAssembler assembler;
  SparseFactor factor;
  std::unique_ptr<PetscSolver> iterative;  // when the model's "solver" chose it (then no factor)
  Eigen::VectorXd up;
  LinearStaticResult failure;  // status != Converged when the system cannot be solved
  // K_ff whole: the assembled one, or, where this process assembled only its share (a distributed
  // solve), one assembled whole into `holder` (for the diagnosis of a mechanism, which reads all).
  const SparseMatrix& whole_K_ff(SparseMatrix& holder) const {
    if (assembler.owned().all()) return assembler.K_ff();
    SystemAssembler all(map);
    structure.assemble_stiffness(map, all);
    holder = all.K_ff();
    return holder;
  }
};

LinearSystem::~LinearSystem() = default;

LinearSystem::LinearSystem(const Model& model, const LinearStaticOptions& options)
    : model_(&model), impl_(std::make_unique<Impl>(model)), zero_energy_tolerance_(options.zero_energy_tolerance) {
  options.validate();
  Impl& s = *impl_;
  s.up = s.map.prescribed_values();
  if (auto conflict = s.map.check_consistency(s.up); !conflict.empty()) throw ModelError("supports and prescribed values", conflict);
  FactorOptions fo;
  fo.singular_rcond = options.singular_rcond;
  // K_ff's pattern follows from the DOF map and the connectivity alone (core/assembly.hpp,
  // planned_pattern): it is ordered and analysed (the part of the factorisation that reads no
  // value) while the element matrices are computed and assembled into it, without triplets to
  // sort. The two tasks share K_ff: the analysis reads its pattern, the assembly writes its values.
  // Below kParallelMinDofs they run one after the other: a second thread would gain little.
  const bool iterative = solves_iteratively(model.solver, s.map.free_size());
  // One model on several processes (`beamfea run` under mpirun): each assembles only the columns
  // of K_ff (and rows of K_fp) of the rows its iterative solve owns, from the elements that reach
  // them: about 1/processes of the matrix and of the element matrices each.
  OwnedColumns owned;
  if (iterative && petsc_processes() > 1) {
    const ProcessRows rows = petsc_process_rows(s.map.free_size(), node_block_size(s.map));
    owned = {static_cast<int>(rows.first), static_cast<int>(rows.first + rows.count)};
    s.assembler.own(owned);
  }
  s.assembler.plan(planned_pattern(s.map, LinearStructure::assembly_blocks(model, s.map), owned));
  const auto tasks = [&](std::size_t task) {
    if (task == 0) {
      s.structure.rebuild(model);
      s.assembler.begin();
      s.structure.assemble(s.map, s.assembler);
      s.assembler.end();
      return;
    }
    if (!iterative) s.factor.analyze(s.assembler.K_ff(), fo);
  };
  run_tasks(s.map.free_size() >= kParallelMinDofs && !iterative ? options.parallel : ParallelTasks{}, 2, tasks);
  const SparseMatrix& K = s.assembler.K_ff();
  LinearStaticResult& res = s.failure;
  res.free_dofs = s.map.free_size();
  res.status = SolveStatus::Succeeded;
  if (iterative) {
    s.iterative = std::make_unique<PetscSolver>(iterative_options(model.solver));
    s.iterative->set_near_null_space(rigid_body_modes(model, s.map));
    s.iterative->set_block_size(node_block_size(s.map));
    s.iterative->set_borrow_matrix(true);  // K_ff lives beside it, unchanged, for as long
    s.iterative->set_owned_columns_only(!owned.all());
    if (s.iterative->compute(K) != FactorStatus::Succeeded) {
      // A zero or negative diagonal entry, or a zero pivot in the multigrid's set-up.
      SparseMatrix whole;
      res.modes = zero_energy_modes(model, s.map, s.whole_K_ff(whole), 12, options.zero_energy_tolerance);
      res.status = res.modes.empty() ? SolveStatus::Failed : SolveStatus::Mechanism;
      res.message = res.modes.empty() ? "the multigrid preconditioner of the iterative solver could not be set up "
                                        "(the stiffness is not positive definite)"
                                      : describe_mechanism(res.modes);
      return;
    }
    factorizations_ = 1;
    return;
  }
  const FactorStatus fs = s.factor.factorize(K, fo);
  if (fs == FactorStatus::TooLarge) {
    res.status = SolveStatus::Failed;
    res.message = fmt::format("the factorisation of {} free DOFs is too large for CHOLMOD's symbolic analysis "
                              "(factor over 2^31 entries or out of memory)", s.map.free_size());
    return;
  }
  if (fs != FactorStatus::Succeeded) {
    res.modes = zero_energy_modes(model, s.map, K, 12, options.zero_energy_tolerance);
    if (!res.modes.empty()) {
      res.status = SolveStatus::Mechanism;
      res.message = describe_mechanism(res.modes);
      return;
    }
    if (fs == FactorStatus::Singular || !s.factor.usable()) {
      res.status = SolveStatus::Failed;
      res.message = "the stiffness matrix could not be factorised";
      return;
    }
    // Ill-conditioned but without a zero-energy mode: the factorisation stands.
  }
  factorizations_ = 1;
}

bool LinearSystem::iterative() const { return impl_->iterative != nullptr; }

double LinearSystem::rcond() const {
  return !impl_->iterative && impl_->factor.cholesky() ? impl_->factor.rcond() : std::numeric_limits<double>::quiet_NaN();
}

void LinearSystem::rebind(const Model& model) {
  model_ = &model;
  impl_->map.rebind(model);
  impl_->structure.rebind(model);
}

LinearStaticResult LinearSystem::solve(const LoadSet& loads) const {
  LinearStaticResult res;
  LinearSolveScratch scratch;
  solve(loads, res, scratch);
  return res;
}

void set_constraint_results(const Model& model, const DofMap& map, const DofMap::ConstraintForces& cf, LinearStaticResult& res) {
  res.reactions.assign(model.nodes.size(), Vec6::Zero());
  res.supported.assign(model.nodes.size(), 0);
  for (int p = 0; p < map.prescribed_size(); ++p) {
    const auto& d = map.prescribed()[p].dof;
    if (d.owner != DofRef::Owner::Node || map.prescribed()[p].constraint >= 0) continue;
    res.reactions[d.index][d.comp] = cf.prescribed[p];
    res.supported[d.index] = 1;
  }
  // Skewed supports: the multipliers of their rows are the reaction in their axes A, A^T of it global.
  res.skewed.clear();
  res.reactions_local.clear();
  for (std::size_t i = 0; i < model.supports.size(); ++i) {
    const Support& sup = model.supports[i];
    if (!sup.skewed) continue;
    const Vec6& local = cf.support_local[i];
    res.reactions[sup.node].head<3>() += sup.axes.transpose() * local.head<3>();
    res.reactions[sup.node].tail<3>() += sup.axes.transpose() * local.tail<3>();
    res.supported[sup.node] = 1;
    res.skewed.resize(model.nodes.size(), 0);
    res.skewed[sup.node] = 1;
  }
  if (!res.skewed.empty()) {
    // The node's whole reaction in the axes of its skewed support (the reader allows one per node).
    res.reactions_local.assign(model.nodes.size(), Vec6::Zero());
    for (const Support& sup : model.supports) {
      if (!sup.skewed) continue;
      const Vec6& g = res.reactions[sup.node];
      res.reactions_local[sup.node] << sup.axes * g.head<3>(), sup.axes * g.tail<3>();
    }
  }
  res.tie_forces = cf.tie;
  res.constraint_forces = cf.constraint;
}

void LinearSystem::solve(const LoadSet& loads, LinearStaticResult& res, LinearSolveScratch& scratch) const {
  const Impl& s = *impl_;
  if (s.failure.status != SolveStatus::Succeeded) {
    res = s.failure;
    return;
  }
  const Model& model = *model_;
  ++solves_;
  res.free_dofs = s.map.free_size();
  element_loads(model, loads, res.element_loads);
  Eigen::VectorXd& f_raw = scratch.f_raw;
  external_force(model, s.map, loads, res.element_loads, f_raw);
  Eigen::VectorXd& f = scratch.f;
  s.map.reduce(f_raw, f);
  if (s.map.prescribed_size() > 0) f -= s.assembler.K_fp() * s.up;
  scratch.u_free.resize(f.size());
  if (s.iterative) {
    if (!solve_iteratively(f, res, scratch)) return;
  } else {
    s.factor.solve(f, scratch.u_free);
    res.solver = {.iterative = false, .iterations = 1,
                  .residual = relative_residual(s.assembler.K_ff(), f, scratch.u_free, scratch.free_residual)};
  }
  s.map.expand(scratch.u_free, s.up, res.u);

  Eigen::VectorXd& r = scratch.residual;  // f_int - f_ext
  s.structure.internal_force(s.map, res.u, r);
  r -= f_raw;
  s.map.constraint_forces(r, scratch.constraint_forces, scratch.constraint_scratch);
  const DofMap::ConstraintForces& cf = scratch.constraint_forces;
  set_constraint_results(model, s.map, cf, res);
  res.joint_forces = cf.joint;
  res.statically_indeterminate = s.map.redundant_constraints();
  res.end_forces.resize(model.elements.size());
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    res.end_forces[e] = s.structure.end_forces(s.map, static_cast<int>(e), res.u);
    if (const auto& beam = s.structure.beam(static_cast<int>(e)); beam && !res.element_loads[e].empty())
      res.end_forces[e] += beam->fixed_end_forces_at(beam->reference_poses(), res.element_loads[e]);
  }
  res.modes.clear();
  res.status = SolveStatus::Succeeded;
  res.message.clear();
  fmt::format_to(std::back_inserter(res.message), "linear static: {} free DOFs, max |u| = {:.6g}", s.map.free_size(),
                 res.u.size() ? res.u.cwiseAbs().maxCoeff() : 0.0);
}

bool LinearSystem::solve_iteratively(const Eigen::VectorXd& f, LinearStaticResult& res, LinearSolveScratch& scratch) const {
  const Impl& s = *impl_;
  const PetscSolver& cg = *s.iterative;
  const SparseMatrix& K = s.assembler.K_ff();
  res.solver = solve_to_rtol(cg, K, f, scratch.u_free, scratch.free_residual);
  const int iterations = res.solver.iterations;
  const double residual = res.solver.residual;
  const IterativeSolveReport& last = cg.last_solve();
  if (last.converged() && residual <= cg.options().rtol) return true;
  // CG broke down (a direction of zero or negative energy) or the preconditioner failed: a
  // mechanism when K has zero-energy modes. Iterations that ran out, or a residual short of rtol,
  // are a solve short of rtol (the diagnosis, an eigensolve of K, would cost more than the solve).
  if (last.outcome == IterativeSolveReport::Outcome::Breakdown ||
      last.outcome == IterativeSolveReport::Outcome::PreconditionerFailed) {
    SparseMatrix whole;
    res.modes = zero_energy_modes(*model_, s.map, s.whole_K_ff(whole), 12, zero_energy_tolerance_);
  } else
    res.modes.clear();
  res.status = res.modes.empty() ? SolveStatus::NotConverged : SolveStatus::Mechanism;
  res.message = res.modes.empty()
                    ? fmt::format("the iterative solver ({}) did not converge: relative residual {:.3g} after {} "
                                  "iterations ({})",
                                  describe_iterative(cg.options()), residual, iterations, last.reason)
                    : describe_mechanism(res.modes);
  res.u.resize(0);
  return false;
}

LinearStaticResult solve_linear_static(const Model& model, const LinearStaticOptions& options) {
  const LinearSystem system(model, options);
  return system.solve(model.default_loads());
}

}  // namespace beamfea
