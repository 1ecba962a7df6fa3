// Modal analysis (solvers/modal.hpp) against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "nl_models.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/modal.hpp"

namespace modal_test {

using namespace beamfea;
using namespace beamfea::test;

namespace {
constexpr double pi = 3.14159265358979323846;
const double E = 210e9, G = 80e9, rho = 7850.0;

// Sets the density of every material and the theory of every beam (until the reader parses them).
void set_density(Model& m, double density) {
  for (auto& mat : m.materials) mat.density = density;
}
void set_timoshenko(Model& m) {
  for (auto& e : m.elements) e.theory = BeamTheory::Timoshenko;
  for (auto& e : m.members) e.theory = BeamTheory::Timoshenko;
}
ModalResult modal(const Model& m, int modes, MassKind kind = MassKind::Consistent, bool preload = false) {
  ModalOptions o;
  o.modes = modes;
  o.mass = kind;
  o.preload = preload;
  ModalResult r = solve_modal(m, o);
  EXPECT_EQ(r.status, ModalStatus::Succeeded) << r.message;
  return r;
}
// Fixes `dofs` at every node of a model read from d.
void fix_everywhere(Model& m, std::initializer_list<int> dofs) {
  for (std::size_t n = 0; n < m.nodes.size(); ++n) {
    Support s;
    s.node = static_cast<int>(n);
    for (int d : dofs) s.fixed[d] = true;
    m.supports.push_back(s);
  }
}
}  // namespace

// Cantilever bending: omega_n = (beta_n L)^2 sqrt(EI / (rho A L^4)), beta_n L = 1.8751, 4.6941,
// 7.8548 (Blevins, Formulas for Natural Frequency and Mode Shape, 1979, Table 8-1; the roots of
// cos(bL) cosh(bL) = -1, to 5 figures; solved here to full precision by Newton). Iy = Iz: each
// frequency twice. The section is slender (r/L = 3e-5) so that rotary inertia changes the third
// frequency by < 1e-7. The error must shrink with every refinement (as h^4) and be < 1e-5 at 32
// elements.
TEST(Modal, CantileverBendingFrequenciesConvergeToBetaL) {
  const double L = 1.0, A = 1e-3, I = 1e-12, J = 2e-12;
  double roots[3] = {1.8751, 4.6941, 7.8548};
  for (double& b : roots)
    for (int it = 0; it < 20; ++it)
      b -= (std::cos(b) * std::cosh(b) + 1) / (-std::sin(b) * std::cosh(b) + std::cos(b) * std::sinh(b));
  EXPECT_NEAR(roots[0], 1.8751, 1e-4);
  EXPECT_NEAR(roots[2], 7.8548, 1e-4);
  double previous[3] = {1, 1, 1};
  for (int n : {2, 4, 8, 16, 32}) {
    json d = straight_member(L, n, E, G, A, I, I, J);
    d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
    Model m = read_model(d);
    set_density(m, rho);
    const ModalResult r = modal(m, 6);
    ASSERT_EQ(r.frequencies.size(), 6);
    for (int k = 0; k < 3; ++k) {
      const double exact = roots[k] * roots[k] * std::sqrt(E * I / (rho * A * std::pow(L, 4))) / (2 * pi);
      const double err = std::abs(r.frequencies[2 * k] / exact - 1.0);
      EXPECT_NEAR(r.frequencies[2 * k + 1], r.frequencies[2 * k], 1e-8 * exact);  // the other plane
      std::cout << "cantilever, " << n << " elements, mode " << k + 1 << ": relative error " << err << "\n";
      if (n > 2 || k < 2) {
        EXPECT_LT(err, previous[k]) << n << " elements, mode " << k + 1;
      }
      previous[k] = err;
      EXPECT_EQ(r.kinds[2 * k], ModeKind::Elastic);
    }
  }
  for (double e : previous) EXPECT_LT(e, 1e-5);
}

// Fixed-free rod: axial omega_n = (2n - 1) pi/(2L) sqrt(E/rho), torsional (2n - 1) pi/(2L)
// sqrt(G J/(rho Ip)) with J = Ip (a circle) (Blevins 1979, Table 8-16 / 8-19). Bending and shear
// are locked at every node so that only u and rx remain. Linear elements: consistent mass
// over-estimates, lumped under-estimates (Cook et al., Concepts and Applications of FEA, 4th ed.,
// sec. 11.3), each by about (k h)^2/24: at 40 elements < 1.2e-4 for the first mode.
TEST(Modal, AxialAndTorsionalFrequenciesOfAFixedFreeRodBracketTheExactOnes) {
  const double L = 2.0, r = 0.01, A = pi * r * r, I = pi * std::pow(r, 4) / 4;
  const int n = 40;
  json d = straight_member(L, n, E, G, A, I, I, 2 * I);
  d["supports"].push_back(fix("A", {"ux", "rx"}));
  Model m = read_model(d);
  set_density(m, rho);
  fix_everywhere(m, {1, 2, 4, 5});
  const double wa = pi / (2 * L) * std::sqrt(E / rho) / (2 * pi);
  const double wt = pi / (2 * L) * std::sqrt(G / rho) / (2 * pi);
  ASSERT_LT(wa, 3 * wt);
  const ModalResult c = modal(m, 4, MassKind::Consistent);
  const ModalResult l = modal(m, 4, MassKind::Lumped);
  // order: torsion 1, axial 1, torsion 2 (3 wt), then axial 2 (3 wa) or torsion 3 (5 wt)
  ASSERT_EQ(c.frequencies.size(), 4);
  const double exact[3] = {wt, wa, 3 * wt};
  for (int k = 0; k < 3; ++k) {
    const double ec = c.frequencies[k] / exact[k] - 1.0, el = l.frequencies[k] / exact[k] - 1.0;
    std::cout << "rod mode " << k + 1 << ": consistent " << ec << ", lumped " << el << "\n";
    EXPECT_GT(ec, 0.0);
    EXPECT_LT(el, 0.0);
    EXPECT_LT(std::abs(ec), (k == 2 ? 9 : 1) * 1.2e-4);
    EXPECT_LT(std::abs(el), (k == 2 ? 9 : 1) * 1.2e-4);
  }
  // the torsion mode moves rx only, the axial mode ux only
  EXPECT_LT(std::abs(c.modes[0][6 * 1 + 0]), 1e-12 * std::abs(c.modes[0][6 * 1 + 3]));
}

// A point mass on a massless cantilever: omega = sqrt(3 EI / (m L^3)) in each bending plane and
// sqrt(EA / (m L)) axially, exact for any number of elements (the static flexibility is exact).
// The effective mass of each mode is m in its direction (Gamma = phi^T M r = sqrt(m)), and the
// model has exactly three finite modes, however many are asked for.
TEST(Modal, PointMassOnAMasslessCantileverIsExact) {
  const double L = 1.2, A = 1e-3, Iy = 2e-7, Iz = 8e-7, J = 1e-7, mass = 25.0;
  for (int n : {1, 5, 60}) {
    json d = straight_member(L, n, E, G, A, Iy, Iz, J);
    d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
    Model m = read_model(d);
    m.masses.push_back({m.find_node("B"), mass, Mat3::Zero()});
    const ModalResult r = modal(m, 10);
    ASSERT_EQ(r.frequencies.size(), 3) << n << " elements";
    const double fz = std::sqrt(3 * E * Iy / (mass * L * L * L)) / (2 * pi);
    const double fy = std::sqrt(3 * E * Iz / (mass * L * L * L)) / (2 * pi);
    const double fx = std::sqrt(E * A / (mass * L)) / (2 * pi);
    EXPECT_NEAR(r.frequencies[0], fz, 1e-9 * fz);
    EXPECT_NEAR(r.frequencies[1], fy, 1e-9 * fy);
    EXPECT_NEAR(r.frequencies[2], fx, 1e-9 * fx);
    EXPECT_NEAR(r.effective_mass(0, 2), mass, 1e-9 * mass);
    EXPECT_NEAR(r.effective_mass(1, 1), mass, 1e-9 * mass);
    EXPECT_NEAR(r.effective_mass(2, 0), mass, 1e-9 * mass);
    EXPECT_NEAR(r.effective_mass(1, 5), mass * L * L, 1e-9 * mass * L * L);  // about z through the origin
    EXPECT_NEAR(r.total_mass[0], mass, 1e-12 * mass);
    // mass-normalised: phi_tip = 1/sqrt(m)
    EXPECT_NEAR(std::abs(r.modes[0][6 * m.find_node("B") + 2]), 1 / std::sqrt(mass), 1e-9);
  }
}

// A pendulum on a spring: a revolute joint about z at a fixed node, a rigid link of length a and
// a point mass m with rotational inertia Ic about its own centre: omega^2 = k / (m a^2 + Ic_zz),
// exact (the mass reaches the joint coordinate through the joint and the link: the parallel-axis
// theorem is the DofMap's T^T M T). Without the spring the mode is a zero-frequency mechanism.
TEST(Modal, RigidLinkCarriesAPointMassExactly) {
  const double a = 0.7, mass = 3.0, Izz = 0.05, k = 400.0;
  json d;
  d["nodes"] = json::array({{{"id", "O"}, {"xyz", {0, 0, 0}}}, {{"id", "P"}, {"xyz", {0, 0, 0}}},
                            {{"id", "C"}, {"xyz", {a * 0.6, a * 0.8, 0}}}});
  d["elements"] = json::array({{{"id", "link"}, {"type", "rigid"}, {"nodes", {"P", "C"}}}});
  d["joints"] = json::array({{{"id", "q"}, {"type", "revolute"}, {"nodes", {"O", "P"}}, {"axes", {{0, 0, 1}}},
                              {"stiffness", {k}}}});
  d["supports"] = json::array({fix("O", {"ux", "uy", "uz", "rx", "ry", "rz"})});
  Model m = read_model(d);
  Mat3 Ic;
  Ic << 0.02, 0.001, 0.0, 0.001, 0.03, 0.0, 0.0, 0.0, Izz;
  m.masses.push_back({m.find_node("C"), mass, Ic});
  const ModalResult r = modal(m, 1);
  ASSERT_EQ(r.frequencies.size(), 1);
  const double f = std::sqrt(k / (mass * a * a + Izz)) / (2 * pi);
  EXPECT_NEAR(r.frequencies[0], f, 1e-12 * f);
  // a point mass offset by a rigid link from a massless cantilever's tip (bending in x-y):
  // omega^2 = EI / (m (L^3/3 + a L^2 + a^2 L)) from the flexibility at the mass.
  const double L = 1.0, Iz = 1e-7, off = 0.4;
  json c = straight_member(L, 3, E, G, 1e-3, 1e-5, Iz, 1e-5);
  c["nodes"].push_back({{"id", "M"}, {"xyz", {L + off, 0, 0}}});
  c["elements"].push_back({{"id", "r"}, {"type", "rigid"}, {"nodes", {"B", "M"}}});
  c["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  Model mc = read_model(c);
  mc.masses.push_back({mc.find_node("M"), mass, Mat3::Zero()});
  const ModalResult rc = modal(mc, 1);
  const double fc = std::sqrt(E * Iz / (mass * (L * L * L / 3 + off * L * L + off * off * L))) / (2 * pi);
  EXPECT_NEAR(rc.frequencies[0], fc, 1e-9 * fc);
  // no spring: a mechanism, frequency 0
  d["joints"][0].erase("stiffness");
  Model m0 = read_model(d);
  m0.masses.push_back({m0.find_node("C"), mass, Ic});
  const ModalResult r0 = modal(m0, 1);
  ASSERT_EQ(r0.frequencies.size(), 1);
  EXPECT_EQ(r0.frequencies[0], 0.0);
  EXPECT_EQ(r0.kinds[0], ModeKind::Mechanism);
}

// A free-free beam: six rigid-body modes at zero frequency, then beta L = 4.7300 (Blevins 1979,
// Table 8-1: cos(bL) cosh(bL) = 1).
TEST(Modal, FreeFreeBeamHasSixRigidBodyModesThenBetaL4730) {
  const double L = 2.0, A = 1e-3, Iy = 1e-10, Iz = 4e-10, J = 1e-10;
  double b = 4.73;
  for (int it = 0; it < 20; ++it)
    b -= (std::cos(b) * std::cosh(b) - 1) / (-std::sin(b) * std::cosh(b) + std::cos(b) * std::sinh(b));
  json d = straight_member(L, 24, E, G, A, Iy, Iz, J);
  Model m = read_model(d);
  set_density(m, rho);
  const ModalResult r = modal(m, 7);
  ASSERT_EQ(r.frequencies.size(), 7);
  for (int k = 0; k < 6; ++k) {
    EXPECT_EQ(r.frequencies[k], 0.0);
    EXPECT_EQ(r.kinds[k], ModeKind::RigidBody);
  }
  const double exact = b * b * std::sqrt(E * Iy / (rho * A * std::pow(L, 4))) / (2 * pi);
  EXPECT_NEAR(r.frequencies[6], exact, 1e-5 * exact);
  EXPECT_EQ(r.kinds[6], ModeKind::Elastic);
}

// A pinned column under half its Euler load: the first bending frequency drops by
// sqrt(1 - P/P_cr) (Bazant & Cedolin, Stability of Structures, 1991, sec. 3.1; the buckling and
// vibration modes are the same sine). Exact in the continuum; 16 elements: < 1e-4 on the ratio.
TEST(Modal, PinnedColumnAtHalfItsEulerLoadVibratesSlowerBySqrtOneHalf) {
  const double L = 3.0, A = 1e-3, I = 1e-9, J = 2e-9;
  const double Pcr = pi * pi * E * I / (L * L);
  json d = straight_member(L, 16, E, G, A, I, 4 * I, J);
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx"}));
  d["supports"].push_back(fix("B", {"uy", "uz"}));
  d["loads"].push_back(load("B", -0.5 * Pcr, 0, 0));
  Model m = read_model(d);
  set_density(m, rho);
  const ModalResult r0 = modal(m, 1);
  const ModalResult r1 = modal(m, 1, MassKind::Consistent, true);
  const double f0 = pi * pi * std::sqrt(E * I / (rho * A * std::pow(L, 4))) / (2 * pi);
  EXPECT_NEAR(r0.frequencies[0], f0, 1e-5 * f0);
  EXPECT_NEAR(r1.frequencies[0] / r0.frequencies[0], std::sqrt(0.5), 1e-4);
  EXPECT_NEAR(r1.frequencies[0], f0 * std::sqrt(0.5), 1e-4 * f0);
  // beyond buckling (1.2 P_cr) the mode is unstable: a negative omega^2
  Model m2 = m;
  m2.default_case.nodal[0].force.x() = -1.2 * Pcr;
  const ModalResult r2 = modal(m2, 1, MassKind::Consistent, true);
  EXPECT_EQ(r2.kinds[0], ModeKind::Unstable);
  EXPECT_LT(r2.frequencies[0], 0.0);
  EXPECT_NEAR(r2.eigenvalues[0] / (4 * pi * pi * f0 * f0), 1 - 1.2, 1e-3);
}

// A deep simply supported Timoshenko beam (L/h = 5): the exact frequencies solve, for the mode
// sin(n pi x/L) (Timoshenko 1921; Han, Benaroya & Wei 1999, J. Sound Vib. 225, 935-988, eq. 50),
//   (rho A w^2 - G As a^2)(rho I w^2 - E I a^2 - G As) - (G As a)^2 = 0,   a = n pi / L,
// a quadratic in w^2 whose smaller root is the bending frequency. Only w and ry are free (x-z
// plane). The element is exact in statics but its shear strain is constant per element, so the
// frequencies converge as h^2 (not h^4 as Euler-Bernoulli's; Phi = 12 EI/(G As h^2) grows as the
// mesh is refined and the interpolation tends to the linear one of a shear element): the error
// must fall by > 3.5 per halving, be < 1e-5, 1e-4, 3e-4 for modes 1-3 at 80 elements, and the
// Richardson extrapolation (4 f_80 - f_40)/3 must agree to 1e-5, while Euler-Bernoulli is > 4 % off.
TEST(Modal, DeepSimplySupportedTimoshenkoBeamMatchesTheFrequencyEquation) {
  const double L = 1.0, b = 0.1, h = 0.2, A = b * h, Iy = b * h * h * h / 12, kz = 6.0 / 5.0;
  const double GAs = G * A / kz;
  double exact[3];
  for (int n = 1; n <= 3; ++n) {
    const double a = n * pi / L;
    // (rho A x - GAs a^2)(rho I x - EI a^2 - GAs) - (GAs a)^2 = 0, x = w^2
    const double qa = rho * A * rho * Iy;
    const double qb = -(rho * A * (E * Iy * a * a + GAs) + GAs * a * a * rho * Iy);
    const double qc = GAs * a * a * (E * Iy * a * a + GAs) - GAs * GAs * a * a;
    exact[n - 1] = std::sqrt((-qb - std::sqrt(qb * qb - 4 * qa * qc)) / (2 * qa)) / (2 * pi);
  }
  double previous[3] = {1, 1, 1}, f40[3] = {}, f80[3] = {};
  for (int ne : {20, 40, 80}) {
    json d = straight_member(L, ne, E, G, A, Iy, h * b * b * b / 12, 1e-5);
    d["sections"][0]["ky"] = kz;
    d["sections"][0]["kz"] = kz;
    d["supports"].push_back(fix("A", {"uz"}));
    d["supports"].push_back(fix("B", {"uz"}));
    Model m = read_model(d);
    m.sections[0].ky = m.sections[0].kz = kz;
    set_density(m, rho);
    fix_everywhere(m, {0, 1, 3, 5});
    const ModalResult eb = modal(m, 3);
    set_timoshenko(m);
    const ModalResult r = modal(m, 3);
    for (int k = 0; k < 3; ++k) {
      const double err = std::abs(r.frequencies[k] / exact[k] - 1.0);
      std::cout << ne << " elements, Timoshenko SS mode " << k + 1 << ": " << r.frequencies[k] << " Hz, exact "
                << exact[k] << " (error " << err << "), Euler-Bernoulli " << eb.frequencies[k] << "\n";
      EXPECT_LT(3.5 * err, previous[k]) << ne << " elements, mode " << k + 1;
      previous[k] = err;
      (ne == 40 ? f40 : f80)[k] = r.frequencies[k];
      EXPECT_GT(eb.frequencies[k] / exact[k] - 1.0, 0.04);
    }
  }
  EXPECT_LT(previous[0], 1e-5);
  EXPECT_LT(previous[1], 1e-4);
  EXPECT_LT(previous[2], 3e-4);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR((4 * f80[k] - f40[k]) / 3, exact[k], 1e-5 * exact[k]) << "mode " << k + 1;
}

// Linear statics with a Timoshenko cantilever of one element: tip deflection
// P L^3/(3 EI) + P L/(G A/k) exact.
TEST(Modal, TimoshenkoCantileverTipDeflectionIsExactWithOneElementInLinearStatics) {
  const double L = 0.5, b = 0.05, h = 0.1, A = b * h, Iy = b * h * h * h / 12, Iz = h * b * b * b / 12, P = 2e4;
  json d = straight_member(L, 1, E, G, A, Iy, Iz, 1e-6);
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  d["loads"].push_back(load("B", 0, P, P));
  Model m = read_model(d);
  m.sections[0].ky = m.sections[0].kz = 1.2;
  set_timoshenko(m);
  const LinearStaticResult r = solve_linear_static(m);
  ASSERT_EQ(r.status, SolveStatus::Succeeded) << r.message;
  const double vy = P * L * L * L / (3 * E * Iz) + 1.2 * P * L / (G * A);
  const double vz = P * L * L * L / (3 * E * Iy) + 1.2 * P * L / (G * A);
  EXPECT_NEAR(r.u[6 + 1], vy, 1e-10 * vy);
  EXPECT_NEAR(r.u[6 + 2], vz, 1e-10 * vz);
}

}  // namespace modal_test
