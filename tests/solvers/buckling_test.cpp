// Linearised buckling (solvers/buckling.hpp) against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "solvers/buckling.hpp"
#include "nl_models.hpp"

namespace buckling_test {

using namespace beamfea;
using namespace beamfea::test;

namespace {
constexpr double pi = 3.14159265358979323846;
const double E = 210e9, G = 81e9, A = 1e-3, I = 1e-6, J = 2e-6;

double first_factor(const json& d, int modes = 1) {
  const Model m = read_model(d);
  BucklingOptions o;
  o.modes = modes;
  const BucklingResult r = solve_buckling(m, o);
  EXPECT_EQ(r.status, BucklingStatus::Succeeded) << r.message;
  return r.load_factors.size() ? r.load_factors[0] : NAN;
}
}  // namespace

// Euler's cantilever: P_cr = pi^2 EI / (4 L^2) (Timoshenko & Gere, Theory of Elastic Stability,
// 2nd ed., 1961, eq. 2.3). The Hermite geometric stiffness converges as h^2 in the error of P_cr
// or faster: the error must shrink at every refinement and be below 1e-4 at 8 elements.
TEST(Buckling, CantileverColumnConvergesToEulerLoad) {
  const double L = 3.0, P = 1000.0;
  const double exact = pi * pi * E * I / (4 * L * L) / P;
  double previous = 1.0;
  for (int n : {1, 2, 4, 8}) {
    json d = straight_member(L, n, E, G, A, I, I, J);
    d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
    d["loads"].push_back(load("B", -P, 0, 0));
    const double err = std::abs(first_factor(d) / exact - 1.0);
    std::cout << "cantilever, " << n << " elements: relative error " << err << "\n";
    EXPECT_LT(err, previous) << n << " elements";
    previous = err;
  }
  EXPECT_LT(previous, 1e-4);
}

// Pinned-pinned column: P_cr = pi^2 EI / L^2 (Timoshenko & Gere eq. 2.5); the first two modes
// (both bending planes, Iy = Iz) coincide, the third is 4 P_cr.
TEST(Buckling, PinnedColumnConvergesToEulerLoadWithHigherModes) {
  const double L = 4.0, P = 1000.0;
  const double exact = pi * pi * E * I / (L * L) / P;
  double previous = 1.0;
  for (int n : {2, 4, 8, 16}) {
    json d = straight_member(L, n, E, G, A, I, I, J);
    d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx"}));
    d["supports"].push_back(fix("B", {"uy", "uz"}));
    d["loads"].push_back(load("B", -P, 0, 0));
    const Model m = read_model(d);
    BucklingOptions o;
    o.modes = 3;
    const BucklingResult r = solve_buckling(m, o);
    ASSERT_EQ(r.status, BucklingStatus::Succeeded);
    ASSERT_EQ(r.load_factors.size(), 3);
    const double err = std::abs(r.load_factors[0] / exact - 1.0);
    std::cout << "pinned, " << n << " elements: relative error " << err << "\n";
    EXPECT_LT(err, previous) << n;
    previous = err;
    EXPECT_NEAR(r.load_factors[1] / r.load_factors[0], 1.0, 1e-8);
    if (n >= 8) {
      EXPECT_NEAR(r.load_factors[2] / exact, 4.0, 4.0 * 2e-3);
    }
    // Modes are normalised: largest translation 1.
    EXPECT_NEAR(r.modes[0].cwiseAbs().maxCoeff(), 1.0, 1e-12);
  }
  EXPECT_LT(previous, 1e-4);
}

// Lateral-torsional buckling of a simply supported beam ("fork" supports) under uniform moment:
// M_cr = (pi / L) sqrt(E Iy G J)  (Timoshenko & Gere 1961, sec. 6.2, eq. 6-21 without warping).
// Bending about the strong axis (local z, Iz >> Iy); the error must shrink with refinement.
TEST(Buckling, LateralTorsionalBucklingErrorShrinksWithRefinement) {
  const double L = 6.0, M = 1000.0, Iy = 2e-6, Iz = 8e-5, Jt = 1e-7;
  const double exact = pi / L * std::sqrt(E * Iy * G * Jt) / M;
  std::vector<double> errs;
  for (int n : {4, 8, 16, 32}) {
    json d = straight_member(L, n, E, G, 1e-2, Iy, Iz, Jt);
    d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx"}));
    d["supports"].push_back(fix("B", {"uy", "uz", "rx"}));
    d["loads"].push_back(load("A", 0, 0, 0, 0, 0, -M));
    d["loads"].push_back(load("B", 0, 0, 0, 0, 0, M));
    errs.push_back(std::abs(first_factor(d) / exact - 1.0));
    std::cout << "lateral-torsional, " << n << " elements: relative error " << errs.back() << "\n";
  }
  for (std::size_t i = 1; i < errs.size(); ++i) EXPECT_LT(errs[i], errs[i - 1]) << i;
  EXPECT_LT(errs.back(), 2e-3);
}

// Model A of Pashkevich et al. (000_9fcd638e60a85b77, sec. 5): a straight rigid link on a
// rotational spring K_theta, axial end force P: P_cr = K_theta / L exactly (constraint curvature
// of the rigid link, no beam at all). Two links: the 2x2 problem
// [2k - PL, -k ... ] gives P_cr = (3 - sqrt 5) k / (2 L) for springs k at both hinges.
TEST(Buckling, RigidChainOnSpringsBucklesAtKOverL) {
  const double L = 0.5, k = 200.0, P = 10.0;
  json d = rigid_chain(1, L, k);
  d["loads"].push_back(load("N1", -P, 0, 0));
  EXPECT_NEAR(first_factor(d) * P, k / L, 1e-9 * k / L);

  json d2 = rigid_chain(2, L, k);
  d2["loads"].push_back(load("N2", -P, 0, 0));
  EXPECT_NEAR(first_factor(d2) * P, (3.0 - std::sqrt(5.0)) / 2.0 * k / L, 1e-9 * k / L);
}

TEST(Buckling, TensionGivesNoPositiveLoadFactor) {
  json d = straight_member(3.0, 4, E, G, A, I, I, J);
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  d["loads"].push_back(load("B", 1000.0, 0, 0));
  const BucklingResult r = solve_buckling(read_model(d));
  EXPECT_EQ(r.status, BucklingStatus::NoCompression);
}

// Above 300 free DOFs the sparse path runs (Spectra: estimate pass, then shift-invert in buckling
// mode): 80 elements (480 DOFs); the cantilever's first two factors (both planes) are pi^2 EI/(4L^2)
// and the next two 9 times that (T&G eq. 2.3, n = 3).
TEST(Buckling, SparseShiftInvertPathGivesEulerLoadsOfAFineMesh) {
  const double L = 3.0, P = 1000.0;
  const double exact = pi * pi * E * I / (4 * L * L) / P;
  json d = straight_member(L, 80, E, G, A, I, I, J);
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  d["loads"].push_back(load("B", -P, 0, 0));
  BucklingOptions o;
  o.modes = 4;
  const BucklingResult r = solve_buckling(read_model(d), o);
  ASSERT_EQ(r.status, BucklingStatus::Succeeded) << r.message;
  ASSERT_GT(r.free_dofs, 300);
  ASSERT_EQ(r.load_factors.size(), 4);
  EXPECT_NEAR(r.load_factors[0] / exact, 1.0, 1e-6);
  EXPECT_NEAR(r.load_factors[1] / exact, 1.0, 1e-6);
  EXPECT_NEAR(r.load_factors[2] / (9 * exact), 1.0, 1e-5);
  EXPECT_NEAR(r.load_factors[3] / (9 * exact), 1.0, 1e-5);
}

}  // namespace buckling_test
