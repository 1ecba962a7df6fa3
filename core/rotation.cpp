#include "core/rotation.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace beamfea {

Mat3 skew(const Vec3& v) {
  Mat3 S;
  S << 0.0, -v.z(), v.y(),
       v.z(), 0.0, -v.x(),
       -v.y(), v.x(), 0.0;
  return S;
}

Vec3 axial(const Mat3& M) {
  return 0.5 * Vec3(M(2, 1) - M(1, 2), M(0, 2) - M(2, 0), M(1, 0) - M(0, 1));
}

Mat3 exp_so3(const Vec3& theta) {
  const double a2 = theta.squaredNorm();
  const Mat3 S = skew(theta);
  double c1, c2;  // sin(a)/a, (1-cos a)/a^2
  if (a2 < 1e-12) {
    c1 = 1.0 - a2 / 6.0;
    c2 = 0.5 - a2 / 24.0;
  } else {
    const double a = std::sqrt(a2);
    c1 = std::sin(a) / a;
    c2 = (1.0 - std::cos(a)) / a2;
  }
  return Mat3::Identity() + c1 * S + c2 * S * S;
}

Vec3 log_so3(const Mat3& R) {
  const double cos_a = std::clamp(0.5 * (R.trace() - 1.0), -1.0, 1.0);
  const Vec3 w = axial(R);  // = sin(a) * axis
  const double sin_a = w.norm();
  if (cos_a > 0.0) {
    // Away from pi: atan2 is accurate; near 0 use a/sin(a) ~ 1 + a^2/6.
    const double a = std::atan2(sin_a, cos_a);
    const double f = sin_a < 1e-8 ? 1.0 + a * a / 6.0 : a / sin_a;
    return f * w;
  }
  // Near pi: sin(a) is small and inaccurate; recover the axis from the symmetric part,
  // R + R^T - 2 cos(a) I = 2 (1 - cos a) n n^T, then fix the sign with w.
  const double a = std::atan2(sin_a, cos_a);
  const Mat3 B = 0.5 * (R + R.transpose()) - cos_a * Mat3::Identity();  // (1-cos a) n n^T
  int k = 0;
  B.diagonal().maxCoeff(&k);
  Vec3 n = B.col(k) / std::sqrt(std::max(B(k, k), 1e-300));
  n.normalize();
  if (n.dot(w) < 0.0) n = -n;
  return a * n;
}

Mat3 tangent_so3(const Vec3& theta) {
  const double a2 = theta.squaredNorm();
  const Mat3 S = skew(theta);
  double c1, c2;  // (1-cos a)/a^2, (a - sin a)/a^3
  if (a2 < 1e-10) {
    c1 = 0.5 - a2 / 24.0;
    c2 = 1.0 / 6.0 - a2 / 120.0;
  } else {
    const double a = std::sqrt(a2);
    // 1 - cos a = 2 sin^2(a/2): the direct form loses ~eps/a^2 relative accuracy in c1, an
    // absolute error ~eps/a in T for small a (4e-11 at a = 1e-5).
    const double s = std::sin(0.5 * a);
    c1 = 2.0 * s * s / a2;
    c2 = (a - std::sin(a)) / (a2 * a);
  }
  return Mat3::Identity() + c1 * S + c2 * S * S;
}

Mat3 tangent_so3_inverse(const Vec3& theta) {
  const double a2 = theta.squaredNorm();
  const Mat3 S = skew(theta);
  double c;  // (1 - (a/2) cot(a/2)) / a^2
  if (a2 < 1e-8) {
    c = 1.0 / 12.0 + a2 / 720.0;
  } else {
    const double a = std::sqrt(a2);
    c = (1.0 - 0.5 * a / std::tan(0.5 * a)) / a2;
  }
  return Mat3::Identity() - 0.5 * S + c * S * S;
}

Mat3 orthonormalize(const Mat3& R) {
  Eigen::JacobiSVD<Mat3> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 Q = svd.matrixU() * svd.matrixV().transpose();
  if (Q.determinant() < 0.0) {
    Mat3 U = svd.matrixU();
    U.col(2) *= -1.0;
    Q = U * svd.matrixV().transpose();
  }
  return Q;
}

}  // namespace beamfea
