// The SLEPc eigen-solvers (solvers/slepc_eigen.hpp) behind modal and buckling: the same pairs as the
// direct solvers, and the closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "core/assembly.hpp"
#include "loop_models.hpp"
#include "nl_models.hpp"
#include "solvers/buckling.hpp"
#include "solvers/initial_stress.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/mass_matrix.hpp"
#include "solvers/modal.hpp"
#include "solvers/slepc_eigen.hpp"
#include "solvers/structure.hpp"

namespace slepc_eigen_test {

using namespace beamfea;
using namespace beamfea::test;

namespace {
constexpr double pi = 3.14159265358979323846;
const double E = 210e9, G = 80e9, rho = 7850.0;

Model with_solver(Model m, SolverChoice::Type type) {
  m.solver.type = type;
  m.solver.given = true;
  return m;
}

// The cosine of the largest angle between the mode phi (raw, M-normalised) and the span of the
// modes of `ref` whose eigenvalue equals `lambda` to `tol` (a degenerate pair is a plane: only the
// subspace is defined), in the Euclidean inner product over raw DOFs.
double subspace_cosine(const Eigen::VectorXd& phi, const std::vector<Eigen::VectorXd>& ref, const Eigen::VectorXd& values,
                       double lambda, double tol) {
  std::vector<Eigen::VectorXd> basis;
  for (Eigen::Index j = 0; j < values.size(); ++j)
    if (std::abs(values[j] - lambda) <= tol * std::max(1.0, std::abs(lambda))) basis.push_back(ref[static_cast<std::size_t>(j)]);
  if (basis.empty()) return 0.0;
  Eigen::MatrixXd B(phi.size(), static_cast<Eigen::Index>(basis.size()));
  for (std::size_t j = 0; j < basis.size(); ++j) B.col(static_cast<Eigen::Index>(j)) = basis[j];
  const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(B).householderQ() * Eigen::MatrixXd::Identity(B.rows(), B.cols());
  return (Q.transpose() * phi).norm() / phi.norm();
}

// Iterative = direct: eigenvalues to `rel` (relative, with `abs_floor` for zero modes), each
// iterative mode in the direct modes' eigenspace (cosine 1 to 1e-6), residuals small.
void expect_same_modes(const Model& m, int modes, double rel, double abs_floor) {
  ModalOptions o;
  o.modes = modes;
  const ModalResult d = solve_modal(with_solver(m, SolverChoice::Type::Direct), o);
  const ModalResult it = solve_modal(with_solver(m, SolverChoice::Type::Iterative), o);
  ASSERT_EQ(d.status, ModalStatus::Succeeded) << d.message;
  ASSERT_EQ(it.status, ModalStatus::Succeeded) << it.message;
  EXPECT_FALSE(d.solver.iterative);
  EXPECT_EQ(d.solver.iterations, 1);
  EXPECT_TRUE(it.solver.iterative);
  EXPECT_GE(it.solver.iterations, 1);
  EXPECT_LT(d.solver.residual, 1e-6);
  EXPECT_LT(it.solver.residual, 1e-6);
  ASSERT_EQ(d.eigenvalues.size(), it.eigenvalues.size());
  for (Eigen::Index k = 0; k < d.eigenvalues.size(); ++k) {
    EXPECT_NEAR(it.eigenvalues[k], d.eigenvalues[k], rel * std::abs(d.eigenvalues[k]) + abs_floor) << "mode " << k;
    EXPECT_EQ(it.kinds[static_cast<std::size_t>(k)], d.kinds[static_cast<std::size_t>(k)]) << "mode " << k;
    if (d.kinds[static_cast<std::size_t>(k)] != ModeKind::Elastic) continue;  // zero modes: any basis of the null space
    EXPECT_GT(subspace_cosine(it.modes[static_cast<std::size_t>(k)], d.modes, d.eigenvalues, it.eigenvalues[k], 1e-6),
              1.0 - 1e-6)
        << "mode " << k;
  }
}

void expect_same_buckling(const Model& m, int modes, double rel) {
  BucklingOptions o;
  o.modes = modes;
  const BucklingResult d = solve_buckling(with_solver(m, SolverChoice::Type::Direct), o);
  const BucklingResult it = solve_buckling(with_solver(m, SolverChoice::Type::Iterative), o);
  ASSERT_EQ(d.status, BucklingStatus::Succeeded) << d.message;
  ASSERT_EQ(it.status, BucklingStatus::Succeeded) << it.message;
  EXPECT_TRUE(it.solver.iterative);
  EXPECT_LT(d.solver.residual, 1e-6);
  EXPECT_LT(it.solver.residual, 1e-6);
  ASSERT_EQ(d.load_factors.size(), it.load_factors.size());
  for (Eigen::Index k = 0; k < d.load_factors.size(); ++k) {
    EXPECT_NEAR(it.load_factors[k], d.load_factors[k], rel * d.load_factors[k]) << "mode " << k;
    EXPECT_GT(subspace_cosine(it.modes[static_cast<std::size_t>(k)], d.modes, d.load_factors, it.load_factors[k], 1e-6),
              1.0 - 1e-6)
        << "mode " << k;
  }
}

// A 3-D portal: two columns of Euler-Bernoulli beams (or Timoshenko), a beam girder joined to one
// column top by a revolute joint about y with a spring, a rigid offset arm carrying a point mass.
Model portal(BeamTheory theory) {
  const double h = 3.0, w = 4.0;
  json d;
  d["nodes"] = json::array({{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {0, 0, h}}},
                            {{"id", "C"}, {"xyz", {w, 0, 0}}}, {{"id", "D"}, {"xyz", {w, 0, h}}},
                            {{"id", "D2"}, {"xyz", {w, 0, h}}}, {{"id", "P"}, {"xyz", {w / 2, 0.5, h}}},
                            {{"id", "Q"}, {"xyz", {w / 2, 0, h}}}});
  d["materials"] = json::array({{{"id", "s"}, {"E", E}, {"G", G}, {"density", rho}}});
  d["sections"] = json::array({{{"id", "c"}, {"A", 4e-3}, {"Iy", 2e-5}, {"Iz", 1e-5}, {"J", 5e-6}, {"k", 0.5}}});
  const json y = json::array({0, 1, 0});
  d["elements"] = json::array(
      {{{"id", "c1"}, {"type", "beam"}, {"nodes", {"A", "B"}}, {"material", "s"}, {"section", "c"}, {"orientation", y}, {"divisions", 6}},
       {{"id", "c2"}, {"type", "beam"}, {"nodes", {"C", "D"}}, {"material", "s"}, {"section", "c"}, {"orientation", y}, {"divisions", 6}},
       {{"id", "g1"}, {"type", "beam"}, {"nodes", {"B", "Q"}}, {"material", "s"}, {"section", "c"}, {"orientation", y}, {"divisions", 4}},
       {{"id", "g2"}, {"type", "beam"}, {"nodes", {"Q", "D2"}}, {"material", "s"}, {"section", "c"}, {"orientation", y}, {"divisions", 4}},
       {{"id", "arm"}, {"type", "rigid"}, {"nodes", {"Q", "P"}}}});
  d["joints"] = json::array({{{"id", "hinge"}, {"type", "revolute"}, {"nodes", {"D", "D2"}}, {"axes", {y}}, {"stiffness", {2e6}}}});
  d["supports"] = json::array({fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}), fix("C", {"ux", "uy", "uz", "rx", "ry", "rz"})});
  d["loads"] = json::array({load("B", 0, 0, -2e5), load("D", 1e4, 0, -2e5)});
  Model m = read_model(d);
  for (auto& e : m.elements) e.theory = theory;
  for (auto& e : m.members) e.theory = theory;
  m.masses.push_back({m.find_node("P"), 50.0, Mat3::Identity()});
  return m;
}
}  // namespace

// Cantilever bending on SLEPc: omega_n = (beta_n L)^2 sqrt(EI / (rho A L^4)), beta_n L = 1.8751,
// 4.6941 (Blevins, Formulas for Natural Frequency and Mode Shape, 1979, Table 8-1; refined by
// Newton on cos(bL) cosh(bL) = -1). Iy = 4 Iz: bending about z first, about y at twice the
// frequency. 32 cubic elements: the discretisation error is below 1e-6 (h^4).
TEST(SlepcEigen, CantileverFrequenciesMatchBetaL) {
  const double L = 1.0, A = 1e-3, Iz = 1e-12, Iy = 4e-12, J = 2e-12;
  double roots[2] = {1.8751, 4.6941};
  for (double& b : roots)
    for (int it = 0; it < 20; ++it)
      b -= (std::cos(b) * std::cosh(b) + 1) / (-std::sin(b) * std::cosh(b) + std::cos(b) * std::sinh(b));
  json d = straight_member(L, 32, E, G, A, Iy, Iz, J);
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  Model m = read_model(d);
  for (auto& mat : m.materials) mat.density = rho;
  m = with_solver(m, SolverChoice::Type::Iterative);
  ModalOptions o;
  o.modes = 4;
  const ModalResult r = solve_modal(m, o);
  ASSERT_EQ(r.status, ModalStatus::Succeeded) << r.message;
  EXPECT_TRUE(r.solver.iterative);
  const auto f = [&](double bL, double I) { return bL * bL * std::sqrt(E * I / (rho * A * L * L * L * L)) / (2 * pi); };
  const double expected[4] = {f(roots[0], Iz), f(roots[0], Iy), f(roots[1], Iz), f(roots[1], Iy)};
  ASSERT_EQ(r.frequencies.size(), 4);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(r.frequencies[k], expected[k], 1e-6 * expected[k]) << "mode " << k;
  EXPECT_LT(r.solver.residual, 1e-8);
}

// The multigrid path (conjugate gradients + GAMG with the rigid-body near null space, forced on a
// small system) gives the factorised path's eigenvalues to the tolerance; hypre's BoomerAMG too.
TEST(SlepcEigen, MultigridShiftInvertMatchesFactorisedPath) {
  json d = straight_member(2.0, 40, E, G, 1e-3, 4e-8, 1e-8, 2e-8);
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  Model m = read_model(d);
  for (auto& mat : m.materials) mat.density = rho;
  const DofMap map(m);
  const LinearStructure structure(m);
  SystemAssembler ka(map), ma(map);
  structure.assemble_stiffness(map, ka);
  ma.begin();
  assemble_mass(structure, map, MassKind::Consistent, ma);
  ma.end();
  const SparseMatrix& K = ka.K_ff();
  const SparseMatrix& M = ma.K_ff();
  const Eigen::MatrixXd Z = free_rigid_body_motions(m, map);
  SlepcEigenOptions o;
  o.count = 6;
  o.target = -1e-3;
  o.rtol = 1e-9;
  o.linear = SlepcEigenOptions::Linear::Factor;
  const SlepcEigenPairs ref = slepc_vibration_pairs(K, M, o, &Z);
  ASSERT_TRUE(ref.converged) << ref.message;
  EXPECT_EQ(ref.linear_iterations, 0);
  for (auto pc : {SolverChoice::Preconditioner::Gamg, SolverChoice::Preconditioner::Hypre}) {
    o.linear = SlepcEigenOptions::Linear::Multigrid;
    o.preconditioner = pc;
    const SlepcEigenPairs mg = slepc_vibration_pairs(K, M, o, &Z);
    ASSERT_TRUE(mg.converged) << mg.message;
    EXPECT_GT(mg.linear_iterations, 0);
    ASSERT_EQ(mg.values.size(), 6);
    for (Eigen::Index k = 0; k < 6; ++k) EXPECT_NEAR(mg.values[k], ref.values[k], 1e-7 * ref.values[k]) << "mode " << k;
    EXPECT_LT(relative_eigen_residual(K, M, mg.values, mg.vectors), 1e-6);
  }
  // A linear solve allowed one iteration cannot reach its tolerance: not converged, and said so.
  o.preconditioner = SolverChoice::Preconditioner::Gamg;
  o.max_linear_iterations = 1;
  const SlepcEigenPairs stuck = slepc_vibration_pairs(K, M, o, &Z);
  EXPECT_FALSE(stuck.converged);
  EXPECT_NE(stuck.message.find("modal"), std::string::npos) << stuck.message;
}

// Joints, a rigid link with a point mass, Euler-Bernoulli and Timoshenko beams.
TEST(SlepcEigen, ModalOfAPortalWithAJointAndARigidArmEqualsDirect) {
  expect_same_modes(portal(BeamTheory::EulerBernoulli), 8, 1e-8, 0.0);
  expect_same_modes(portal(BeamTheory::Timoshenko), 8, 1e-8, 0.0);
}

// About the loaded state (K + K_g): the preload path, with LU for the possibly indefinite shift.
TEST(SlepcEigen, ModalAboutTheLoadedStateEqualsDirect) {
  const Model m = portal(BeamTheory::EulerBernoulli);
  ModalOptions o;
  o.modes = 5;
  o.preload = true;
  const ModalResult d = solve_modal(with_solver(m, SolverChoice::Type::Direct), o);
  const ModalResult it = solve_modal(with_solver(m, SolverChoice::Type::Iterative), o);
  ASSERT_EQ(d.status, ModalStatus::Succeeded) << d.message;
  ASSERT_EQ(it.status, ModalStatus::Succeeded) << it.message;
  for (Eigen::Index k = 0; k < 5; ++k) EXPECT_NEAR(it.eigenvalues[k], d.eigenvalues[k], 1e-8 * d.eigenvalues[k]);
}

// A closed loop of rigid bars and joints (the sway frame, closed through a rigid ground link) with
// point masses at the tops: the joint coordinates' modes; and its buckling load k/h (Bazant &
// Cedolin 1991, sec. 1.2), on SLEPc.
TEST(SlepcEigen, ClosedLoopModesAndBucklingEqualDirect) {
  const double h = 2.0, w = 3.0, k = 500.0;
  Model m = read_model(sway_frame_model(h, w, k, 1.0, true));
  m.masses.push_back({m.find_node("T1"), 2.0, 0.1 * Mat3::Identity()});
  m.masses.push_back({m.find_node("T2"), 3.0, 0.1 * Mat3::Identity()});
  m.masses.push_back({m.find_node("G2"), 1.0, 0.1 * Mat3::Identity()});
  expect_same_modes(m, 3, 1e-8, 1e-9);
  BucklingOptions o;
  o.modes = 1;
  const BucklingResult b = solve_buckling(with_solver(m, SolverChoice::Type::Iterative), o);
  ASSERT_EQ(b.status, BucklingStatus::Succeeded) << b.message;
  EXPECT_NEAR(b.load_factors[0], k / h, 1e-8 * k / h);
}

// Euler's cantilever: P_cr = pi^2 EI / (4 L^2) (Timoshenko & Gere, Theory of Elastic Stability,
// 1961, sec. 2.1), 16 elements (error ~1e-8); the direct and iterative load factors and modes agree.
TEST(SlepcEigen, CantileverBucklingIsEulersLoad) {
  const double L = 3.0, Iz = 2e-6, Iy = 5e-6, P = 1e3;
  json d = straight_member(L, 16, E, G, 1e-2, Iy, Iz, 1e-6);
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  d["loads"].push_back(load("B", -P, 0, 0));
  const Model m = read_model(d);
  BucklingOptions o;
  o.modes = 3;
  const BucklingResult it = solve_buckling(with_solver(m, SolverChoice::Type::Iterative), o);
  ASSERT_EQ(it.status, BucklingStatus::Succeeded) << it.message;
  const double Pcr = pi * pi * E * Iz / (4 * L * L);
  EXPECT_NEAR(it.load_factors[0] * P, Pcr, 1e-6 * Pcr);
  EXPECT_LT(it.solver.residual, 1e-8);
  expect_same_buckling(m, 3, 1e-8);
}

TEST(SlepcEigen, BucklingOfAPortalEqualsDirect) {
  expect_same_buckling(portal(BeamTheory::EulerBernoulli), 3, 1e-8);
  expect_same_buckling(portal(BeamTheory::Timoshenko), 3, 1e-8);
}

// The multigrid path of buckling: CG + GAMG applies K^{-1}.
TEST(SlepcEigen, MultigridBucklingMatchesFactorisedPath) {
  json d = straight_member(3.0, 40, E, G, 1e-2, 5e-6, 2e-6, 1e-6);
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  d["loads"].push_back(load("B", -1e3, 0, 0));
  const Model m = read_model(d);
  const BucklingResult ref = solve_buckling(with_solver(m, SolverChoice::Type::Direct));
  ASSERT_EQ(ref.status, BucklingStatus::Succeeded);
  // K and -K_g as solve_buckling forms them, through its result: rebuild with the same parts.
  const DofMap map(m);
  const LinearStructure structure(m);
  SystemAssembler ka(map);
  structure.assemble_stiffness(map, ka);
  const LinearStaticResult lin = LinearSystem(m).solve(m.default_loads());
  SparseMatrix Kg = geometric_stiffness(m, map, structure, lin, m.default_loads(), GeometricStiffness::Full);
  const SparseMatrix KG = -0.5 * (SparseMatrix(Kg.transpose()) + Kg);
  SlepcEigenOptions o;
  o.count = 4;
  o.rtol = 1e-9;
  o.linear = SlepcEigenOptions::Linear::Multigrid;
  const Eigen::MatrixXd Z = free_rigid_body_motions(m, map);
  const SlepcEigenPairs mg = slepc_buckling_pairs(ka.K_ff(), KG, o, &Z);
  ASSERT_TRUE(mg.converged) << mg.message;
  EXPECT_GT(mg.linear_iterations, 0);
  ASSERT_EQ(mg.values.size(), 4);
  for (Eigen::Index k = 0; k < 4; ++k) EXPECT_NEAR(mg.values[k], ref.load_factors[k], 1e-7 * ref.load_factors[k]);
}

}  // namespace slepc_eigen_test
