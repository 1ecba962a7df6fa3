// Mass matrices (elements/beam_mass.hpp) and the Timoshenko stiffness (elements/beam.hpp).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>

#include "elements/beam_mass.hpp"

namespace beam_mass_test {

using namespace beamfea;

namespace {
using Mat4 = Eigen::Matrix<double, 4, 4>;
constexpr double kTight = 1e-12;  // round-off level, relative

BeamSection section(double Asy = 0.0, double Asz = 0.0) {
  BeamSection s;
  s.E = 210e9;
  s.G = 80e9;
  s.A = 6e-3;
  s.Iy = 2e-5;
  s.Iz = 5e-6;
  s.J = 8e-6;
  s.Asy = Asy;
  s.Asz = Asz;
  return s;
}

Mat4 planar(const Mat12& M, const std::array<int, 4>& d, const std::array<double, 4>& sg) {
  Mat4 m;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) m(a, b) = sg[a] * sg[b] * M(d[a], d[b]);
  return m;
}

double rel(const Mat4& a, const Mat4& b) { return (a - b).norm() / b.norm(); }
}  // namespace

// Phi = 0: the classical consistent matrix rho A L/420 [156 22L 54 -13L; ...] plus the rotary
// inertia rho I/(30L) [36 3L -36 3L; ...] (Przemieniecki, Theory of Matrix Structural Analysis,
// 1968, eqs. 11.18 and 11.41), in both bending planes (x-z with theta = -ry), and the axial and
// torsional matrices rho A L/6 [2 1; 1 2], rho (Iy + Iz) L/6 [2 1; 1 2].
TEST(BeamMass, EulerBernoulliConsistentMatrixIsTheClassicalOne) {
  const double rho = 7850, L = 1.7;
  const BeamSection s = section();
  const Mat12 M = beam_local_mass(s, rho, L, MassKind::Consistent);
  auto classical = [&](double I) {
    Mat4 t, r;
    t << 156, 22 * L, 54, -13 * L, 22 * L, 4 * L * L, 13 * L, -3 * L * L, 54, 13 * L, 156, -22 * L, -13 * L,
        -3 * L * L, -22 * L, 4 * L * L;
    r << 36, 3 * L, -36, 3 * L, 3 * L, 4 * L * L, -3 * L, -L * L, -36, -3 * L, 36, -3 * L, 3 * L, -L * L, -3 * L,
        4 * L * L;
    return Mat4(rho * s.A * L / 420.0 * t + rho * I / (30.0 * L) * r);
  };
  EXPECT_LT(rel(planar(M, {1, 5, 7, 11}, {1, 1, 1, 1}), classical(s.Iz)), kTight);
  EXPECT_LT(rel(planar(M, {2, 4, 8, 10}, {1, -1, 1, -1}), classical(s.Iy)), kTight);
  EXPECT_NEAR(M(0, 0), rho * s.A * L / 3, kTight * M(0, 0));
  EXPECT_NEAR(M(0, 6), rho * s.A * L / 6, kTight * M(0, 0));
  EXPECT_NEAR(M(3, 3), rho * (s.Iy + s.Iz) * L / 3, kTight * M(3, 3));
  EXPECT_NEAR(M(3, 9), rho * (s.Iy + s.Iz) * L / 6, kTight * M(3, 3));
  // no coupling between the planes, axial and torsion
  EXPECT_EQ(M(1, 2), 0.0);
  EXPECT_EQ(M(0, 1), 0.0);
  EXPECT_EQ(M(3, 4), 0.0);
}

// Rigid-body motions carry the element's exact mass and inertia, whatever Phi or lumping:
// a unit translation rho A L; a unit rotation about the axis rho (Iy + Iz) L.
TEST(BeamMass, RigidMotionsCarryTheExactMassAndAxialInertia) {
  const double rho = 2700, L = 0.6;
  for (MassKind kind : {MassKind::Consistent, MassKind::Lumped})
    for (const BeamSection& s : {section(), section(5e-3, 4e-3)}) {
      const Mat12 M = beam_local_mass(s, rho, L, kind);
      for (int d = 0; d < 3; ++d) {
        Vec12 r = Vec12::Zero();
        r(d) = r(6 + d) = 1.0;
        EXPECT_NEAR(r.dot(M * r), rho * s.A * L, 1e-12 * rho * s.A * L);
      }
      Vec12 t = Vec12::Zero();
      t(3) = t(9) = 1.0;
      EXPECT_NEAR(t.dot(M * t), rho * (s.Iy + s.Iz) * L, 1e-12 * rho * (s.Iy + s.Iz) * L);
      EXPECT_LT((M - M.transpose()).norm(), kTight * M.norm());
      Eigen::SelfAdjointEigenSolver<Mat12> es(M);
      EXPECT_GT(es.eigenvalues().minCoeff(), 0.0);
    }
}

// The interdependent interpolation (Reddy 1997 eq. 31) is the exact static solution of the
// Timoshenko beam: the energy int EI theta'^2 + G As (v' - theta)^2 dx of its shape functions
// must give Przemieniecki's closed-form matrix (eq. 5.116), i.e. beam_local_stiffness, in both
// planes. This ties the mass matrix's shape functions to the element's stiffness.
TEST(BeamMass, TimoshenkoShapeFunctionsReproduceTheClosedFormStiffness) {
  const double L = 0.4;
  const BeamSection s = section(5e-3, 4e-3);
  const Mat12 k = beam_local_stiffness(s, L);
  struct Plane {
    double EI, GAs, phi;
    std::array<int, 4> dofs;
    std::array<double, 4> sign;
  };
  const Plane planes[] = {{s.E * s.Iz, s.G * s.Asy, s.phi_y(L), {1, 5, 7, 11}, {1, 1, 1, 1}},
                          {s.E * s.Iy, s.G * s.Asz, s.phi_z(L), {2, 4, 8, 10}, {1, -1, 1, -1}}};
  for (const Plane& p : planes) {
    EXPECT_GT(p.phi, 0.1);  // a deep member: shear matters
    // 4-point Gauss on [0, 1]; the integrands are of degree <= 4
    const double a = std::sqrt(3.0 / 7.0 - 2.0 / 7.0 * std::sqrt(6.0 / 5.0));
    const double b = std::sqrt(3.0 / 7.0 + 2.0 / 7.0 * std::sqrt(6.0 / 5.0));
    const double wa = (18.0 + std::sqrt(30.0)) / 36.0, wb = (18.0 - std::sqrt(30.0)) / 36.0;
    const double pts[] = {-b, -a, a, b}, wts[] = {wb, wa, wa, wb};
    Mat4 kq = Mat4::Zero();
    for (int g = 0; g < 4; ++g) {
      const PlanarShape sh = timoshenko_shape(0.5 * (1 + pts[g]), L, p.phi);
      const Eigen::Matrix<double, 1, 4> gamma = sh.dv - sh.theta;
      kq += 0.5 * wts[g] * L * (p.EI * sh.dtheta.transpose() * sh.dtheta + p.GAs * gamma.transpose() * gamma);
    }
    EXPECT_LT(rel(kq, planar(k, p.dofs, p.sign)), 1e-11);
    // and the shear strain is constant along the element (no span load)
    const PlanarShape s0 = timoshenko_shape(0.1, L, p.phi), s1 = timoshenko_shape(0.8, L, p.phi);
    EXPECT_LT(((s0.dv - s0.theta) - (s1.dv - s1.theta)).norm(), 1e-12 * (s0.dv - s0.theta).norm() / L + 1e-12);
  }
}

// One Timoshenko element is an exact cantilever: tip deflection P L^3/(3 EI) + P L/(G As)
// (Timoshenko & Gere, Mechanics of Materials; the shear term with As = A/k). The tip block of
// the element matrix is the cantilever's tip stiffness.
TEST(BeamMass, OneTimoshenkoElementGivesTheExactCantileverTipDeflection) {
  const double L = 0.3, P = 1000.0;
  const BeamSection s = section(5e-3, 4e-3);
  const Mat6 Kt = beam_local_stiffness(s, L).bottomRightCorner<6, 6>();
  Vec6 f = Vec6::Zero();
  f(1) = P;  // along y: bending about z (Iz), shear area Asy
  f(2) = P;  // along z: Iy, Asz
  const Vec6 u = Kt.ldlt().solve(f);
  const double vy = P * L * L * L / (3 * s.E * s.Iz) + P * L / (s.G * s.Asy);
  const double vz = P * L * L * L / (3 * s.E * s.Iy) + P * L / (s.G * s.Asz);
  EXPECT_NEAR(u(1), vy, 1e-12 * vy);
  EXPECT_NEAR(u(2), vz, 1e-12 * vz);
  // the Euler-Bernoulli element misses the shear part, which is large here
  BeamSection eb = s;
  eb.Asy = eb.Asz = 0.0;
  const Vec6 ue = Mat6(beam_local_stiffness(eb, L).bottomRightCorner<6, 6>()).ldlt().solve(f);
  EXPECT_GT(std::abs(ue(1) / vy - 1.0), 0.05);
}

// Phi -> 0 recovers the Euler-Bernoulli matrices continuously; a large Phi changes the mass.
TEST(BeamMass, TimoshenkoMassTendsToEulerBernoulliAsShearStiffnessGrows) {
  const double rho = 7850, L = 1.0;
  const Mat12 eb = beam_local_mass(section(), rho, L, MassKind::Consistent);
  const Mat12 stiff = beam_local_mass(section(1e6, 1e6), rho, L, MassKind::Consistent);
  const Mat12 soft = beam_local_mass(section(1e-5, 1e-5), rho, L, MassKind::Consistent);
  EXPECT_LT((stiff - eb).norm(), 1e-8 * eb.norm());
  EXPECT_GT((soft - eb).norm(), 1e-2 * eb.norm());
}

// Lumped: diagonal, half of everything at each node.
TEST(BeamMass, LumpedMatrixIsDiagonalWithHalvesAtEachNode) {
  const double rho = 1000, L = 2.0;
  const BeamSection s = section();
  const Mat12 M = beam_local_mass(s, rho, L, MassKind::Lumped);
  EXPECT_EQ((M - Mat12(M.diagonal().asDiagonal())).norm(), 0.0);
  EXPECT_DOUBLE_EQ(M(1, 1), 0.5 * rho * s.A * L);
  EXPECT_DOUBLE_EQ(M(5, 5), 0.5 * rho * s.Iz * L);
  EXPECT_DOUBLE_EQ(M(10, 10), 0.5 * rho * s.Iy * L);
}

}  // namespace beam_mass_test
