#include "solvers/condensed_stiffness.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <fmt/compile.h>
#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <optional>
#include <type_traits>

#include "core/assembly.hpp"
#include "core/errors.hpp"
#include "solvers/condensation.hpp"
#include "solvers/initial_stress.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/near_null_space.hpp"
#include "solvers/petsc_solver.hpp"
#include "solvers/sparse_factor.hpp"
#include "solvers/structure.hpp"
#include "solvers/structure_cache.hpp"

namespace beamfea {

void CondensedStiffnessOptions::validate() const {
  if (!(rank_tolerance > 0.0 && rank_tolerance < 1.0)) throw Error("CondensedStiffnessOptions: rank_tolerance must be in (0, 1)");
  if (!(motion_tolerance > 0.0 && motion_tolerance < 1.0))
    throw Error("CondensedStiffnessOptions: motion_tolerance must be in (0, 1)");
}

void analyse_rank(const Mat6& K, double L, double tolerance, CondensedStiffness& out) {
  Vec6 s;
  s << 1, 1, 1, 1 / L, 1 / L, 1 / L;
  const Mat6 Ks = s.asDiagonal() * (0.5 * (K + K.transpose())) * s.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Mat6> es(Ks);
  out.eigenvalues = es.eigenvalues();
  const double big = es.eigenvalues().cwiseAbs().maxCoeff();
  out.rank = 0;
  out.null_space.clear();
  for (int i = 0; i < 6; ++i) {
    if (std::abs(es.eigenvalues()[i]) > tolerance * big && big > 0.0) {
      ++out.rank;
    } else {
      Vec6 v = s.asDiagonal() * es.eigenvectors().col(i);
      v.normalize();
      // Make the largest component positive, for reproducible output.
      Eigen::Index k;
      v.cwiseAbs().maxCoeff(&k);
      if (v[k] < 0) v = -v;
      out.null_space.push_back(v);
    }
  }
}

namespace {

// Eigenvalues of the compliance below this fraction of the largest are the zeros of its rigid and
// free directions (exactly zero up to the rounding of U_r: 1e-16 relative).
constexpr double kPseudoInverseTolerance = 1e-12;

// A unit vector (in the unscaled components) with its largest component positive: reproducible output.
Vec6 reproducible_direction(Vec6 v) {
  v.normalize();
  Eigen::Index k;
  v.cwiseAbs().maxCoeff(&k);
  return v[k] < 0 ? Vec6(-v) : v;
}

// The pseudo-inverse of a symmetric 6x6 matrix (eigenvalues below kPseudoInverseTolerance of the
// largest taken as zero).
Mat6 pseudo_inverse(const Mat6& C) {
  Eigen::SelfAdjointEigenSolver<Mat6> ec(C);
  const double cmax = ec.eigenvalues().cwiseAbs().maxCoeff();
  Vec6 ci = Vec6::Zero();
  for (int i = 0; i < 6; ++i)
    if (std::abs(ec.eigenvalues()[i]) > kPseudoInverseTolerance * cmax) ci[i] = 1.0 / ec.eigenvalues()[i];
  return ec.eigenvectors() * ci.asDiagonal() * ec.eigenvectors().transpose();
}

// The arrays of one node condensation. A thread keeps one set for models of up to kDenseMaxDofs
// free DOFs (a sweep's cases then allocate none of them: the SVD keeps its storage while the sizes
// stay); larger models use a set of their own, freed on return.
struct NodeCondensationScratch {
  Eigen::MatrixXd Tn, Ts, A, Kz;
  Eigen::VectorXd col_scale;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd;
  CondensationWorkspace dense;
  std::vector<Vec6> free_dirs;
  const PetscSolver* cg = nullptr;  // the iterative solver set up for K, when the model chose it
};

// The thread's set for n free DOFs up to kDenseMaxDofs, else `local`.
NodeCondensationScratch& scratch_for(Eigen::Index n, NodeCondensationScratch& local) {
  thread_local NodeCondensationScratch s;
  return n <= kDenseMaxDofs ? s : local;
}

template <class Matrix>
void node_compliance_of(const Matrix& K, const Eigen::MatrixXd& Tn, const Eigen::VectorXd& col_scale, double L,
                        const CondensedStiffnessOptions& options, NodeCondensationScratch& w, CondensedStiffness& out);

template <class Matrix>
CondensedStiffness node_compliance_of(const Matrix& K, const Eigen::MatrixXd& Tn, const Eigen::VectorXd& col_scale,
                                      double L, const CondensedStiffnessOptions& options) {
  NodeCondensationScratch local;
  CondensedStiffness out;
  node_compliance_of(K, Tn, col_scale, L, options, scratch_for(Tn.cols(), local), out);
  return out;
}

// Whether the scaled rows Ts (6 x n) of a node reach every direction, decided without an SVD
// where the rows are orthogonal because no two share a column (a node whose six DOFs are free DOFs
// of their own, or scaled ones: no constraint mixes them): the singular values are then the rows'
// norms, and the node moves in every direction when the least of them passes the motion test of
// node_compliance_of. False (the SVD decides) when two rows share a column or a row is too short.
bool moves_in_every_direction(const Eigen::MatrixXd& Ts, double motion_tolerance) {
  if (Ts.rows() != 6) return false;
  Vec6 norm2 = Vec6::Zero();
  for (Eigen::Index j = 0; j < Ts.cols(); ++j) {
    int rows = 0;
    for (int k = 0; k < 6; ++k) {
      const double t = Ts(k, j);
      if (t == 0.0) continue;
      if (++rows > 1) return false;
      norm2[k] += t * t;
    }
  }
  const double smax = std::sqrt(norm2.maxCoeff()), smin = std::sqrt(norm2.minCoeff());
  return smin > motion_tolerance * std::max(smax, 1.0);
}

// `out` as a default CondensedStiffness, its vectors and strings keeping their storage.
void reset(CondensedStiffness& out) {
  out.ok = false;
  out.message.clear();
  out.K.setZero();
  out.compliance.setZero();
  out.rank = 0;
  out.null_space.clear();
  out.rigid_directions.clear();
  out.eigenvalues.setZero();
  out.modes.clear();
  out.statically_indeterminate.clear();
  out.solver = {.iterative = false, .iterations = 1, .residual = 0.0};
  out.not_converged = false;
}

}  // namespace

CondensedStiffness node_compliance(const SparseMatrix& K, const Eigen::MatrixXd& Tn, const Eigen::VectorXd& col_scale,
                                   double L, const CondensedStiffnessOptions& options) {
  return node_compliance_of(K, Tn, col_scale, L, options);
}
CondensedStiffness node_compliance(const Eigen::MatrixXd& K, const Eigen::MatrixXd& Tn, const Eigen::VectorXd& col_scale,
                                   double L, const CondensedStiffnessOptions& options) {
  return node_compliance_of(K, Tn, col_scale, L, options);
}

namespace {

template <class Matrix>
void node_compliance_of(const Matrix& K, const Eigen::MatrixXd& Tn, const Eigen::VectorXd& col_scale, double L,
                        const CondensedStiffnessOptions& options, NodeCondensationScratch& w, CondensedStiffness& out) {
  options.validate();
  reset(out);
  Vec6 S;
  S << 1, 1, 1, L, L, L;
  // Directions the node can move: the range of the scaled rows (a zero column pads an empty Tn).
  Eigen::MatrixXd& Ts = w.Ts;
  if (Tn.cols() > 0) Ts = S.asDiagonal() * Tn * col_scale.asDiagonal();
  else Ts.setZero(6, 1);
  // At most six rows: fixed-capacity matrices (no heap, products by coefficients rather than GEMM).
  using Rows6 = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;
  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
  Rows6 Ur;
  int r = 0;
  // Relative to the largest, and to 1: the scaled rows of a node that moves at all are O(1) (a
  // translation, or a rotation times a lever arm over L), those of a held node rounding noise.
  const bool whole = moves_in_every_direction(Ts, options.motion_tolerance);
  if (whole) {
    // Every direction: the range is R^6 and any orthonormal basis of it serves; the identity
    // leaves K_c = S K_z S and the compliance S^-1 K_z^-1 S^-1 without rotations.
    r = 6;
  } else {
    Eigen::JacobiSVD<Eigen::MatrixXd>& svd = w.svd;
    svd.compute(Ts, Eigen::ComputeFullU);
    const Eigen::VectorXd& sv = svd.singularValues();
    const double smax = sv.size() ? sv[0] : 0.0;
    while (r < sv.size() && sv[r] > options.motion_tolerance * std::max(smax, 1.0)) ++r;
    const Eigen::MatrixXd& U = svd.matrixU();  // 6 x 6
    for (int k = r; k < 6; ++k) out.rigid_directions.push_back(reproducible_direction(S.cwiseInverse().asDiagonal() * U.col(k)));
    if (r == 0) {  // held in every direction: nothing to condense
      analyse_rank(out.K, L, options.rank_tolerance, out);
      out.null_space.clear();
      out.ok = true;
      return;
    }
    Ur = U.leftCols(r);
  }
  // K_z of the rows A = U_r^T S T_n (S T_n when the node moves in every direction: a node whose
  // DOFs are free DOFs of their own then takes the static condensation onto them).
  Eigen::MatrixXd& Kz = w.Kz;
  Eigen::MatrixXd& A = w.A;
  A.resize(r, Tn.cols());
  if (whole) A.noalias() = S.asDiagonal() * Tn;
  else A.noalias() = (Ur.transpose() * S.asDiagonal()).lazyProduct(Tn);
  Condensation::Outcome outcome;
  if constexpr (std::is_same_v<Matrix, SparseMatrix>) {
    outcome = w.cg ? condense_iteratively(*w.cg, K, A, Kz, out.solver)
                   : condense(K, A, Kz, {}, &w.dense, &out.solver.residual);
  } else {
    outcome = condense(K, A, Kz, {}, &w.dense, &out.solver.residual);
  }
  if (outcome == Condensation::Outcome::Mechanism && w.cg) {
    // K is not positive definite: the direct saddle point, which holding the node may make regular.
    out.solver = {.iterative = false, .iterations = 1, .residual = 0.0};
    outcome = condense(K, A, Kz, {}, &w.dense, &out.solver.residual);
  }
  out.not_converged = outcome == Condensation::Outcome::NotConverged;
  if (outcome != Condensation::Outcome::Succeeded) return;
  // Free directions of the node: the null space of K_z.
  const Small Kzs = Kz;
  Eigen::SelfAdjointEigenSolver<Small> es(Kzs);
  const double big = es.eigenvalues().cwiseAbs().maxCoeff();
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1> inv = Eigen::VectorXd::Zero(r);
  for (int i = 0; i < r; ++i) {
    const double ev = es.eigenvalues()[i];
    if (big > 0.0 && std::abs(ev) > options.rank_tolerance * big) {
      inv[i] = 1.0 / ev;
    } else {
      const Vec6 v = whole ? Vec6(es.eigenvectors().col(i)) : Vec6(Ur * es.eigenvectors().col(i));
      out.null_space.push_back(reproducible_direction(S.cwiseInverse().asDiagonal() * v));
    }
  }
  const Small Cz = es.eigenvectors() * inv.asDiagonal() * es.eigenvectors().transpose();
  const Mat6 Sinv = S.cwiseInverse().asDiagonal();
  if (whole) out.compliance = Sinv * Cz * Sinv;
  else out.compliance = Sinv * Ur * Cz * Ur.transpose() * Sinv;
  out.compliance = 0.5 * (out.compliance + out.compliance.transpose()).eval();
  if (whole) {
    out.K = S.asDiagonal() * Kzs * S.asDiagonal();  // K_c itself
  } else if (r == 6) {
    out.K = S.asDiagonal() * Ur * Kzs * Ur.transpose() * S.asDiagonal();  // K_c itself
  } else {
    // Restricted node: the pseudo-inverse of the compliance in the components [ux .. rz] (as the
    // loaded stiffness of a chain with fewer than six joints has always been reported).
    out.K = pseudo_inverse(out.compliance);
  }
  out.K = 0.5 * (out.K + out.K.transpose()).eval();
  if (whole) {
    // The length-scaled K_c that analyse_rank decomposes, S^-1 K_c S^-1, is K_z itself (to the
    // rounding of multiplying by L and dividing by it): its eigenvalues are those above, and its
    // rank the six less the free directions they gave.
    out.eigenvalues = es.eigenvalues();
    out.rank = 6 - static_cast<int>(out.null_space.size());
  } else {
    // analyse_rank replaces the null space: the free directions found above are put back (swapped
    // through the scratch, so that neither list allocates once it has its size).
    w.free_dirs.swap(out.null_space);
    analyse_rank(out.K, L, options.rank_tolerance, out);  // rank and scaled eigenvalues of the matrix
    out.null_space.swap(w.free_dirs);
  }
  out.ok = true;
}

template <class Matrix>
void condense_to_node_of(const Model& model, const DofMap& map, const Matrix& K, int node,
                         const CondensedStiffnessOptions& options, CondensedStiffness& out) {
  options.validate();
  const int n = map.free_size();
  NodeCondensationScratch local;
  NodeCondensationScratch& w = scratch_for(n, local);
  Eigen::MatrixXd& Tn = w.Tn;
  Tn.setZero(6, n);
  for (int k = 0; k < 6; ++k)
    for (SparseRowMatrix::InnerIterator it(map.T_free(), map.raw_node(node, k)); it; ++it) Tn(k, it.col()) += it.value();
  const double L = model.length_scale();
  Eigen::VectorXd& col_scale = w.col_scale;
  col_scale.resize(n);
  for (int j = 0; j < n; ++j) {
    const DofRef& d = map.free_dofs()[j];
    const bool rotation = d.owner == DofRef::Owner::Node ? d.comp >= 3 : !model.joints[d.index].is_translation(d.comp);
    col_scale[j] = rotation ? 1.0 / L : 1.0;
  }
  // The model's iterative solver: the multigrid set up once for the node's six solves.
  std::optional<PetscSolver> cg;
  if constexpr (std::is_same_v<Matrix, SparseMatrix>) {
    if (solves_iteratively(model.solver, n)) {
      cg.emplace(iterative_options(model.solver));
      cg->set_near_null_space(rigid_body_modes(model, map));
      cg->set_block_size(node_block_size(map));
      if (cg->compute(K) == FactorStatus::Succeeded) w.cg = &*cg;
      else cg.reset();  // not positive definite: the direct saddle point decides
    }
  }
  node_compliance_of(K, Tn, col_scale, L, options, w, out);
  w.cg = nullptr;
  if (out.not_converged) {
    fmt::memory_buffer text;
    fmt::format_to(std::back_inserter(text), "stiffness of node '{}': the iterative solver ({}) did not converge: "
                   "relative residual {:.3g} after {} iterations ({})",
                   model.nodes[node].id, describe_iterative(cg->options()), out.solver.residual, out.solver.iterations,
                   cg->last_solve().reason);
    out.message.assign(text.data(), text.size());
    return;
  }
  if (!out.ok) {
    if constexpr (std::is_same_v<Matrix, SparseMatrix>) out.modes = zero_energy_modes(model, map, K, 12);
    else out.modes = zero_energy_modes(model, map, SparseMatrix(K.sparseView()), 12);
    out.message = "holding node '" + model.nodes[node].id + "' still leaves a mechanism; " + describe_mechanism(out.modes);
    return;
  }
  // Formatted on the stack by a format compiled with the program (no parse at run time, no
  // push_back per character), then copied into the message's own storage, which a caller writing
  // case after case over one CondensedStiffness keeps.
  fmt::memory_buffer text;
  fmt::format_to(std::back_inserter(text), FMT_COMPILE("stiffness of node '{}': rank {}, {} rigid directions, {} free directions"),
                 model.nodes[node].id, out.rank, out.rigid_directions.size(), out.null_space.size());
  out.message.assign(text.data(), text.size());
}

template <class Matrix>
CondensedStiffness condense_to_node_of(const Model& model, const DofMap& map, const Matrix& K, int node,
                                       const CondensedStiffnessOptions& options) {
  CondensedStiffness out;
  condense_to_node_of(model, map, K, node, options, out);
  return out;
}

}  // namespace

CondensedStiffness condense_to_node(const Model& model, const DofMap& map, const SparseMatrix& K, int node,
                                    const CondensedStiffnessOptions& options) {
  return condense_to_node_of(model, map, K, node, options);
}
CondensedStiffness condense_to_node(const Model& model, const DofMap& map, const Eigen::MatrixXd& K, int node,
                                    const CondensedStiffnessOptions& options) {
  return condense_to_node_of(model, map, K, node, options);
}

CondensedStiffness linear_node_stiffness(const Model& model, int node, const CondensedStiffnessOptions& options) {
  CondensedStiffness out;
  linear_node_stiffness(model, node, out, options);
  return out;
}

void linear_node_stiffness(const Model& model, int node, CondensedStiffness& out, const CondensedStiffnessOptions& options) {
  // Small models: the thread's map and element matrices when the model's content that they read is
  // that of the last call (a sweep over joint springs), solvers/structure_cache.hpp.
  std::optional<LinearStructureCache::Parts> own;
  const LinearStructureCache::Parts& parts = LinearStructureCache::keeps(model)
                                                 ? thread_structure_cache().get(model)
                                                 : own.emplace(model);
  const DofMap& map = parts.map;
  const LinearStructure& structure = parts.structure;
  auto condensed = [&](auto&& assembler) {
    assembler.begin();
    structure.assemble(map, assembler);
    assembler.end();
    condense_to_node_of(model, map, assembler.K_ff(), node, options, out);
    out.statically_indeterminate = map.redundant_constraints();
  };
  // Small models: assembled into a dense matrix and condensed by the dense Schur complement. The
  // thread keeps the assembler (its n x n array, at most kDenseMaxDofs square, and its scratch), so
  // that a sweep's cases allocate none of it; reset to this call's map before each use.
  if (map.free_size() <= kDenseMaxDofs && !solves_iteratively(model.solver, map.free_size())) {
    thread_local DenseAssembler dense(map);
    dense.reset(map);
    condensed(dense);
    return;
  }
  SystemAssembler sparse(map);
  condensed(sparse);
}

CondensedStiffness loaded_node_stiffness(const Model& model, int node, const CondensedStiffnessOptions& options) {
  return loaded_node_stiffness(model, model.default_loads(), node, options);
}

CondensedStiffness loaded_node_stiffness(const Model& model, const LoadSet& loads, int node,
                                         const CondensedStiffnessOptions& options) {
  return loaded_node_stiffness(model, loads, node, PreloadOptions{}, options);
}

CondensedStiffness loaded_node_stiffness(const Model& model, const LoadSet& loads, int node, const PreloadOptions& preload,
                                         const CondensedStiffnessOptions& options) {
  const DofMap map(model);
  const LinearStructure structure(model);
  SystemAssembler assembler(map);
  assembler.begin();
  structure.assemble(map, assembler);
  assembler.end();
  std::string why;
  const std::optional<SparseMatrix> Kt = loaded_tangent(model, map, structure, assembler.K_ff(), loads, preload, why);
  if (!Kt) {
    CondensedStiffness out;
    out.message = "loaded stiffness: " + why;
    if (preload.about == Equilibrium::LinearStatic) out.modes = LinearSystem(model).solve(loads).modes;
    return out;
  }
  return condense_to_node(model, map, *Kt, node, options);
}

}  // namespace beamfea
