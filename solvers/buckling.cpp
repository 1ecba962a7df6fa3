#include "solvers/buckling.hpp"

#include <Eigen/Eigenvalues>
#include <Spectra/MatOp/SparseCholesky.h>
#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsSolver.h>
#include <Spectra/MatOp/SymShiftInvert.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <fmt/format.h>

#include <algorithm>

#include "core/assembly.hpp"
#include "core/errors.hpp"
#include "solvers/initial_stress.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/mass_matrix.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

void BucklingOptions::validate() const {
  if (modes < 1) throw Error("BucklingOptions: modes must be at least 1");
}

const char* to_string(BucklingStatus s) {
  switch (s) {
    case BucklingStatus::Succeeded: return "ok";
    case BucklingStatus::NoCompression: return "no buckling";
    case BucklingStatus::Mechanism: return "mechanism";
    case BucklingStatus::NotConverged: return "not converged";
    case BucklingStatus::Failed: return "failed";
  }
  return "?";
}

Eigen::VectorXd normalise_mode(const Model& model, const Eigen::VectorXd& u) {
  double best = 0.0;
  Eigen::Index arg = -1;
  for (int pass = 0; pass < 2 && arg < 0; ++pass)
    for (std::size_t n = 0; n < model.nodes.size(); ++n)
      for (int k = 0; k < 3; ++k) {
        const Eigen::Index i = 6 * static_cast<Eigen::Index>(n) + 3 * pass + k;
        if (std::abs(u[i]) > best * (1 + 1e-9) + 1e-300) {
          best = std::abs(u[i]);
          arg = i;
        }
      }
  if (arg < 0) return u;
  return u / u[arg];
}

namespace {

using LoadFactorPairs = std::vector<std::pair<double, Eigen::VectorXd>>;

// Dense: -Kg phi = mu K phi, mu = 1 / lambda; the positive load factors, lowest first. False when
// the eigen-solver fails.
bool dense_buckling_pairs(const SparseMatrix& K, const SparseMatrix& KG, LoadFactorPairs& pairs) {
  const Eigen::MatrixXd KGd(KG), Kd(K);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(KGd, Kd);
  if (es.info() != Eigen::Success) return false;
  const double mu_max = es.eigenvalues().cwiseAbs().maxCoeff();
  for (auto i = static_cast<int>(K.rows()) - 1; i >= 0; --i) {
    const double mu = es.eigenvalues()[i];
    if (mu <= 1e-12 * mu_max || mu <= 0.0) break;
    pairs.emplace_back(1.0 / mu, es.eigenvectors().col(i));
  }
  return true;
}

// Sparse (Spectra): the positive load factors nearest half the first one; none when the loads put
// nothing in compression.
LoadFactorPairs sparse_buckling_pairs(const SparseMatrix& K, const SparseMatrix& KG, int want) {
  const auto n = static_cast<int>(K.rows());
  LoadFactorPairs pairs;
  // Pass 1, an estimate of the first load factor without a shift: the largest eigenvalue
  // mu = 1/lambda of (-Kg) phi = mu K phi (Spectra, Cholesky mode on K).
  double sigma = 0.0;
  {
    Spectra::SparseSymMatProd<double> Aop(KG);
    Spectra::SparseCholesky<double> Bop(K);
    Spectra::SymGEigsSolver<Spectra::SparseSymMatProd<double>, Spectra::SparseCholesky<double>, Spectra::GEigsMode::Cholesky>
        est(Aop, Bop, 1, std::min(n, 20));
    est.init();
    est.compute(Spectra::SortRule::LargestAlge, 2000, 1e-6);
    if (est.info() == Spectra::CompInfo::Successful && est.eigenvalues()[0] > 0.0) sigma = 0.5 / est.eigenvalues()[0];
  }
  if (!(sigma > 0.0)) return pairs;
  // Pass 2, shift-invert in buckling mode about half the first load factor: the factors nearest
  // sigma, negative ones (tension buckling) dropped.
  using OpType = Spectra::SymShiftInvert<double, Eigen::Sparse, Eigen::Sparse>;
  using BOpType = Spectra::SparseSymMatProd<double>;
  const int nev = std::min(n - 1, 2 * want + 2);
  const int ncv = std::min(n, std::max(2 * nev + 1, 24));
  for (int attempt = 0; attempt < 4 && pairs.size() < static_cast<std::size_t>(want); ++attempt) {
    pairs.clear();
    OpType op(K, KG);
    BOpType Bop(K);
    Spectra::SymGEigsShiftSolver<OpType, BOpType, Spectra::GEigsMode::Buckling> eigs(op, Bop, nev, ncv, sigma);
    eigs.init();
    eigs.compute(Spectra::SortRule::LargestMagn, 2000, 1e-10);
    if (eigs.info() == Spectra::CompInfo::Successful) {
      const Eigen::VectorXd v = eigs.eigenvalues();
      const Eigen::MatrixXd V = eigs.eigenvectors();
      for (int i = 0; i < v.size(); ++i)
        if (v[i] > 0.0) pairs.emplace_back(v[i], V.col(i));
    }
    sigma *= 0.5;
  }
  return pairs;
}

}  // namespace

BucklingResult solve_buckling(const Model& model, const BucklingOptions& options) {
  return solve_buckling(model, model.default_loads(), options);
}

BucklingResult solve_buckling(const Model& model, const LoadSet& loads, const BucklingOptions& options) {
  options.validate();
  BucklingResult res;
  const LinearStaticResult lin = LinearSystem(model).solve(loads);
  if (lin.status != SolveStatus::Succeeded) {
    res.status = lin.status == SolveStatus::Mechanism ? BucklingStatus::Mechanism : BucklingStatus::Failed;
    res.message = "buckling: the linear static solution failed: " + lin.message;
    return res;
  }
  res.linear_u = lin.u;
  const DofMap map(model);
  const LinearStructure structure(model);
  SystemAssembler ka(map);
  structure.assemble_stiffness(map, ka);
  const SparseMatrix& K = ka.K_ff();
  SparseMatrix Kg = geometric_stiffness(model, map, structure, lin, loads, options.geometric_stiffness);
  Kg = SparseMatrix(0.5 * (SparseMatrix(Kg.transpose()) + Kg));
  res.free_dofs = map.free_size();
  const int n = map.free_size();
  if (n == 0) {
    // Every DOF is held: nothing can move, so nothing can buckle (an answer, not a failure).
    res.status = BucklingStatus::NoCompression;
    res.message = "buckling: no free DOF (every DOF is supported, prescribed or held): nothing can buckle";
    return res;
  }
  const int want = std::min(options.modes, n);

  // Solve K phi = lambda (-Kg) phi.
  const SparseMatrix KG = -Kg;
  LoadFactorPairs pairs;
  if (eigen_solver_iterative(model.solver, n)) {
    // SLEPc: Krylov-Schur on (-Kg) phi = mu K phi, the largest mu = 1/lambda (solvers/slepc_eigen.hpp).
    const Eigen::MatrixXd rigid = free_rigid_body_motions(model, map);
    const SlepcEigenPairs sp = slepc_buckling_pairs(K, KG, slepc_options(model.solver, want), &rigid);
    res.solver = EigenSolverReport{true, sp.iterations, sp.linear_iterations, 0.0};
    if (!sp.converged) {
      res.status = BucklingStatus::NotConverged;
      res.message = sp.message;
      return res;
    }
    for (Eigen::Index i = 0; i < sp.values.size(); ++i) pairs.emplace_back(sp.values[i], sp.vectors.col(i));
  } else if (n <= 300) {
    if (!dense_buckling_pairs(K, KG, pairs)) {
      res.status = BucklingStatus::Failed;
      res.message = "buckling: the dense eigen-solver failed (is K positive definite?)";
      return res;
    }
  } else {
    pairs = sparse_buckling_pairs(K, KG, want);
  }
  std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  if (pairs.size() > static_cast<std::size_t>(want)) pairs.resize(want);
  if (pairs.empty()) {
    res.status = BucklingStatus::NoCompression;
    res.message = "buckling: no positive load factor (the loads put nothing in compression)";
    return res;
  }
  res.load_factors.resize(static_cast<Eigen::Index>(pairs.size()));
  Eigen::MatrixXd X(n, static_cast<Eigen::Index>(pairs.size()));
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    res.load_factors[static_cast<Eigen::Index>(i)] = pairs[i].first;
    X.col(static_cast<Eigen::Index>(i)) = pairs[i].second;
    const Eigen::VectorXd raw = map.T_free() * pairs[i].second;
    res.modes.push_back(normalise_mode(model, raw));
  }
  res.solver.residual = relative_eigen_residual(K, KG, res.load_factors, X);
  res.status = BucklingStatus::Succeeded;
  res.message = fmt::format("buckling: {} free DOFs, lowest load factor {:.6g}", n, res.load_factors[0]);
  return res;
}

}  // namespace beamfea
