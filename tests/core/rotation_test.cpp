// Rotation algebra of core/rotation.hpp, with the edge cases near 0 and near pi on their own
// (STYLE.md: "Rotation edge cases near 0 and near pi get tests of their own", as in Ceres'
// rotation_test.cc).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/rotation.hpp"

namespace beamfea::rotation_test {
namespace {

using std::numbers::pi;

const std::vector<Vec3> kAxes = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(), Vec3(1, 1, 1).normalized(),
                                 Vec3(-0.3, 0.8, -0.52).normalized(), Vec3(1e-3, -1.0, 2e-3).normalized()};

bool is_rotation(const Mat3& R, double tol) {
  return (R * R.transpose() - Mat3::Identity()).norm() < tol && std::abs(R.determinant() - 1.0) < tol;
}

// Rodrigues' formula evaluated directly, as the reference for exp (valid away from 0).
Mat3 rodrigues(const Vec3& axis, double angle) {
  const Mat3 K = skew(axis);
  return Mat3::Identity() + std::sin(angle) * K + (1.0 - std::cos(angle)) * K * K;
}

TEST(Rotation, SkewAndAxialAreInverse) {
  const Vec3 v(0.3, -1.2, 2.5), w(-0.7, 0.4, 0.9);
  EXPECT_LT((axial(skew(v)) - v).norm(), 1e-16);
  EXPECT_LT((skew(v) * w - v.cross(w)).norm(), 1e-15);
}

TEST(Rotation, ExpMatchesRodriguesAndIsARotation) {
  for (const Vec3& n : kAxes)
    for (double a : {1e-3, 0.5, 1.0, 2.0, 3.0, pi, 4.0, 2 * pi + 0.3}) {
      const Mat3 R = exp_so3(a * n);
      EXPECT_TRUE(is_rotation(R, 1e-14));
      EXPECT_LT((R - rodrigues(n, a)).norm(), 1e-15 * 8);
      EXPECT_LT((R * n - n).norm(), 1e-15 * 4);  // the axis is fixed
    }
}

TEST(Rotation, LogInvertsExpOnThePrincipalBranch) {
  for (const Vec3& n : kAxes)
    for (double a : {1e-6, 1e-3, 0.3, 1.0, pi / 2 - 1e-12, pi / 2, pi / 2 + 1e-12, 2.0, 3.0, 3.14}) {
      const Vec3 theta = a * n;
      EXPECT_LT((log_so3(exp_so3(theta)) - theta).norm(), 4e-15 * std::max(1.0, a)) << "angle " << a;
    }
}

TEST(Rotation, ExpInvertsLogForAnyRotation) {
  for (const Vec3& n : kAxes)
    for (double a : {0.0, 0.4, 2.5, pi, 4.0, 2 * pi - 0.1, 7.0}) {
      const Mat3 R = exp_so3(a * n);
      const Vec3 theta = log_so3(R);
      EXPECT_LE(theta.norm(), pi + 1e-15);
      EXPECT_LT((exp_so3(theta) - R).norm(), 1e-14) << "angle " << a;
    }
}

TEST(Rotation, ExpAndLogAreExactAtZero) {
  EXPECT_EQ(exp_so3(Vec3::Zero()), Mat3::Identity());
  EXPECT_EQ(log_so3(Mat3::Identity()), Vec3::Zero());
}

// |theta| ~ 1e-9: exp = I + [theta] + O(theta^2) and log returns theta to relative round-off,
// not to absolute round-off (which would be a relative error of 1e-7).
TEST(Rotation, ExpAndLogKeepRelativeAccuracyNearZero) {
  for (const Vec3& n : kAxes)
    for (double a : {1e-12, 1e-9, 3e-8, 1e-6}) {
      const Vec3 theta = a * n;
      const Mat3 R = exp_so3(theta);
      EXPECT_LT((R - Mat3::Identity() - skew(theta)).norm(), a * a);
      EXPECT_LT((log_so3(R) - theta).norm(), 1e-14 * a) << "angle " << a;
    }
}

// pi - 1e-9: sin(angle) is tiny, the axis comes from the symmetric part; the rotation vector
// must still be recovered to ~1e-9 relative (the axis sign from the small skew part).
TEST(Rotation, LogRecoversTheRotationVectorJustBelowPi) {
  for (const Vec3& n : kAxes)
    for (double d : {1e-6, 1e-9, 1e-12}) {
      const Vec3 theta = (pi - d) * n;
      const Vec3 back = log_so3(exp_so3(theta));
      EXPECT_LT((back - theta).norm(), 1e-9) << "pi - " << d;
      EXPECT_GT(back.dot(theta), 0.0);
    }
}

// Exactly pi: theta and -theta are the same rotation; either is a correct logarithm.
TEST(Rotation, LogAtExactlyPiReturnsAHalfTurnAboutTheRightAxis) {
  for (const Vec3& n : kAxes) {
    const Mat3 R = exp_so3(pi * n);
    const Vec3 back = log_so3(R);
    EXPECT_NEAR(back.norm(), pi, 1e-12);
    EXPECT_NEAR(std::abs(back.normalized().dot(n)), 1.0, 1e-14);
    EXPECT_LT((exp_so3(back) - R).norm(), 1e-14);
  }
  // The matrix of a half-turn written directly, with no round-off from exp.
  Mat3 R = -Mat3::Identity();
  R(0, 0) = 1.0;  // pi about x
  EXPECT_LT((log_so3(R).cwiseAbs() - Vec3(pi, 0, 0)).norm(), 1e-15);
}

// Just above pi the principal logarithm flips to the opposite axis: theta - 2 pi n.
TEST(Rotation, LogJustAbovePiFlipsToThePrincipalBranch) {
  for (const Vec3& n : kAxes) {
    const Vec3 back = log_so3(exp_so3((pi + 1e-9) * n));
    EXPECT_LT((back - (-(pi - 1e-9)) * n).norm(), 1e-9);
  }
}

// d/dt exp(theta + t w) exp(theta)^T at t = 0 equals [T(theta) w]x (central differences).
TEST(Rotation, TangentMatchesFiniteDifferencesOfExp) {
  const std::vector<Vec3> ws = {Vec3(1, 0, 0), Vec3(0.2, -0.7, 0.4), Vec3(-0.5, 0.1, 0.9)};
  for (const Vec3& n : kAxes)
    for (double a : {0.0, 1e-9, 1e-5, 3e-5, 0.3, 1.5, 3.0, pi - 1e-9, 4.5}) {
      const Vec3 theta = a * n;
      const Mat3 T = tangent_so3(theta);
      for (const Vec3& w : ws) {
        const double h = 1e-6;
        const Mat3 dR = (exp_so3(theta + h * w) - exp_so3(theta - h * w)) / (2 * h);
        const Mat3 spin = dR * exp_so3(theta).transpose();
        EXPECT_LT((spin + spin.transpose()).norm(), 1e-9);
        EXPECT_LT((axial(spin) - T * w).norm(), 1e-9) << "angle " << a;
      }
    }
}

TEST(Rotation, TangentInverseTimesTangentIsIdentity) {
  for (const Vec3& n : kAxes)
    for (double a : {0.0, 1e-9, 1e-4 - 1e-12, 1e-4 + 1e-12, 1e-5, 0.3, 1.5, 3.0, pi - 1e-9, pi, 5.0}) {
      const Vec3 theta = a * n;
      EXPECT_LT((tangent_so3_inverse(theta) * tangent_so3(theta) - Mat3::Identity()).norm(), 1e-14 * std::max(1.0, a * a))
          << "angle " << a;
    }
}

// The series branches join the closed forms continuously.
TEST(Rotation, SeriesBranchesAreContinuousAtTheirThresholds) {
  const Vec3 n = Vec3(0.3, -0.4, 0.866).normalized();
  for (double a : {1e-6, 1e-5, 1e-4}) {
    const Vec3 below = (a * (1 - 1e-9)) * n, above = (a * (1 + 1e-9)) * n;
    EXPECT_LT((exp_so3(below) - exp_so3(above)).norm(), 1e-15 + 3e-9 * a);
    EXPECT_LT((tangent_so3(below) - tangent_so3(above)).norm(), 1e-15 + 3e-9 * a);
    EXPECT_LT((tangent_so3_inverse(below) - tangent_so3_inverse(above)).norm(), 1e-15 + 3e-9 * a);
  }
}

TEST(Rotation, OrthonormalizeProjectsANearlyOrthonormalMatrixOntoSO3) {
  const Mat3 R = exp_so3(Vec3(0.3, -1.1, 0.7));
  Mat3 E;
  E << 1e-6, -2e-6, 0.5e-6, 3e-6, 1e-6, -1e-6, 0.0, 2e-6, -3e-6;
  const Mat3 Q = orthonormalize(R + E);
  EXPECT_TRUE(is_rotation(Q, 1e-15 * 8));
  EXPECT_LT((Q - R).norm(), 1e-5);
  EXPECT_LT((orthonormalize(R) - R).norm(), 1e-15 * 8);
}

}  // namespace
}  // namespace beamfea::rotation_test
