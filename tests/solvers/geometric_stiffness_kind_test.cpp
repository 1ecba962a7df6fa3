// "full" and "axial" geometric stiffness (elements/frame_element.hpp, GeometricStiffness) in the
// buckling analysis: the same where no end moment acts, different where one does, each against
// its closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "elements/beam.hpp"
#include "elements/geometric_stiffness.hpp"
#include "nl_models.hpp"
#include "solvers/buckling.hpp"

namespace geometric_stiffness_kind_test {

using namespace beamfea;
using namespace beamfea::test;

namespace {
constexpr double pi = 3.14159265358979323846;
const double E = 210e9, G = 81e9;

double first_factor(const Model& m, GeometricStiffness kind) {
  BucklingOptions o;
  o.modes = 1;
  o.geometric_stiffness = kind;
  const BucklingResult r = solve_buckling(m, o);
  EXPECT_EQ(r.status, BucklingStatus::Succeeded) << r.message;
  return r.load_factors.size() ? r.load_factors[0] : NAN;
}
}  // namespace

// A pinned column under an axial load alone has no end moments: both matrices are the same, and
// both give Euler's pi^2 EI / L^2 (Timoshenko & Gere 1961, eq. 2.5).
TEST(GeometricStiffnessKind, PinnedColumnBucklesAtEulersLoadWithEither) {
  const double L = 4.0, P = 1000.0, A = 1e-3, I = 1e-6;
  json d = straight_member(L, 16, E, G, A, I, I, 2e-6);
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx"}));
  d["supports"].push_back(fix("B", {"uy", "uz"}));
  d["loads"].push_back(load("B", -P, 0, 0));
  const Model m = read_model(d);
  const double full = first_factor(m, GeometricStiffness::Full), axial = first_factor(m, GeometricStiffness::Axial);
  EXPECT_NEAR(axial / full, 1.0, 1e-12);
  EXPECT_NEAR(full * P / (pi * pi * E * I / (L * L)), 1.0, 1e-5);
}

// A fork-supported beam-column under the axial force P and equal end moments M about its strong
// axis, both scaled by lambda. The full matrix couples the moment with the twist: flexural-torsional
// buckling at (P_y - lambda P)(P_phi - lambda P) r0^2 = (lambda M)^2, P_y = pi^2 E Iy / L^2,
// P_phi = G J / r0^2, r0^2 = (Iy + Iz) / A (Timoshenko & Gere 1961, sec. 6.5, no warping). The
// axial matrix has no moment terms: the weak-axis Euler load alone, lambda = P_y / P.
TEST(GeometricStiffnessKind, EndMomentsLowerTheFullFactorOnlyEachMatchingItsClosedForm) {
  const double L = 6.0, A = 1e-2, Iy = 2e-6, Iz = 8e-5, Jt = 1e-7, P = 5e4, M = 2e4;
  json d = straight_member(L, 32, E, G, A, Iy, Iz, Jt);
  d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx"}));
  d["supports"].push_back(fix("B", {"uy", "uz", "rx"}));
  d["loads"].push_back(load("A", 0, 0, 0, 0, 0, -M));
  d["loads"].push_back(load("B", -P, 0, 0, 0, 0, M));
  const Model m = read_model(d);
  const double Py = pi * pi * E * Iy / (L * L), r02 = (Iy + Iz) / A, Pphi = G * Jt / r02;
  // (P^2 r0^2 - M^2) lambda^2 - P (Py + Pphi) r0^2 lambda + Py Pphi r0^2 = 0: the smaller root.
  const double a = P * P * r02 - M * M, b = -P * (Py + Pphi) * r02, c = Py * Pphi * r02;
  const double lambda_full = (-b - std::sqrt(b * b - 4 * a * c)) / (2 * a);
  const double full = first_factor(m, GeometricStiffness::Full), axial = first_factor(m, GeometricStiffness::Axial);
  std::cout << "full " << full << " (closed form " << lambda_full << "), axial " << axial << " (" << Py / P << ")\n";
  EXPECT_NEAR(full / lambda_full, 1.0, 2e-3);
  EXPECT_NEAR(axial / (Py / P), 1.0, 1e-5);
  EXPECT_LT(full, 0.9 * axial);
}

// A stubby Timoshenko column: the axial matrix with the shear-deformable coefficients converges to
// Engesser's load P_E / (1 + k P_E / (G A)) (Timoshenko & Gere 1961, eq. 2.44); the full matrix,
// with its Euler-Bernoulli coefficients, to a load about 4e-5 below it (second order in the shear
// parameter).
TEST(GeometricStiffnessKind, AxialMatrixOfATimoshenkoColumnConvergesToEngessersLoad) {
  const double L = 1.0, P = 1000.0, A = 4e-3, I = 2e-6, k = 1.2;
  const double PE = pi * pi * E * I / (L * L), engesser = PE / (1.0 + k * PE / (G * A));
  double previous = 1.0, full_error = 0.0;
  for (int n : {8, 16, 32, 64}) {
    json d = straight_member(L, n, E, G, A, I, I, 2e-6);
    d["sections"][0]["k"] = k;
    d["elements"][0]["theory"] = "timoshenko";
    d["supports"].push_back(fix("A", {"ux", "uy", "uz", "rx"}));
    d["supports"].push_back(fix("B", {"uy", "uz"}));
    d["loads"].push_back(load("B", -P, 0, 0));
    const Model m = read_model(d);
    const double err = std::abs(first_factor(m, GeometricStiffness::Axial) * P / engesser - 1.0);
    full_error = std::abs(first_factor(m, GeometricStiffness::Full) * P / engesser - 1.0);
    std::cout << n << " elements: axial error " << err << ", full error " << full_error << "\n";
    EXPECT_LT(err, previous) << n;
    previous = err;
  }
  EXPECT_LT(previous, 5e-6);
  EXPECT_GT(full_error, 3e-5);
}

// Under a rigid rotation theta about z the axial matrix gives only the force pair N theta of the
// turned axial force (no end moments), with or without shear deformation.
TEST(GeometricStiffnessKind, AxialMatrixTurnsTheAxialForceUnderARigidRotation) {
  const double L = 0.7, N = -350.0, theta = 1e-3;
  for (double As : {0.0, 1e-4}) {
    BeamSection s{E, G, 1e-3, 2e-7, 3e-7, 1e-7, As, As};
    Vec12 f = Vec12::Zero();
    f[0] = -N;
    f[6] = N;
    Vec12 d = Vec12::Zero();
    d[5] = d[11] = theta;
    d[7] = theta * L;
    const Vec12 r = beam_local_axial_geometric_stiffness(s, L, f) * d;
    Vec12 expect = Vec12::Zero();
    expect[1] = -N * theta;
    expect[7] = N * theta;
    EXPECT_LE((r - expect).cwiseAbs().maxCoeff(), 1e-12 * std::abs(N * theta)) << "As " << As;
  }
}

}  // namespace geometric_stiffness_kind_test
