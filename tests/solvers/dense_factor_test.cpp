// The small-model dense paths of solvers/sparse_factor agree with the sparse ones (CHOLMOD,
// UMFPACK) on the models of the test suite: the examples' models (Pashkevich chains, lumped and
// beam; space frame; workspace map; load sweep; Lee's frame).
#include <gtest/gtest.h>

#include <Eigen/UmfPackSupport>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <random>

#include "core/assembly.hpp"
#include "core/dense_assembly.hpp"
#include "io/model_reader.hpp"
#include "solvers/condensation.hpp"
#include "solvers/condensed_stiffness.hpp"
#include "solvers/dense_condensation.hpp"
#include "solvers/sparse_factor.hpp"
#include "solvers/structure.hpp"

namespace dense_factor_test {

using namespace beamfea;
namespace fs = std::filesystem;

namespace {

// Agreement asked of the two paths: relative, in the max norm, of the loads balanced
// (|K (u_dense - u_sparse)| / |f|: both factorisations are backward stable, so this is what
// rounding leaves whatever the conditioning) and of the displacements where the matrix is well
// conditioned. An ill-conditioned matrix (the Pashkevich A beam models, rcond 1e-7) amplifies
// rounding in either solution by up to its condition number: there the displacements are asked
// to agree within the forward error bound, kConditionSlack * eps * cond_1(S K S) (Higham,
// Accuracy and Stability of Numerical Algorithms, 2nd ed., Thm 10.4 with the bound of 7.2).
constexpr double kAgreement = 1e-12;
constexpr double kConditionSlack = 10.0;
constexpr int kMaxDofs = 600;  // the dense condition number below costs n^3

double forward_bound(const SparseMatrix& K, const Eigen::VectorXd& s) {
  const Eigen::MatrixXd A = s.asDiagonal() * Eigen::MatrixXd(K) * s.asDiagonal();
  const Eigen::MatrixXd Ainv = A.llt().solve(Eigen::MatrixXd::Identity(A.rows(), A.cols()));
  const double cond = A.cwiseAbs().colwise().sum().maxCoeff() * Ainv.cwiseAbs().colwise().sum().maxCoeff();
  return std::max(kAgreement, kConditionSlack * std::numeric_limits<double>::epsilon() * cond);
}

std::vector<fs::path> suite_models() {
  std::vector<fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(fs::path(BEAMFEA_SOURCE_DIR) / "examples")) {
    const auto name = e.path().filename().string();
    if (e.path().extension() == ".json" && (name == "model.json" || e.path().parent_path().filename() == "models"))
      out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

struct Assembled {
  Model model;
  std::unique_ptr<DofMap> map;
  SparseMatrix K;
};

Assembled assemble(const fs::path& file) {
  Assembled a{read_model(read_json_file(file.string())), nullptr, {}};
  a.map = std::make_unique<DofMap>(a.model);
  const LinearStructure structure(a.model);
  SystemAssembler assembler(*a.map);
  assembler.begin();
  structure.assemble(*a.map, assembler);
  assembler.end();
  a.K = assembler.K_ff();
  return a;
}

// The rows of T_free of the last node's six DOFs (the end effector of the chains): 6 x n.
Eigen::MatrixXd last_node_rows(const Assembled& a) {
  const int node = static_cast<int>(a.model.nodes.size()) - 1;
  Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(6, a.K.rows());
  for (int k = 0; k < 6; ++k)
    for (SparseRowMatrix::InnerIterator it(a.map->T_free(), a.map->raw_node(node, k)); it; ++it)
      rows(k, it.col()) += it.value();
  return rows;
}

double rel_diff(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(b.cwiseAbs().maxCoeff(), 1e-300);
}

}  // namespace

TEST(DenseFactor, AgreesWithCholmodOnTheSuiteModels) {
  const auto files = suite_models();
  ASSERT_GE(files.size(), 20u);
  int compared = 0;
  double worst = 0.0;
  for (const auto& f : files) {
    const Assembled a = assemble(f);
    const int n = static_cast<int>(a.K.rows());
    if (n == 0 || n > kMaxDofs) continue;
    FactorOptions dense, sparse;
    dense.dense_max_dofs = n;
    sparse.dense_max_dofs = 0;
    SparseFactor fd, fs_;
    const FactorStatus sd = fd.factorize(a.K, dense), ss = fs_.factorize(a.K, sparse);
    ASSERT_EQ(sd, ss) << f;
    if (ss != FactorStatus::Succeeded) continue;
    EXPECT_TRUE(fd.dense()) << f;
    EXPECT_FALSE(fs_.dense()) << f;
    // A displacement of every DOF (unit size after the Jacobi scaling) and its load.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    Eigen::MatrixXd X(n, 3);
    for (Eigen::Index i = 0; i < X.size(); ++i) X.data()[i] = U(rng);
    X = fd.scaling().asDiagonal() * X;
    const Eigen::MatrixXd B = a.K * X;
    const Eigen::MatrixXd Ud = fd.solve(B), Us = fs_.solve(B);
    const Eigen::MatrixXd dB = a.K * (Ud - Us);
    EXPECT_LE(dB.cwiseAbs().maxCoeff() / B.cwiseAbs().maxCoeff(), kAgreement) << f << " (" << n << " DOFs)";
    const double bound = forward_bound(a.K, fd.scaling());
    EXPECT_LE(rel_diff(Ud, Us), bound) << f << " (" << n << " DOFs, rcond " << fs_.rcond() << ")";
    EXPECT_LE(rel_diff(fd.solve(Eigen::VectorXd(B.col(0))), Us.col(0)), bound) << f;
    worst = std::max(worst, rel_diff(Ud, Us));
    // Same reciprocal condition estimate up to the factor's ordering: the same decision.
    EXPECT_GE(fd.rcond(), dense.singular_rcond) << f;
    ++compared;
  }
  EXPECT_GE(compared, 20);
  std::printf("dense vs CHOLMOD on %d models: largest relative displacement difference %.2e\n", compared, worst);
}

TEST(DenseFactor, SchurCondensationAgreesWithTheSaddlePointLu) {
  int compared = 0;
  for (const auto& f : suite_models()) {
    const Assembled a = assemble(f);
    const int n = static_cast<int>(a.K.rows());
    if (n == 0 || n > kMaxDofs) continue;
    const Eigen::MatrixXd rows = last_node_rows(a);  // if the node is free
    if ((rows.rowwise().norm().array() == 0.0).any()) continue;
    FactorOptions o;
    o.dense_max_dofs = n;
    Eigen::MatrixXd Kz;
    if (!dense_schur_condensation(Eigen::MatrixXd(a.K), rows, Kz, o)) continue;  // a mechanism held by the node: LU's case
    // Reference: UMFPACK on [K A^T; A 0] [X; M] = [0; I], Kz = -M.
    std::vector<Eigen::Triplet<double>> t;
    for (int j = 0; j < a.K.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(a.K, j); it; ++it) t.emplace_back(static_cast<int>(it.row()), j, it.value());
    for (int k = 0; k < 6; ++k)
      for (int j = 0; j < n; ++j)
        if (rows(k, j) != 0.0) {
          t.emplace_back(n + k, j, rows(k, j));
          t.emplace_back(j, n + k, rows(k, j));
        }
    SparseMatrix S(n + 6, n + 6);
    S.setFromTriplets(t.begin(), t.end());
    S.makeCompressed();
    Eigen::UmfPackLU<SparseMatrix> lu(S);
    ASSERT_EQ(lu.info(), Eigen::Success) << f;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n + 6, 6);
    rhs.bottomRows(6).setIdentity();
    const Eigen::MatrixXd M = Eigen::MatrixXd(lu.solve(rhs)).bottomRows(6);
    const Eigen::MatrixXd ref = -0.5 * (M + M.transpose());
    SparseFactor fk;
    fk.factorize(a.K);
    EXPECT_LE(rel_diff(Kz, ref), forward_bound(a.K, fk.scaling())) << f << " (" << n << " DOFs)";
    ++compared;
  }
  EXPECT_GE(compared, 12);
}

// Static condensation onto a node's own free DOFs (dense_static_condensation, the stiffness analysis'
// path for a node no constraint mixes): K_z = D^-1 (K_22 - K_21 K_11^-1 K_12) D^-1 by the
// factor of K_11 alone equals the compliance route (A K^-1 A^T)^-1 with A = D E, within the
// forward error bound of the conditioning (two algorithms: their roundings differ).
TEST(DenseFactor, StaticCondensationOntoANodesOwnDofsAgreesWithTheSchurComplementOfItsRows) {
  int compared = 0;
  for (const auto& f : suite_models()) {
    const Assembled a = assemble(f);
    const int n = static_cast<int>(a.K.rows());
    if (n == 0 || n > kMaxDofs) continue;
    // A scale per row, as the node condensation's S gives rotations (L): D is not the identity.
    Eigen::MatrixXd rows = last_node_rows(a);
    rows.bottomRows(3) *= 0.25;
    std::vector<int> cols;
    std::vector<double> coef;
    for (int k = 0; k < 6; ++k) {
      Eigen::Index c = 0;
      if ((rows.row(k).array() != 0.0).count() != 1) break;  // a held or constrained DOF: not this path
      rows.row(k).cwiseAbs().maxCoeff(&c);
      cols.push_back(static_cast<int>(c));
      coef.push_back(rows(k, c));
    }
    if (cols.size() != 6) continue;
    FactorOptions o;
    o.dense_max_dofs = n;
    Eigen::MatrixXd Kz, ref;
    const bool picked = dense_static_condensation(Eigen::MatrixXd(a.K), cols, coef, Kz, o);
    if (!dense_schur_condensation(Eigen::MatrixXd(a.K), rows, ref, o)) {
      EXPECT_FALSE(picked) << f << ": a mechanism or an ill-posed condensation stays with the saddle point";
      continue;
    }
    ASSERT_TRUE(picked) << f;
    SparseFactor fk;
    fk.factorize(a.K);
    EXPECT_LE(rel_diff(Kz, ref), forward_bound(a.K, fk.scaling())) << f << " (" << n << " DOFs)";
    Eigen::MatrixXd Kz_sparse;  // the condensation of the sparse K on the dense back end: the same arithmetic
    SolverOptions dense_backend;
    dense_backend.backend = SolverBackend::DenseLlt;
    ASSERT_EQ(condense(a.K, rows, Kz_sparse, dense_backend), Condensation::Outcome::Succeeded) << f;
    EXPECT_LE(rel_diff(Kz_sparse, Kz), 1e-14) << f;
    ++compared;
  }
  EXPECT_GE(compared, 8);
}

TEST(DenseFactor, StaticCondensationByHandAndItsRefusals) {
  // K = [2 -1; -1 2], DOF 1 kept: K_22 - K_21 K_11^-1 K_12 = 2 - 1/2 = 3/2; with the row scaled by
  // a = 2, K_z = (3/2) / 4.
  Eigen::MatrixXd K(2, 2);
  K << 2.0, -1.0, -1.0, 2.0;
  Eigen::MatrixXd Kz;
  const std::vector<int> one{1};
  ASSERT_TRUE(dense_static_condensation(K, one, std::vector<double>{1.0}, Kz));
  EXPECT_NEAR(Kz(0, 0), 1.5, 1e-15);
  ASSERT_TRUE(dense_static_condensation(K, one, std::vector<double>{2.0}, Kz));
  EXPECT_NEAR(Kz(0, 0), 0.375, 1e-15);
  // Both DOFs kept: nothing condensed, K_z = K.
  ASSERT_TRUE(dense_static_condensation(K, std::vector<int>{0, 1}, std::vector<double>{1.0, 1.0}, Kz));
  EXPECT_NEAR((Kz - K).norm(), 0.0, 1e-15);
  // A mechanism (K singular, K_11 positive): left to the saddle point, as dense_schur_condensation leaves it.
  Eigen::MatrixXd M(2, 2);
  M << 1.0, -1.0, -1.0, 1.0;
  EXPECT_FALSE(dense_static_condensation(M, one, std::vector<double>{1.0}, Kz));
  // Indefinite, a column picked twice, a zero coefficient, a column out of range.
  Eigen::MatrixXd I(2, 2);
  I << 1.0, 2.0, 2.0, 1.0;
  EXPECT_FALSE(dense_static_condensation(I, one, std::vector<double>{1.0}, Kz));
  EXPECT_FALSE(dense_static_condensation(K, std::vector<int>{1, 1}, std::vector<double>{1.0, 1.0}, Kz));
  EXPECT_FALSE(dense_static_condensation(K, one, std::vector<double>{0.0}, Kz));
  EXPECT_FALSE(dense_static_condensation(K, std::vector<int>{2}, std::vector<double>{1.0}, Kz));
}

TEST(DenseFactor, RefusesWhatItCannotDoAndLeavesItToTheSparsePath) {
  SparseMatrix K(2, 2);
  K.insert(0, 0) = 1.0;
  K.insert(1, 0) = 2.0;
  K.insert(0, 1) = 2.0;
  K.insert(1, 1) = 1.0;  // eigenvalues 3 and -1: indefinite, positive diagonal
  K.makeCompressed();
  Eigen::MatrixXd Kz;
  EXPECT_FALSE(dense_schur_condensation(Eigen::MatrixXd(K), Eigen::MatrixXd::Identity(1, 2), Kz));
  SparseFactor f;
  EXPECT_EQ(f.factorize(K), FactorStatus::NotPositiveDefinite);
  EXPECT_FALSE(f.dense());
  EXPECT_TRUE(f.usable());  // UMFPACK's LU
}

TEST(DenseFactor, CholeskySkippingZerosMatchesEigensLlt) {
  // A banded matrix with zeros inside the band (skipped), a dense one, and an indefinite one.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int n : {1, 7, 40, 161}) {
    for (const int band : {2, n}) {
      Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n, n);
      for (int i = 0; i < n; ++i)
        for (int j = std::max(0, i - band); j <= i; ++j)
          if ((i + j) % 3 != 1) B(i, j) = U(rng);
      const Eigen::MatrixXd K = B * B.transpose() + n * Eigen::MatrixXd::Identity(n, n);
      Eigen::MatrixXd L = K;
      std::vector<int> last;
      ASSERT_TRUE(cholesky_in_place(L, last)) << n;
      const Eigen::MatrixXd ref = K.llt().matrixL();
      const Eigen::MatrixXd mine = L.triangularView<Eigen::Lower>();
      EXPECT_LE(rel_diff(mine, ref), kAgreement) << n << " band " << band;
      for (int k = 0; k < n; ++k) {
        EXPECT_GE(last[k], k);
        for (int i = last[k] + 1; i < n; ++i) EXPECT_EQ(mine(i, k), 0.0) << i << "," << k;
      }
    }
  }
  Eigen::Matrix2d K;
  K << 1.0, 2.0, 2.0, 1.0;  // indefinite
  Eigen::MatrixXd A = K;
  std::vector<int> last;
  EXPECT_FALSE(cholesky_in_place(A, last));
}

TEST(DenseFactor, DenseAssemblyAndCondensationAgreeWithTheSparseOnTheSuiteModels) {
  int compared = 0;
  for (const auto& f : suite_models()) {
    const Assembled a = assemble(f);
    const int n = static_cast<int>(a.K.rows());
    if (n == 0 || n > kMaxDofs) continue;
    const LinearStructure structure(a.model);
    DenseAssembler dense(*a.map);
    dense.begin();
    structure.assemble(*a.map, dense);
    dense.end();
    const Eigen::MatrixXd Ks = a.K;
    // The same sums in another order: rounding of the largest entries.
    EXPECT_LE(rel_diff(dense.K_ff(), Ks), 1e-14) << f;
    // The node stiffness of the last node both ways (the dense K goes through the dense Schur
    // complement; the sparse one through its own copy to dense, or the saddle point when large).
    const int node = static_cast<int>(a.model.nodes.size()) - 1;
    const CondensedStiffness cd = condense_to_node(a.model, *a.map, dense.K_ff(), node);
    const CondensedStiffness cs = condense_to_node(a.model, *a.map, a.K, node);
    ASSERT_EQ(cd.ok, cs.ok) << f;
    if (!cd.ok) continue;
    EXPECT_EQ(cd.rank, cs.rank) << f;
    EXPECT_EQ(cd.rigid_directions.size(), cs.rigid_directions.size()) << f;
    // The condensation goes through solves with K: its rounding grows with K's conditioning (the
    // generated lumped five-bar's virtual springs, axial against bending: cond ~1e5).
    const double bound = forward_bound(a.K, a.K.diagonal().cwiseSqrt().cwiseInverse());
    EXPECT_LE(rel_diff(cd.K, cs.K), bound) << f;
    EXPECT_LE(rel_diff(cd.compliance, cs.compliance), bound) << f;
    ++compared;
  }
  EXPECT_GE(compared, 12);
}

}  // namespace dense_factor_test
