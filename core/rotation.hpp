#pragma once
// Rotation algebra on SO(3): the one place in beamfea where it lives.
//
// Conventions: a rotation vector (pseudo-vector) theta = angle * axis, right-handed.
// exp(theta) = I + sin|t|/|t| [t] + (1-cos|t|)/|t|^2 [t]^2   (Rodrigues)
// log(R) inverts exp on |theta| <= pi, with dedicated branches near 0 and near pi.
// tangent(theta) = T_s(theta), the map with  d exp(theta) = [T_s(theta) dtheta] exp(theta)
// i.e. a change dtheta of the rotation vector produces the *spatial* spin T_s dtheta.
// Reference: J.C. Simo, L. Vu-Quoc (1986), Comput. Meth. Appl. Mech. Eng. 58, eqs. (2.13)-(2.17);
// near-zero expansions as in Ceres' rotation.h.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace beamfea {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// [v]x: the skew-symmetric matrix with [v]x w = v x w.
Mat3 skew(const Vec3& v);
// The axial vector of the skew part of M: axial(skew(v)) = v.
Vec3 axial(const Mat3& M);

Mat3 exp_so3(const Vec3& theta);
// Principal logarithm: |result| <= pi. Robust near 0 and near pi.
Vec3 log_so3(const Mat3& R);

// Spatial tangent: d/dt exp(theta + t*w) exp(theta)^T = [T(theta) w]x.
// T(theta) = I + (1-cos a)/a^2 [t] + (a - sin a)/a^3 [t]^2, a = |theta|.
Mat3 tangent_so3(const Vec3& theta);
// Inverse of tangent_so3 (singular at |theta| = 2*pi; fine on the principal branch).
Mat3 tangent_so3_inverse(const Vec3& theta);

// A proper orthonormal frame from a nearly orthonormal matrix (polar decomposition).
Mat3 orthonormalize(const Mat3& R);

}  // namespace beamfea
