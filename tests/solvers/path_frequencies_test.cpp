// Natural frequencies along a path (solvers/path/vibration.hpp) against closed forms and the modal
// analysis.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "nl_models.hpp"
#include "solvers/modal.hpp"
#include "solvers/path_following.hpp"
#include "solvers/path/vibration.hpp"

namespace path_frequencies_test {

using namespace beamfea;
using namespace beamfea::test;

namespace {
constexpr double pi = 3.14159265358979323846;
const double E = 210e9, G = 80e9, rho = 7850.0;

// A pinned column along x (16 elements) loaded by -P_cr at B: weak plane x-z (Iy = I), strong
// plane x-y (Iz = 4 I); torsion held at A.
json pinned_column(double L, double A, double I) {
  const double Pcr = pi * pi * E * I / (L * L);
  json d = straight_member(L, 16, E, G, A, I, 4 * I, 2 * I);
  d["materials"][0]["density"] = rho;
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx"}));
  d["supports"].push_back(fix("B", {"uy", "uz"}));
  d["loads"].push_back(load("B", -Pcr, 0, 0));
  return d;
}
}  // namespace

// A pinned column under P = lambda P_cr (Euler load of the weak plane), load control past P_cr.
// The sine is both the buckling and the vibration mode, so (Bazant & Cedolin, Stability of
// Structures, 1991, sec. 3.1; Timoshenko & Gere, Theory of Elastic Stability, 1961, sec. 2.12)
//   omega_k(P) = omega_k(0) sqrt(1 - P / P_k),   P_k the buckling load of mode k.
// Lowest three: the weak plane's k = 1 (P_1 = P_cr), the strong plane's k = 1 (I_z = 4 I: P = 4
// P_cr, omega 2x), the weak plane's k = 2 (P = 4 P_cr, omega 4x).
// The path's tangent is the co-rotational one: its geometric stiffness is the chord's, N/l (I -
// r1 r1^T), i.e. a string with linear interpolation per element, whose eigenvalue for the sampled
// sine sin(k pi x/L) is (2/h^2)(1 - cos(k pi h/L)) instead of (k pi/L)^2 (the sampled sine is an
// eigenvector of both the cubic bending stiffness and this string matrix on a uniform mesh). So the
// discrete buckling loads are the closed form
//   P_k,n = P_k / c_n(k),   c_n(k) = (2 n^2/(k pi)^2) (1 - cos(k pi/n))  (~ 1 - (k pi/n)^2/12),
// 0.32 % above P_cr for n = 16 (h^2 convergence: docs/analyses/path.md). Asserted, with these
// loads: f_k(lambda)/f_k(0) = sqrt(1 - lambda P_cr/P_k,n) to 2e-4 at every step (below P_cr and,
// negative, beyond), the path's critical point at P_1,n to 2e-4, and |f_1| < 1 % f_1(0) at the
// load factor P_1,n/P_cr itself (the frequency falls to zero at the bifurcation). The continuum
// ratio sqrt(1 - lambda) differs by up to 0.005 at lambda = 0.9: that is the co-rotational
// element's discretisation, not the frequencies'.
TEST(PathFrequencies, PinnedColumnFrequencyFallsAsSqrtOneMinusPOverPcrAndReachesZeroAtBuckling) {
  const double L = 3.0, A = 1e-3, I = 1e-9;
  const int n = 16;
  const Model m = read_model(pinned_column(L, A, I));
  const double f0 = pi * pi * std::sqrt(E * I / (rho * A * std::pow(L, 4))) / (2 * pi);
  const auto c = [&](int k) { return 2.0 * n * n / (k * k * pi * pi) * (1.0 - std::cos(k * pi / n)); };
  const double lam_cr[3] = {1.0 / c(1), 4.0 / c(1), 4.0 / c(2)};  // P_k,n / P_cr
  // The load factor of the steps adapts to Newton's iteration counts: equal increments are kept by
  // asking for the iteration count the trivial path takes (1).
  auto path_to = [&](double target, int increments) {
    PathOptions o;
    o.control = PathControl::LoadFactor;
    o.target = target;
    o.increments = increments;
    o.desired_iterations = 1;
    o.frequency_modes = 3;
    return follow_path(m, o);
  };
  const PathResult r = path_to(1.1, 11);
  ASSERT_TRUE(r.completed) << r.brief_report();
  ASSERT_FALSE(r.steps.empty());
  ASSERT_EQ(r.steps[0].frequencies.size(), 3);
  const Eigen::VectorXd f_start = r.steps[0].frequencies;
  EXPECT_NEAR(f_start[0], f0, 1e-5 * f0);  // 16 elements: h^4 (modal_test.cpp)
  int below = 0;
  for (const auto& s : r.steps) {
    ASSERT_EQ(s.frequencies.size(), 3) << "step " << s.step << ": " << s.frequencies_failure;
    const double lam = s.load_factor;
    std::cout << "lambda " << lam << ": f1/f0 " << s.frequencies[0] / f_start[0] << " (closed form "
              << std::copysign(std::sqrt(std::abs(1 - lam / lam_cr[0])), 1 - lam / lam_cr[0]) << ", continuum "
              << std::copysign(std::sqrt(std::abs(1 - lam)), 1 - lam) << "), f2 " << s.frequencies[1] / f_start[1]
              << ", f3 " << s.frequencies[2] / f_start[2] << "\n";
    for (int k = 0; k < 3; ++k) {
      const double x = 1.0 - lam / lam_cr[k];
      EXPECT_NEAR(s.frequencies[k] / f_start[k], std::copysign(std::sqrt(std::abs(x)), x), 2e-4)
          << "mode " << k + 1 << ", lambda " << lam;
    }
    if (lam > 0.05 && lam < 0.95) ++below;
  }
  EXPECT_GE(below, 5);                                   // several steps below P_cr
  EXPECT_NEAR(r.steps.back().load_factor, 1.1, 1e-12);
  EXPECT_LT(r.steps.back().frequencies[0], 0.0);         // beyond P_cr: unstable
  EXPECT_FALSE(r.steps.back().stable);
  // the bifurcation the stability analysis finds is where the frequency vanishes
  ASSERT_EQ(r.critical_points.size(), 1u);
  EXPECT_NEAR(r.critical_points[0].load_factor, lam_cr[0], 2e-4);
  // At the discrete Euler load itself the first frequency is (nearly) zero.
  const PathResult at = path_to(lam_cr[0], 10);
  ASSERT_TRUE(at.completed) << at.brief_report();
  ASSERT_EQ(at.steps.back().frequencies.size(), 3);
  EXPECT_NEAR(at.steps.back().load_factor, lam_cr[0], 1e-12);
  EXPECT_LT(std::abs(at.steps.back().frequencies[0]), 0.01 * f0);
  std::cout << "at P_cr,n = " << lam_cr[0] << " P_cr: f1/f0 = " << at.steps.back().frequencies[0] / f0 << "\n";
}

// A cantilever (8 elements, Iy != Iz) under a small transverse tip load: the path's frequencies
// equal the modal analysis's, at the start (the reference state: the same K and M, to 1e-9) and
// at the loaded state (tip deflection ~1e-4 L: the deformed geometry changes the frequencies by
// O(1e-4) at most, here 1e-8, asserted 1e-6 relative against modal about the loaded state). Lumped mass
// too.
TEST(PathFrequencies, CantileverUnderASmallTipLoadHasTheModalFrequencies) {
  const double L = 1.0, A = 1e-3, Iy = 2e-8, Iz = 5e-8, J = 3e-8;
  const double P = 1e-4 * 3 * E * Iy / (L * L * L);  // tip deflection 1e-4 L in z
  json d = straight_member(L, 8, E, G, A, Iy, Iz, J);
  d["materials"][0]["density"] = rho;
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  d["loads"].push_back(load("B", 0, 0, P));
  const Model m = read_model(d);
  for (MassKind kind : {MassKind::Consistent, MassKind::Lumped}) {
    PathOptions o;
    o.control = PathControl::LoadFactor;
    o.target = 1.0;
    o.increments = 2;
    o.frequency_modes = 6;
    o.frequency_mass = kind;
    o.track = {m.find_node("B")};
    const PathResult r = follow_path(m, o);
    ASSERT_TRUE(r.completed) << r.brief_report();
    EXPECT_NEAR(r.steps.back().track[0][2], 1e-4 * L, 2e-7 * L);  // the deflection it was sized for
    ModalOptions mo;
    mo.modes = 6;
    mo.mass = kind;
    const ModalResult free = solve_modal(m, mo);
    mo.preload = true;
    const ModalResult loaded = solve_modal(m, mo);
    ASSERT_EQ(free.status, ModalStatus::Succeeded);
    ASSERT_EQ(loaded.status, ModalStatus::Succeeded);
    const auto& f_start = r.steps.front().frequencies;
    const auto& f_end = r.steps.back().frequencies;
    ASSERT_EQ(f_start.size(), 6);
    ASSERT_EQ(f_end.size(), 6);
    for (int k = 0; k < 6; ++k) {
      EXPECT_NEAR(f_start[k], free.frequencies[k], 1e-9 * free.frequencies[k]) << "mode " << k + 1;
      EXPECT_NEAR(f_end[k], loaded.frequencies[k], 1e-6 * loaded.frequencies[k]) << "mode " << k + 1;
      std::cout << (kind == MassKind::Lumped ? "lumped" : "consistent") << " mode " << k + 1 << ": path "
                << f_end[k] << " Hz, modal " << loaded.frequencies[k] << " Hz, relative "
                << f_end[k] / loaded.frequencies[k] - 1 << "\n";
    }
  }
}

// The mass in the deformed configuration: a cantilever rolled by a tip moment into a quarter circle
// carries the same total translational mass (rigid translations are still rigid translations), and
// a point mass's rotary inertia turns with its node: diag(1, 2, 3) turned by pi/2 about z is
// diag(2, 1, 3) (the reference mass would keep diag(1, 2, 3)).
TEST(PathFrequencies, DeformedMassKeepsTheTotalMassAndTurnsInertias) {
  const double L = 1.0, A = 1e-3, I = 1e-8;
  json d = straight_member(L, 8, E, G, A, I, I, 2 * I);
  d["materials"][0]["density"] = rho;
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  d["loads"].push_back(load("B", 0, 0, 0, 0, 0, 0.5 * pi * E * I / L));  // a quarter circle in x-y
  Model m = read_model(d);
  PointMass pm;
  pm.node = m.find_node("B");
  pm.mass = 2.0;
  pm.inertia = Vec3(1.0, 2.0, 3.0).asDiagonal();
  m.masses.push_back(pm);
  PathOptions o;
  o.control = PathControl::LoadFactor;
  o.increments = 10;
  const PathResult r = follow_path(m, o);
  ASSERT_TRUE(r.completed) << r.brief_report();
  const NonlinearState& s = r.steps.back().state;
  const int b = m.find_node("B");
  // a quarter circle of length L: radius 2L/pi
  EXPECT_NEAR(s.x[b].x(), 2 * L / pi, 3e-3);  // 8 chords: 1.6e-3 short
  EXPECT_NEAR(s.x[b].y(), 2 * L / pi, 3e-3);
  const NonlinearStructure ns(m);
  const SparseMatrix M = deformed_raw_mass(ns, s, MassKind::Consistent);
  const int nn = static_cast<int>(m.nodes.size());
  const double mtot = rho * A * L + pm.mass;
  for (int dir = 0; dir < 3; ++dir) {
    Eigen::VectorXd u = Eigen::VectorXd::Zero(6 * nn);
    for (int n = 0; n < nn; ++n) u[6 * n + dir] = 1.0;
    EXPECT_NEAR(u.dot(M * u), mtot, 1e-12 * mtot) << "direction " << dir;
  }
  // B has turned by pi/2 about z; the beam's own rotary inertia there is rho Ip L_e/3 ~ 1e-5.
  const Eigen::Vector3d expected(2.0, 1.0, 3.0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(M.coeff(6 * b + 3 + i, 6 * b + 3 + j), i == j ? expected[i] : 0.0, 1e-3) << i << "," << j;
}

}  // namespace path_frequencies_test
