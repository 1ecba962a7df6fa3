// The solver contract (solvers/linear_solver.hpp) checked on every back end by one typed suite,
// and the one condensation (solvers/condensation.hpp) against closed forms on its dense and
// sparse back ends.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "core/errors.hpp"
#include "solvers/condensation.hpp"
#include "solvers/linear_solver.hpp"

namespace linear_solver_test {

using namespace beamfea;

namespace {

constexpr double kEI = 2.1e11 * 8.0e-6;  // steel, I = 8e-6 m^4
constexpr double kLength = 3.0;

// The bending stiffness (w, theta per node) of a beam of `elements` Euler-Bernoulli elements over
// kLength, in the full pattern of both triangles; `clamped`: node 0's DOFs removed (a cantilever).
// Element matrix: Przemieniecki, Theory of Matrix Structural Analysis (1968), eq. 5.115 in 2-D.
SparseMatrix beam_stiffness(int elements, bool clamped) {
  const double h = kLength / elements;
  Eigen::Matrix4d k;
  k << 12, 6 * h, -12, 6 * h,  //
      6 * h, 4 * h * h, -6 * h, 2 * h * h,  //
      -12, -6 * h, 12, -6 * h,  //
      6 * h, 2 * h * h, -6 * h, 4 * h * h;
  k *= kEI / (h * h * h);
  const int first = clamped ? 2 : 0;
  const int n = 2 * (elements + 1) - first;
  std::vector<Eigen::Triplet<double>> t;
  for (int e = 0; e < elements; ++e)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        const int i = 2 * e + a - first, j = 2 * e + b - first;
        if (i >= 0 && j >= 0) t.emplace_back(i, j, k(a, b));
      }
  SparseMatrix K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  K.makeCompressed();
  return K;
}

// A random sparse symmetric matrix, strictly diagonally dominant with a positive diagonal: SPD.
SparseMatrix random_spd(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  std::uniform_int_distribution<int> pick(0, n - 1);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (int c = 0; c < 4 * n; ++c) {
    const int i = pick(rng), j = pick(rng);
    if (i == j) continue;
    A(i, j) = A(j, i) = U(rng);
  }
  for (int i = 0; i < n; ++i) A(i, i) = A.row(i).cwiseAbs().sum() + 0.5 + std::abs(U(rng));
  SparseMatrix S = A.sparseView();
  S.makeCompressed();
  return S;
}

// tridiag(1, d, 1) of size n: eigenvalues d + 2 cos(k pi / (n + 1)), k = 1..n (Toeplitz
// tridiagonal matrix; e.g. Smith, Numerical Solution of PDEs, 3rd ed., p. 59).
SparseMatrix toeplitz_tridiagonal(int n, double d) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, d);
    if (i + 1 < n) {
      t.emplace_back(i, i + 1, 1.0);
      t.emplace_back(i + 1, i, 1.0);
    }
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

// A free chain of n unit springs' nodes (the graph Laplacian of a path): singular, one zero
// eigenvalue (the rigid translation), exactly so in floating point (integer pivots).
SparseMatrix free_spring_chain(int n) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i + 1 < n; ++i) {
    t.emplace_back(i, i, 1.0);
    t.emplace_back(i + 1, i + 1, 1.0);
    t.emplace_back(i, i + 1, -1.0);
    t.emplace_back(i + 1, i, -1.0);
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

// |A x - b| / (|A| |x| + |b|), max norms: what a backward-stable solve leaves (a few eps).
double relative_residual(const SparseMatrix& A, const Eigen::MatrixXd& X, const Eigen::MatrixXd& B) {
  const double a = Eigen::MatrixXd(A).cwiseAbs().rowwise().sum().maxCoeff();
  return (A * X - B).cwiseAbs().maxCoeff() / (a * X.cwiseAbs().maxCoeff() + B.cwiseAbs().maxCoeff());
}
constexpr double kResidual = 1e-12;

template <SolverBackend B>
struct Backend {
  static constexpr SolverBackend value = B;
};

// Which back ends give the full inertia of an indefinite matrix (LDL^T), which only that of a
// positive definite one (LL^T), which none (LU).
bool full_inertia(SolverBackend b) { return b == SolverBackend::SimplicialLdlt || b == SolverBackend::DenseLdlt; }
bool definite_inertia(SolverBackend b) {
  return b == SolverBackend::Automatic || b == SolverBackend::Cholmod || b == SolverBackend::DenseLlt;
}

}  // namespace

template <class T>
class LinearSolverContract : public ::testing::Test {
 protected:
  std::unique_ptr<LinearSolver> make() const {
    SolverOptions o;
    o.backend = T::value;
    return make_linear_solver(o);
  }
};
using Backends = ::testing::Types<Backend<SolverBackend::Automatic>, Backend<SolverBackend::Cholmod>,
                                  Backend<SolverBackend::Umfpack>, Backend<SolverBackend::SimplicialLdlt>,
                                  Backend<SolverBackend::DenseLlt>, Backend<SolverBackend::DenseLdlt>,
                                  Backend<SolverBackend::DenseLu>>;
TYPED_TEST_SUITE(LinearSolverContract, Backends);

// A cantilever under a tip load P: tip deflection P L^3 / (3 EI) and rotation P L^2 / (2 EI)
// (Timoshenko & Gere, Mechanics of Materials, table of beam deflections), exact at the nodes of
// cubic elements; 8 elements (16 DOFs, Automatic's dense path) and 120 (240 DOFs, CHOLMOD).
TYPED_TEST(LinearSolverContract, SolvesACantileverToItsClosedFormTipDeflection) {
  for (const int elements : {8, 120}) {
    const SparseMatrix K = beam_stiffness(elements, true);
    const auto solver = this->make();
    ASSERT_EQ(solver->compute(K), FactorStatus::Succeeded) << elements;
    ASSERT_TRUE(solver->usable());
    EXPECT_EQ(solver->rows(), K.rows());
    const double P = 1000.0;
    Eigen::VectorXd f = Eigen::VectorXd::Zero(K.rows());
    f[K.rows() - 2] = P;
    const Eigen::VectorXd u = solver->solve(f);
    EXPECT_LE(relative_residual(K, u, f), kResidual) << elements;
    const double w = P * std::pow(kLength, 3) / (3.0 * kEI), theta = P * kLength * kLength / (2.0 * kEI);
    // The forward error of a matrix of condition ~1e10 (120 elements, unscaled): about 1e-6.
    EXPECT_NEAR(u[K.rows() - 2], w, 1e-6 * w) << elements;
    EXPECT_NEAR(u[K.rows() - 1], theta, 1e-6 * theta) << elements;
    if (definite_inertia(TypeParam::value) || full_inertia(TypeParam::value)) {
      ASSERT_TRUE(solver->inertia().has_value());
      EXPECT_EQ(*solver->inertia(), (Inertia{0, 0, static_cast<int>(K.rows())}));
    } else {
      EXPECT_FALSE(solver->inertia().has_value());
    }
  }
}

TYPED_TEST(LinearSolverContract, SolvesManyRightHandSidesOfARandomSpdMatrixAtOnceAndOneByOne) {
  const SparseMatrix A = random_spd(200, 11);
  const auto solver = this->make();
  ASSERT_EQ(solver->compute(A), FactorStatus::Succeeded);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::MatrixXd X0(A.rows(), 7);
  for (Eigen::Index i = 0; i < X0.size(); ++i) X0.data()[i] = U(rng);
  const Eigen::MatrixXd B = A * X0;
  const Eigen::MatrixXd X = solver->solve(B);
  EXPECT_LE(relative_residual(A, X, B), kResidual);
  EXPECT_LE((X - X0).cwiseAbs().maxCoeff(), 1e-10);  // diagonally dominant: well conditioned
  for (Eigen::Index c = 0; c < B.cols(); ++c) {
    Eigen::VectorXd x(A.rows());
    solver->solve(B.col(c), x);
    EXPECT_LE((x - X.col(c)).cwiseAbs().maxCoeff(), 1e-12) << c;
  }
}

TYPED_TEST(LinearSolverContract, RefactorisesAMatrixOfTheSamePatternWithNewValues) {
  const SparseMatrix A = random_spd(60, 5);
  SparseMatrix A2 = A;
  for (int j = 0; j < A2.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A2, j); it; ++it)
      if (it.row() != j) it.valueRef() *= -0.5;  // still diagonally dominant, same pattern
  const auto solver = this->make();
  solver->analyze(A);
  ASSERT_EQ(solver->compute(A), FactorStatus::Succeeded);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  const Eigen::VectorXd x1 = solver->solve(b);
  ASSERT_EQ(solver->compute(A2), FactorStatus::Succeeded);
  const Eigen::VectorXd x2 = solver->solve(b);
  EXPECT_LE(relative_residual(A, x1, b), kResidual);
  EXPECT_LE(relative_residual(A2, x2, b), kResidual);
  EXPECT_GT((x1 - x2).norm(), 1e-3 * x1.norm());  // the new values were used
}

// tridiag(1, 1/2, 1) of size 10: eigenvalues 1/2 + 2 cos(k pi / 11), negative for k = 7..10
// (cos(7 pi / 11) = -0.415 < -1/4 < cos(6 pi / 11) = -0.142): inertia (4, 0, 6).
TYPED_TEST(LinearSolverContract, GivesTheInertiaOfAnIndefiniteMatrixWhereItCan) {
  const SparseMatrix A = toeplitz_tridiagonal(10, 0.5);
  const auto solver = this->make();
  const FactorStatus s = solver->compute(A);
  if (full_inertia(TypeParam::value)) {
    EXPECT_EQ(s, FactorStatus::Succeeded);
    ASSERT_TRUE(solver->inertia().has_value());
    EXPECT_EQ(*solver->inertia(), (Inertia{4, 0, 6}));
  } else {
    EXPECT_FALSE(solver->inertia().has_value());
  }
  if (definite_inertia(TypeParam::value)) {
    EXPECT_NE(s, FactorStatus::Succeeded);  // the LL^T fails; an LU may stand in
  }
  if (solver->usable()) {  // regular: whatever factor there is solves it
    const Eigen::VectorXd b = Eigen::VectorXd::Ones(A.rows());
    EXPECT_LE(relative_residual(A, solver->solve(b), b), kResidual);
  }
}

TYPED_TEST(LinearSolverContract, ReportsASingularMatrixAsAnOutcomeNotAnException) {
  const SparseMatrix A = free_spring_chain(8);
  const auto solver = this->make();
  FactorStatus s = FactorStatus::Succeeded;
  EXPECT_NO_THROW(s = solver->compute(A));
  EXPECT_NE(s, FactorStatus::Succeeded) << to_string(s);
  if (full_inertia(TypeParam::value)) {
    // One zero pivot; Eigen's simplicial LDL^T stops at an exactly zero one and gives none.
    if (const auto in = solver->inertia()) {
      EXPECT_EQ(*in, (Inertia{0, 1, 7}));
    }
  } else {
    EXPECT_FALSE(solver->inertia().has_value());
  }
}

// The one condensation, on a cantilever of EI and L: onto the tip deflection alone (the tip
// rotation free) K_z = 3 EI / L^3; onto the tip's deflection and rotation the 2x2 of the inverse
// of its compliance [L^3/3, L^2/2; L^2/2, L] / EI, i.e. EI [12/L^3, -6/L^2; -6/L^2, 4/L]
// (Timoshenko & Gere; Przemieniecki eq. 5.115). On the dense and sparse back ends, equal results.
TEST(Condensation, CantileverTipStiffnessIsItsClosedFormOnDenseAndSparseBackEnds) {
  const SparseMatrix K = beam_stiffness(10, true);
  const Eigen::Index n = K.rows();
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(1, n), tip = Eigen::MatrixXd::Zero(2, n);
  w(0, n - 2) = 1.0;
  tip(0, n - 2) = 1.0;
  tip(1, n - 1) = 1.0;
  Eigen::Matrix2d closed;
  const double L = kLength;
  closed << 12.0 / (L * L * L), -6.0 / (L * L), -6.0 / (L * L), 4.0 / L;
  closed *= kEI;
  SolverOptions dense, sparse, automatic, automatic_sparse;
  dense.backend = SolverBackend::DenseLlt;
  sparse.backend = SolverBackend::Umfpack;
  automatic_sparse.dense_max_dofs = 0;
  std::vector<Eigen::MatrixXd> tips;
  for (const SolverOptions& o : {dense, sparse, automatic, automatic_sparse}) {
    Eigen::MatrixXd Kz;
    ASSERT_EQ(condense(K, w, Kz, o), Condensation::Outcome::Succeeded) << to_string(o.backend);
    EXPECT_NEAR(Kz(0, 0), 3.0 * kEI / (L * L * L), 1e-9 * 3.0 * kEI / (L * L * L)) << to_string(o.backend);
    ASSERT_EQ(condense(K, tip, Kz, o), Condensation::Outcome::Succeeded) << to_string(o.backend);
    EXPECT_LE((Kz - closed).cwiseAbs().maxCoeff(), 1e-9 * closed.cwiseAbs().maxCoeff()) << to_string(o.backend);
    tips.push_back(Kz);
    // The dense K of a small model's dense assembly: the same.
    Eigen::MatrixXd Kd;
    ASSERT_EQ(condense(Eigen::MatrixXd(K), tip, Kd, o), Condensation::Outcome::Succeeded);
    EXPECT_LE((Kd - Kz).cwiseAbs().maxCoeff(), 1e-12 * closed.cwiseAbs().maxCoeff());
  }
  for (const auto& Kz : tips) EXPECT_LE((Kz - tips[0]).cwiseAbs().maxCoeff(), 1e-10 * closed.cwiseAbs().maxCoeff());
}

// A free-free beam (K singular: two rigid-body modes) held at both ends: the saddle point sees past
// the singular K and gives the beam's own 4x4 end stiffness EI/L^3 [12 6L -12 6L; 6L 4L^2 -6L 2L^2;
// ...] (Przemieniecki eq. 5.115); the dense route cannot factor K and reports a mechanism, as it
// does for the beam held at the tip's deflection only. A zero row is a held DOF.
TEST(Condensation, SaddlePointSeesPastASingularStiffnessTheDenseRouteDoesNot) {
  const SparseMatrix K = beam_stiffness(6, false);
  const Eigen::Index n = K.rows();
  Eigen::MatrixXd ends = Eigen::MatrixXd::Zero(4, n);
  ends(0, 0) = ends(1, 1) = ends(2, n - 2) = ends(3, n - 1) = 1.0;
  const double L = kLength;
  Eigen::Matrix4d k;
  k << 12, 6 * L, -12, 6 * L, 6 * L, 4 * L * L, -6 * L, 2 * L * L, -12, -6 * L, 12, -6 * L, 6 * L, 2 * L * L, -6 * L,
      4 * L * L;
  k *= kEI / (L * L * L);
  SolverOptions dense, sparse, automatic;
  dense.backend = SolverBackend::DenseLdlt;
  sparse.backend = SolverBackend::Cholmod;
  Eigen::MatrixXd Kz;
  EXPECT_EQ(condense(K, ends, Kz, dense), Condensation::Outcome::Mechanism);
  for (const SolverOptions& o : {sparse, automatic}) {
    ASSERT_EQ(condense(K, ends, Kz, o), Condensation::Outcome::Succeeded) << to_string(o.backend);
    EXPECT_LE((Kz - k).cwiseAbs().maxCoeff(), 1e-9 * k.cwiseAbs().maxCoeff()) << to_string(o.backend);
  }
  Eigen::MatrixXd tip_w = Eigen::MatrixXd::Zero(1, n);
  tip_w(0, n - 2) = 1.0;
  EXPECT_EQ(condense(K, tip_w, Kz, dense), Condensation::Outcome::Mechanism);
  Eigen::MatrixXd zero_row = ends;
  zero_row.row(2).setZero();
  EXPECT_EQ(condense(K, zero_row, Kz, automatic), Condensation::Outcome::HeldDof);
}

TEST(SolverOptions, RejectsOutOfRangeValues) {
  SolverOptions o;
  o.singular_rcond = 0.0;
  EXPECT_THROW(make_linear_solver(o), Error);
  o = {};
  o.dense_max_dofs = -1;
  EXPECT_THROW(o.validate(), Error);
}

}  // namespace linear_solver_test
