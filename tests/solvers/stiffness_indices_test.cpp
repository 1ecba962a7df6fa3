// Stiffness indices of a node from its compliance (solvers/stiffness_indices.hpp), against the
// closed forms of compliances built in the test: for C_tt = R diag(c1, c2, c3) R^T the
// eigen-stiffnesses of a force are 1 / c_i along the columns of R, min = 1 / max c_i, max =
// 1 / min c_i, condition = max c_i / min c_i; a direction with zero compliance is blocked (left
// out), a direction along an unbounded one is free (stiffness zero).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "solvers/stiffness_indices.hpp"

namespace stiffness_indices_test {

using beamfea::Mat3;
using beamfea::Mat6;
using beamfea::Vec3;
using beamfea::Vec6;

constexpr double kRel = 1e-12;  // relative tolerance of the closed forms (a few roundings)

Mat6 block_diagonal(const Mat3& Ctt, const Mat3& Crr) {
  Mat6 C = Mat6::Zero();
  C.topLeftCorner<3, 3>() = Ctt;
  C.bottomRightCorner<3, 3>() = Crr;
  return C;
}

// |cos| of the angle between two directions: 1 when parallel (either sign).
double alignment(const Vec3& a, const Vec3& b) { return std::abs(a.normalized().dot(b.normalized())); }

TEST(StiffnessIndices, ADiagonalComplianceGivesTheReciprocalsOfItsExtremesAlongTheAxes) {
  const double c1 = 2e-6, c2 = 5e-5, c3 = 1e-5;   // translational, m/N
  const double r1 = 3e-4, r2 = 1e-4, r3 = 6e-4;   // rotational, rad/(N m)
  const Mat6 C = block_diagonal(Vec3(c1, c2, c3).asDiagonal(), Vec3(r1, r2, r3).asDiagonal());
  const auto ix = beamfea::stiffness_indices(C, {}, 2.0);
  const auto& t = ix.translational;
  ASSERT_TRUE(t.min && t.max && t.condition);
  EXPECT_NEAR(*t.min, 1 / c2, kRel / c2);
  EXPECT_NEAR(*t.max, 1 / c1, kRel / c1);
  EXPECT_NEAR(*t.condition, c2 / c1, kRel * c2 / c1);
  EXPECT_NEAR((t.direction_min - Vec3::UnitY()).norm(), 0.0, 1e-12);  // signed: largest component positive
  EXPECT_NEAR((t.direction_max - Vec3::UnitX()).norm(), 0.0, 1e-12);
  EXPECT_EQ(t.blocked_count, 0);
  EXPECT_EQ(t.free_count, 0);
  const auto& r = ix.rotational;
  ASSERT_TRUE(r.min && r.max && r.condition);
  EXPECT_NEAR(*r.min, 1 / r3, kRel / r3);
  EXPECT_NEAR(*r.max, 1 / r2, kRel / r2);
  EXPECT_NEAR(*r.condition, r3 / r2, kRel * r3 / r2);
  EXPECT_NEAR((r.direction_min - Vec3::UnitZ()).norm(), 0.0, 1e-12);
  EXPECT_NEAR((r.direction_max - Vec3::UnitY()).norm(), 0.0, 1e-12);
}

TEST(StiffnessIndices, ARotatedComplianceHasTheSameValuesAndRotatedDirections) {
  const double c1 = 2e-6, c2 = 5e-5, c3 = 1e-5;
  const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Mat3 Ctt = R * Vec3(c1, c2, c3).asDiagonal() * R.transpose();
  const Mat3 Crr = R * Vec3(4e-4, 1e-4, 2e-4).asDiagonal() * R.transpose();
  const auto ix = beamfea::stiffness_indices(block_diagonal(Ctt, Crr), {}, 1.5);
  const auto& t = ix.translational;
  ASSERT_TRUE(t.min && t.max && t.condition);
  EXPECT_NEAR(*t.min, 1 / c2, 1e-10 / c2);
  EXPECT_NEAR(*t.max, 1 / c1, 1e-10 / c1);
  EXPECT_NEAR(*t.condition, c2 / c1, 1e-10 * c2 / c1);
  // The extreme directions are R's second and first columns.
  EXPECT_NEAR(alignment(t.direction_min, R.col(1)), 1.0, 1e-12);
  EXPECT_NEAR(alignment(t.direction_max, R.col(0)), 1.0, 1e-12);
  EXPECT_NEAR(t.direction_min.norm(), 1.0, 1e-14);
  const auto& r = ix.rotational;
  ASSERT_TRUE(r.min && r.max);
  EXPECT_NEAR(*r.min, 1 / 4e-4, 1e-10 / 4e-4);
  EXPECT_NEAR(*r.max, 1 / 1e-4, 1e-10 / 1e-4);
  EXPECT_NEAR(alignment(r.direction_min, R.col(0)), 1.0, 1e-12);
  EXPECT_NEAR(alignment(r.direction_max, R.col(1)), 1.0, 1e-12);
}

TEST(StiffnessIndices, ASupportedDirectionIsInfinitelyStiffAndLeftOutOfMinMaxAndCondition) {
  // The node held in ux: the compliance's row and column 0 are zero.
  const double c2 = 5e-5, c3 = 1e-5;
  const Mat6 C = block_diagonal(Vec3(0, c2, c3).asDiagonal(), Vec3(3e-4, 1e-4, 6e-4).asDiagonal());
  const auto t = beamfea::stiffness_indices(C, {}, 2.0).translational;
  ASSERT_TRUE(t.min && t.max && t.condition);
  EXPECT_NEAR(*t.min, 1 / c2, kRel / c2);
  EXPECT_NEAR(*t.max, 1 / c3, kRel / c3);  // not infinity: ux is blocked
  EXPECT_NEAR(*t.condition, c2 / c3, kRel * c2 / c3);
  ASSERT_EQ(t.blocked_count, 1);
  EXPECT_NEAR(alignment(t.blocked[0], Vec3::UnitX()), 1.0, 1e-12);
  EXPECT_NEAR(alignment(t.direction_max, Vec3::UnitZ()), 1.0, 1e-12);
}

TEST(StiffnessIndices, ANodeBlockedInEveryDirectionHasNoMinMaxOrCondition) {
  const auto ix = beamfea::stiffness_indices(Mat6::Zero(), {}, 1.0);
  EXPECT_FALSE(ix.translational.min || ix.translational.max || ix.translational.condition);
  EXPECT_FALSE(ix.rotational.min || ix.rotational.max || ix.rotational.condition);
  EXPECT_EQ(ix.translational.blocked_count, 3);
  EXPECT_EQ(ix.rotational.blocked_count, 3);
}

TEST(StiffnessIndices, AMechanismDirectionMakesMinZeroAndTheConditionUnbounded) {
  // The node slides freely along (1, 1, 0) / sqrt 2: unbounded, the compliance (by convention)
  // zero there; across it the compliance c_a in the x-y plane and c3 along z.
  const double ca = 4e-5, c3 = 1e-5;
  const Vec3 n = Vec3(1, 1, 0).normalized(), a = Vec3(1, -1, 0).normalized();
  const Mat3 Ctt = ca * a * a.transpose() + c3 * Vec3::UnitZ() * Vec3::UnitZ().transpose();
  Vec6 free_direction = Vec6::Zero();
  free_direction.head<3>() = n;
  const auto ix = beamfea::stiffness_indices(block_diagonal(Ctt, Mat3::Identity() * 1e-4), {free_direction}, 1.0);
  const auto& t = ix.translational;
  ASSERT_TRUE(t.min && t.max);
  EXPECT_EQ(*t.min, 0.0);
  EXPECT_FALSE(t.condition);
  EXPECT_NEAR(alignment(t.direction_min, n), 1.0, 1e-12);
  EXPECT_NEAR(*t.max, 1 / c3, kRel / c3);
  ASSERT_EQ(t.free_count, 1);
  EXPECT_EQ(t.blocked_count, 0);
  // The rotations are not affected by a free translation.
  ASSERT_TRUE(ix.rotational.condition);
  EXPECT_NEAR(*ix.rotational.condition, 1.0, 1e-12);
}

TEST(StiffnessIndices, StiffnessAlongADirectionIsTheReciprocalOfItsCompliance) {
  const Mat3 R = Eigen::AngleAxisd(-1.1, Vec3(0.3, -1, 0.5).normalized()).toRotationMatrix();
  const Mat3 Ctt = R * Vec3(2e-6, 5e-5, 1e-5).asDiagonal() * R.transpose();
  Mat6 C = block_diagonal(Ctt, Vec3(3e-4, 1e-4, 6e-4).asDiagonal());
  C(0, 5) = C(5, 0) = 2e-5;  // a coupling of force and rotation
  const Vec3 d(1, 2, 2);     // norm 3
  // d^T C_tt d / 9 summed by hand.
  double c = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c += d[i] * Ctt(i, j) * d[j];
  c /= 9.0;
  const auto k = beamfea::stiffness_along(C, {}, 1.0, d);
  ASSERT_TRUE(k);
  EXPECT_NEAR(*k, 1 / c, 1e-12 / c);
  // Along a supported direction: no finite stiffness; along a free one: zero.
  Mat6 held = C;
  held.row(0).setZero();
  held.col(0).setZero();
  EXPECT_FALSE(beamfea::stiffness_along(held, {}, 1.0, Vec3::UnitX()));
  Vec6 n = Vec6::Zero();
  n[1] = 1.0;
  EXPECT_EQ(beamfea::stiffness_along(C, {n}, 1.0, Vec3(0, 1, 1)).value_or(-1.0), 0.0);
}

TEST(StiffnessIndices, DeflectionIsTheComplianceTimesTheWrenchUnlessTheWrenchDrivesAFreeDirection) {
  Mat6 C;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) C(i, j) = 1e-5 / (1.0 + i + j);  // a Hilbert matrix: symmetric positive
  const Vec6 w(100, -50, 20, 3, -4, 5);
  Vec6 expected = Vec6::Zero();
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) expected[i] += C(i, j) * w[j];
  const auto u = beamfea::deflection_under(C, {}, 2.0, w);
  ASSERT_TRUE(u);
  EXPECT_NEAR((*u - expected).norm(), 0.0, 1e-14 * expected.norm());
  // A free rotation about z (scaled metric: a unit vector), driven by the moment mz = 5.
  Vec6 n = Vec6::Zero();
  n[5] = 1.0;
  EXPECT_FALSE(beamfea::deflection_under(C, {n}, 2.0, w));
  Vec6 no_mz = w;
  no_mz[5] = 0.0;
  EXPECT_TRUE(beamfea::deflection_under(C, {n}, 2.0, no_mz));
}

TEST(StiffnessIndices, TheComplianceAxesAreTheEigenvaluesDescendingAlongTheRotatedAxes) {
  const Mat3 R = Eigen::AngleAxisd(0.4, Vec3(-2, 1, 0.5).normalized()).toRotationMatrix();
  const Mat3 C = R * Vec3(3e-6, 7e-5, 1e-5).asDiagonal() * R.transpose();
  const auto axes = beamfea::compliance_axes(C);
  EXPECT_NEAR(axes.semi_axes[0], 7e-5, 1e-12 * 7e-5);
  EXPECT_NEAR(axes.semi_axes[1], 1e-5, 1e-11 * 1e-5);
  EXPECT_NEAR(axes.semi_axes[2], 3e-6, 1e-10 * 3e-6);
  EXPECT_NEAR(alignment(axes.axes.col(0), R.col(1)), 1.0, 1e-12);
  EXPECT_NEAR(alignment(axes.axes.col(1), R.col(2)), 1.0, 1e-12);
  EXPECT_NEAR(alignment(axes.axes.col(2), R.col(0)), 1.0, 1e-12);
  // A blocked direction: a zero semi-axis (never a negative one from rounding).
  const auto flat = beamfea::compliance_axes(Vec3(0, 2e-6, 1e-6).asDiagonal());
  EXPECT_EQ(flat.semi_axes[2], 0.0);
}

}  // namespace stiffness_indices_test
