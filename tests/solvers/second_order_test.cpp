// Second-order (P-Delta) statics and tension-/compression-only members (solvers/second_order.hpp)
// against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "nl_models.hpp"
#include "solvers/buckling.hpp"
#include "solvers/condensed_stiffness.hpp"
#include "solvers/modal.hpp"
#include "solvers/second_order.hpp"

namespace second_order_test {

using namespace beamfea;
using namespace beamfea::test;

namespace {
constexpr double pi = 3.14159265358979323846;
const double E = 210e9, G = 81e9, A = 1e-3, I = 1e-6, J = 2e-6;
const double L = 3.0;
const double P_cr = pi * pi * E * I / (4 * L * L);  // Euler's cantilever (Timoshenko & Gere 1961, eq. 2.3)

// A cantilever column along x, clamped at A, with the axial compression P and the lateral load H
// (along y) at its tip B, in n elements.
json column(int n, double P, double H) {
  json d = straight_member(L, n, E, G, A, I, I, J);
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  d["loads"].push_back(load("B", -P, H, 0));
  return d;
}

// The tip deflection of that column: H (tan kL - kL) / (k^3 EI), k = sqrt(P / EI) (Timoshenko &
// Gere 1961, sec. 1.7, the beam-column with a lateral end load).
double tip_deflection(double P, double H) {
  const double k = std::sqrt(P / (E * I));
  return H * (std::tan(k * L) - k * L) / (k * k * k * E * I);
}
}  // namespace

// The tip deflection converges to the closed form with the mesh (the Hermite K_g's error shrinks
// at every refinement) and the base moment is H L + P delta, the second-order moment.
TEST(SecondOrder, CantileverColumnTipDeflectionConvergesToTheBeamColumnClosedForm) {
  const double P = 0.5 * P_cr, H = 1000.0;
  const double exact = tip_deflection(P, H);
  double previous = 1.0;
  for (int n : {1, 2, 4, 8, 16}) {
    const Model m = read_model(column(n, P, H));
    const SecondOrderResult r = solve_second_order(m, m.default_loads());
    ASSERT_EQ(r.status, SecondOrderStatus::Converged) << r.message;
    const double tip = r.solution.u[6 + 1];  // node B, uy
    const double err = std::abs(tip / exact - 1.0);
    std::cout << n << " elements: tip " << tip << ", relative error " << err << ", " << r.iterations << " iterations\n";
    EXPECT_LT(err, previous) << n;
    previous = err;
    // One factorisation per solve, all on one symbolic analysis.
    EXPECT_EQ(r.factorizations, r.iterations + 1);
    EXPECT_EQ(r.symbolic_analyses, 1);
    if (n == 16) {
      // The linear tip deflection H L^3 / (3 EI) is exact for any mesh.
      const double linear = H * L * L * L / (3 * E * I);
      EXPECT_NEAR(r.linear.u[6 + 1], linear, 1e-9 * linear);
      EXPECT_NEAR(r.amplification, tip / r.linear.u[6 + 1], 1e-12);
      EXPECT_NEAR(r.solution.reactions[0][5], -(H * L + P * tip), 1e-6 * H * L);
    }
  }
  EXPECT_LT(previous, 1e-5);
}

// At and above Euler's load K + K_g is indefinite: the analysis diverges and names the critical
// load factor P_cr / P; the linear step is kept.
TEST(SecondOrder, ColumnAboveTheCriticalLoadDivergesWithTheCriticalFactor) {
  const double P = 1.25 * P_cr, H = 1000.0;
  const Model m = read_model(column(16, P, H));
  const SecondOrderResult r = solve_second_order(m, m.default_loads());
  ASSERT_EQ(r.status, SecondOrderStatus::Diverged) << r.message;
  EXPECT_NEAR(r.critical_load_factor, P_cr / P, 1e-4);  // the 16-element buckling load's error
  const std::string head = "second-order analysis diverged: load above the critical load factor ";
  ASSERT_EQ(r.message.rfind(head, 0), 0u) << r.message;
  EXPECT_NEAR(std::stod(r.message.substr(head.size())), r.critical_load_factor, 1e-5);
  const double linear = H * L * L * L / (3 * E * I);
  EXPECT_NEAR(r.linear.u[6 + 1], linear, 1e-9 * linear);
}

// The loaded tangent about the second-order equilibrium: the tip's lateral compliance of the
// column under P is (tan kL - kL) / (k^3 EI), the beam-column's (no lateral load needed).
TEST(SecondOrder, StiffnessAboutTheSecondOrderEquilibriumHasTheBeamColumnCompliance) {
  const double P = 0.6 * P_cr;
  const Model m = read_model(column(16, P, 0.0));
  PreloadOptions about;
  about.about = Equilibrium::SecondOrder;
  const CondensedStiffness k = loaded_node_stiffness(m, m.default_loads(), m.find_node("B"), about);
  ASSERT_TRUE(k.ok) << k.message;
  const double exact = tip_deflection(P, 1.0);
  EXPECT_NEAR(k.compliance(1, 1), exact, 1e-5 * exact);
}

// Frequencies about the second-order equilibrium: a pinned column under P vibrates at
// omega_0 sqrt(1 - P / P_cr), P_cr = pi^2 EI / L^2 (its first mode is its buckling mode; Bazant &
// Cedolin, Stability of Structures, sec. 3.1).
TEST(SecondOrder, ModalAboutTheSecondOrderEquilibriumLowersTheFrequencyByTheAxialLoad) {
  const double Lp = 4.0, P_pin = pi * pi * E * I / (Lp * Lp), P = 0.5 * P_pin;
  json d = straight_member(Lp, 16, E, G, A, I, I, J);
  d["materials"][0]["density"] = 7850.0;
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx"}));
  d["supports"].push_back(fix("B", {"uy", "uz"}));
  d["loads"].push_back(load("B", -P, 0, 0));
  const Model m = read_model(d);
  ModalOptions o;
  o.modes = 1;
  const double f0 = solve_modal(m, o).frequencies[0];
  o.preload = true;
  o.about_state.about = Equilibrium::SecondOrder;
  const ModalResult r = solve_modal(m, m.default_loads(), o);
  ASSERT_EQ(r.status, ModalStatus::Succeeded) << r.message;
  EXPECT_NEAR(r.frequencies[0] / f0, std::sqrt(1.0 - P / P_pin), 1e-4);
}

// A rigid link of length L on a rotational spring k, compressed by P and pushed sideways by H:
// k theta = H L + P L theta, so the tip moves H L^2 / (k - P L) (statics of the displaced link),
// the amplification 1 / (1 - P L / k). K_g is the rigid link's constraint curvature alone.
TEST(SecondOrder, RigidLinkOnASpringAmplifiesByOneOverOneMinusPLOverK) {
  const double Lr = 0.5, k = 200.0, P = 150.0, H = 1.0;
  json d = rigid_chain(1, Lr, k);
  d["loads"].push_back(load("N1", -P, H, 0));
  const Model m = read_model(d);
  const SecondOrderResult r = solve_second_order(m, m.default_loads());
  ASSERT_EQ(r.status, SecondOrderStatus::Converged) << r.message;
  const double tip = r.solution.u[6 * m.find_node("N1") + 1];
  EXPECT_NEAR(tip, H * Lr * Lr / (k - P * Lr), 1e-9 * tip);
  EXPECT_NEAR(r.amplification, 1.0 / (1.0 - P * Lr / k), 1e-9);
  // Above P = k / L: diverged, the factor k / (P L).
  d["loads"][0] = load("N1", -2.0 * k / Lr, H, 0);
  const Model over = read_model(d);
  const SecondOrderResult o = solve_second_order(over, over.default_loads());
  ASSERT_EQ(o.status, SecondOrderStatus::Diverged) << o.message;
  EXPECT_NEAR(o.critical_load_factor, 0.5, 1e-9);
}

// A Timoshenko column runs through the same iteration; with shear flexibility its tip moves more
// than the Euler-Bernoulli column's, and the amplification is nearer the Euler-Bernoulli one the
// stiffer the shear (both converge with the mesh).
TEST(SecondOrder, TimoshenkoColumnConvergesAndIsMoreFlexible) {
  const double P = 0.5 * P_cr, H = 1000.0;
  json d = column(16, P, H);
  d["sections"][0]["k"] = 1.2;
  d["sections"][0]["A"] = 1e-4;  // a slender shear area: G As = 6.75e6 N against P_E / P ~ 0.04
  d["elements"][0]["theory"] = "timoshenko";
  const Model m = read_model(d);
  const SecondOrderResult r = solve_second_order(m, m.default_loads());
  ASSERT_EQ(r.status, SecondOrderStatus::Converged) << r.message;
  const Model eb = read_model(column(16, P, H));
  const SecondOrderResult r_eb = solve_second_order(eb, eb.default_loads());
  EXPECT_GT(r.solution.u[7], r_eb.solution.u[7]);
  EXPECT_GT(r.amplification, 1.0);
}

}  // namespace second_order_test
