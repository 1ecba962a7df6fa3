// Linearised buckling with the geometric stiffness of elements/geometric_stiffness.hpp, against
// closed forms. Each problem is a straight member along global x meshed into n equal elements,
// assembled densely here; the critical load factor solves  K phi = lambda (-Kg) phi, computed as
// the largest eigenvalue mu = 1/lambda of the definite pencil (-Kg, K) (K is positive definite
// once supported, -Kg need not be).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <vector>

#include "elements/beam.hpp"
#include "elements/geometric_stiffness.hpp"

namespace beamfea::geometric_stiffness_test {
namespace {

using Eigen::MatrixXd;
using std::numbers::pi;

// Which of a node's six DOFs (ux uy uz rx ry rz) are fixed.
using Fixity = std::array<bool, 6>;

struct Column {
  BeamSection s;
  double L = 0.0;
  int n = 1;
  Fixity first{}, last{};
  // Local end forces of element e for a unit load factor.
  std::function<Vec12(int e)> end_forces;
};

// Smallest positive critical load factor.
double critical_load_factor(const Column& c) {
  const int nn = c.n + 1, ndof = 6 * nn;
  MatrixXd K = MatrixXd::Zero(ndof, ndof), Kg = MatrixXd::Zero(ndof, ndof);
  const double h = c.L / c.n;
  for (int e = 0; e < c.n; ++e) {
    const Vec3 x1(e * h, 0, 0), x2((e + 1) * h, 0, 0);
    const LinearBeam beam(c.s, x1, x2, Vec3(0, 0, 1));
    const Mat12& T = beam.transformation();
    const Mat12 kg = T.transpose() * beam_local_geometric_stiffness(h, c.s.A, c.s.Iy, c.s.Iz, c.end_forces(e)) * T;
    K.block<12, 12>(6 * e, 6 * e) += beam.stiffness();
    Kg.block<12, 12>(6 * e, 6 * e) += kg;
  }
  std::vector<int> free;
  for (int i = 0; i < ndof; ++i) {
    const int node = i / 6, comp = i % 6;
    const bool fixed = (node == 0 && c.first[comp]) || (node == nn - 1 && c.last[comp]);
    if (!fixed) free.push_back(i);
  }
  const int nf = static_cast<int>(free.size());
  MatrixXd Kf(nf, nf), Gf(nf, nf);
  for (int i = 0; i < nf; ++i)
    for (int j = 0; j < nf; ++j) {
      Kf(i, j) = K(free[i], free[j]);
      Gf(i, j) = -Kg(free[i], free[j]);
    }
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> es(Gf, Kf, Eigen::EigenvaluesOnly | Eigen::Ax_lBx);
  EXPECT_EQ(es.info(), Eigen::Success);
  const double mu_max = es.eigenvalues().maxCoeff();
  EXPECT_GT(mu_max, 0.0);
  return 1.0 / mu_max;
}

// Axial compression of unit magnitude: on the element, +1 along x at node 1, -1 at node 2.
Vec12 unit_compression(int) {
  Vec12 f = Vec12::Zero();
  f(0) = 1.0;
  f(6) = -1.0;
  return f;
}

// Weak axis: local z-bending (Iz) is the weak plane; torsional buckling (G J A / Ip) well above.
BeamSection column_section() {
  BeamSection s;
  s.E = 1000.0;
  s.G = 400.0;
  s.A = 1.0;
  s.Iz = 1.0;
  s.Iy = 2.0;
  s.J = 5.0;
  return s;
}

std::vector<double> relative_errors(Column c, double exact, const char* name,
                                    const std::vector<int>& meshes = {1, 2, 4, 8, 16}) {
  std::vector<double> err;
  for (int n : meshes) {
    c.n = n;
    const double Pcr = critical_load_factor(c);
    err.push_back(std::abs(Pcr - exact) / exact);
    std::printf("  %-28s n = %2d  critical = %.8g  exact = %.8g  rel. error = %.3e\n", name, n, Pcr, exact, err.back());
  }
  return err;
}

// Error decreasing with refinement, at the rate of cubic Hermite elements (eigenvalue error
// O(h^4): a factor 16 per halving; we ask for 10), until round-off.
void expect_converges(const std::vector<double>& err, double finest) {
  for (size_t i = 1; i < err.size(); ++i) {
    if (err[i - 1] > 1e-9) {
      EXPECT_LT(err[i], err[i - 1] / 10.0) << "refinement step " << i;
    }
  }
  EXPECT_LT(err.back(), finest);
}

// Euler column, pinned at both ends: P_cr = pi^2 E I / L^2 (Timoshenko & Gere, Theory of Elastic
// Stability, 2nd ed., 1961, Ch. 2: the Euler load with effective length L).
TEST(GeometricStiffness, PinnedPinnedColumnBucklesAtEulerLoad) {
  Column c;
  c.s = column_section();
  c.L = 10.0;
  c.first = {true, true, true, true, false, false};  // also axial and twist, against rigid motion
  c.last = {false, true, true, false, false, false};
  c.end_forces = unit_compression;
  const double exact = pi * pi * c.s.E * c.s.Iz / (c.L * c.L);
  const auto err = relative_errors(c, exact, "pinned-pinned column");
  EXPECT_LT(err[0], 0.25);  // one element: 12 EI/L^2 instead of pi^2 EI/L^2
  expect_converges(err, 5e-6);  // 16 elements: 2.1e-6
}

// Cantilever (fixed-free) column: P_cr = pi^2 E I / (4 L^2) (Timoshenko & Gere, Art. 2.1: effective length 2L).
TEST(GeometricStiffness, CantileverColumnBucklesAtQuarterEulerLoad) {
  Column c;
  c.s = column_section();
  c.L = 10.0;
  c.first = {true, true, true, true, true, true};
  c.last = {false, false, false, false, false, false};
  c.end_forces = unit_compression;
  const double exact = pi * pi * c.s.E * c.s.Iz / (4.0 * c.L * c.L);
  const auto err = relative_errors(c, exact, "cantilever column");
  EXPECT_LT(err[0], 0.01);
  expect_converges(err, 5e-7);  // 16 elements: 1.3e-7
}

// With the torsional mode made critical (small J), a pinned column twists at the Wagner load
// P = G J A / Ip (Timoshenko & Gere, Ch. 5, pure torsional buckling without warping): checks the Ip/A term.
TEST(GeometricStiffness, ColumnWithSmallTorsionConstantBucklesTorsionallyAtWagnerLoad) {
  Column c;
  c.s = column_section();
  c.s.J = 0.01;
  c.L = 10.0;
  c.n = 4;
  c.first = {true, true, true, true, false, false};
  c.last = {false, true, true, true, false, false};
  c.end_forces = unit_compression;
  const double exact = c.s.G * c.s.J * c.s.A / (c.s.Iy + c.s.Iz);
  EXPECT_NEAR(critical_load_factor(c), exact, 1e-9 * exact);
}

// Lateral-torsional buckling of a simply supported beam under uniform moment about its strong
// axis (local z, Iz), fork supports (lateral displacement w, in-plane v and twist rx fixed at
// both ends, warping free): M_cr = (pi / L) sqrt(E Iy G J) (Timoshenko & Gere, Sec. 6.2, the
// narrow rectangular beam in pure bending, i.e. without the warping term).
TEST(GeometricStiffness, SimplySupportedBeamUnderUniformMomentBucklesLaterallyAtTimoshenkoMoment) {
  Column c;
  c.s.E = 1000.0;
  c.s.G = 400.0;
  c.s.A = 1.0;
  c.s.Iy = 1.0;   // weak axis: lateral bending (w, ry)
  c.s.Iz = 10.0;  // strong axis: the applied moment bends in x-y
  c.s.J = 2.0;
  c.L = 10.0;
  c.first = {true, true, true, true, false, false};
  c.last = {false, true, true, true, false, false};
  // Internal moment +1 about local z everywhere: on the element, Mz1 = -1, Mz2 = +1; no shear.
  c.end_forces = [](int) {
    Vec12 f = Vec12::Zero();
    f(5) = -1.0;
    f(11) = 1.0;
    return f;
  };
  const double exact = pi / c.L * std::sqrt(c.s.E * c.s.Iy * c.s.G * c.s.J);
  // One element cannot twist between its forks: start at two.
  const auto err = relative_errors(c, exact, "lateral-torsional buckling", {2, 4, 8, 16, 32});
  // The linear twist interpolation converges at O(h^2): a factor 4 per halving; we ask for 3.5.
  for (size_t i = 1; i < err.size(); ++i) {
    EXPECT_LT(err[i], err[i - 1] / 3.5) << "refinement step " << i;
  }
  EXPECT_LT(err[1], 0.03);      // 4 elements: 2.6e-2
  EXPECT_LT(err.back(), 5e-4);  // 32 elements
}

TEST(GeometricStiffness, IsSymmetricAndLinearInTheEndForces) {
  BeamSection s;
  s.E = 1000.0, s.G = 400.0, s.A = 1.0, s.Iy = 1.0, s.Iz = 10.0, s.J = 2.0;
  Vec12 f = Vec12::Zero();
  f(5) = -3.0, f(11) = 2.0, f(4) = 0.5, f(10) = -0.25, f(0) = 1.0, f(6) = -1.0, f(3) = 0.3, f(9) = -0.3;
  const Mat12 kp = beam_local_geometric_stiffness(2.0, s.A, s.Iy, s.Iz, f);
  const Mat12 kn = beam_local_geometric_stiffness(2.0, s.A, s.Iy, s.Iz, -f);
  EXPECT_NEAR((kp + kn).norm(), 0.0, 1e-12);  // linear in the forces
  EXPECT_NEAR((kp - kp.transpose()).norm(), 0.0, 1e-12);
}

// Rigid-body motions do no work against kg when the end forces are in equilibrium under an
// axial force only: a rigid translation along x and rigid rotation about x are in its null space.
TEST(GeometricStiffness, AxialTranslationAndTwistAreInTheNullSpaceOfTheAxialGeometricStiffness) {
  Vec12 f = Vec12::Zero();
  f(0) = 2.0, f(6) = -2.0;
  const Mat12 kg = beam_local_geometric_stiffness(3.0, 1.0, 1.0, 2.0, f);
  Vec12 ux = Vec12::Zero(), rx = Vec12::Zero(), uy = Vec12::Zero();
  ux(0) = ux(6) = 1.0;
  rx(3) = rx(9) = 1.0;
  uy(1) = uy(7) = 1.0;
  EXPECT_NEAR((kg * ux).norm(), 0.0, 1e-14);
  EXPECT_NEAR((kg * rx).norm(), 0.0, 1e-14);
  EXPECT_NEAR((kg * uy).norm(), 0.0, 1e-14);
}

}  // namespace
}  // namespace beamfea::geometric_stiffness_test
