// The element contract on the linear beam: symmetry, zero force under rigid-body motion,
// six zero eigenvalues when unsupported.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "elements/beam.hpp"

namespace beam_contract_test {

using namespace beamfea;

namespace {
LinearBeam skew_beam() {
  return LinearBeam({2.1e11, 8.1e10, 1e-3, 2e-6, 3e-6, 1e-6}, Vec3(0.1, -0.2, 0.3), Vec3(1.3, 0.7, -0.4), Vec3(0.2, 1, 0.5));
}
Vec12 rigid_motion(const Vec3& t, const Vec3& w, const Vec3& x1, const Vec3& x2) {
  Vec12 u;
  u << t + w.cross(x1), w, t + w.cross(x2), w;
  return u;
}
}  // namespace

TEST(LinearBeam, StiffnessIsSymmetric) {
  const auto b = skew_beam();
  EXPECT_LT((b.stiffness() - b.stiffness().transpose()).cwiseAbs().maxCoeff(), 1e-9 * b.stiffness().cwiseAbs().maxCoeff());
}

TEST(LinearBeam, RigidBodyMotionGivesNoForceAndNoEnergy) {
  const auto b = skew_beam();
  const Vec12 u = rigid_motion(Vec3(0.3, -0.1, 0.2), Vec3(0.01, 0.02, -0.03), Vec3(0.1, -0.2, 0.3), Vec3(1.3, 0.7, -0.4));
  EXPECT_LT(b.internal_force(u).norm(), 1e-9 * b.stiffness().norm() * u.norm());
  EXPECT_NEAR(b.strain_energy(u), 0.0, 1e-9);
}

TEST(LinearBeam, UnsupportedElementHasExactlySixZeroEigenvalues) {
  const auto b = skew_beam();
  Eigen::SelfAdjointEigenSolver<Mat12> es(b.stiffness());
  const double top = es.eigenvalues().maxCoeff();
  int zeros = 0;
  for (int i = 0; i < 12; ++i) zeros += std::abs(es.eigenvalues()[i]) < 1e-10 * top ? 1 : 0;
  EXPECT_EQ(zeros, 6);
  EXPECT_GT(es.eigenvalues()[6], 1e-12 * top);
}

TEST(LinearBeam, LocalAxesFollowTheOrientationVectorConvention) {
  // x along the member, y = orientation x x, z = x x y (OpenSees vecxz).
  const Mat3 R = beam_local_axes(Vec3(0, 0, 0), Vec3(0, 0, 2), Vec3(1, 0, 0));
  EXPECT_TRUE(R.row(0).isApprox(Eigen::RowVector3d(0, 0, 1)));
  EXPECT_TRUE(R.row(1).isApprox(Eigen::RowVector3d(0, -1, 0)));  // (1,0,0) x (0,0,1)
  EXPECT_TRUE(R.row(2).isApprox(Eigen::RowVector3d(1, 0, 0)));   // = the orientation vector
}

TEST(LinearBeam, CubicShapeReproducesTheCantileverDeflectionCurve) {
  // Tip load P: v(x) = P x^2 (3L - x) / 6EI (Timoshenko & Gere, App. G case 1).
  const double L = 2, E = 2e11, I = 3e-6, P = 1e3;
  const Mat3 R = Mat3::Identity();
  Vec12 u = Vec12::Zero();
  u[7] = P * L * L * L / (3 * E * I);
  u[11] = P * L * L / (2 * E * I);
  for (double xi : {0.25, 0.5, 0.8}) {
    const double x = xi * L;
    EXPECT_NEAR(beam_displacement_at(R, L, u, xi).y(), P * x * x * (3 * L - x) / (6 * E * I), 1e-12);
  }
}

}  // namespace beam_contract_test
