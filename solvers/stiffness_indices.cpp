#include "solvers/stiffness_indices.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "core/errors.hpp"

namespace beamfea {

namespace {

// A block compressed onto the directions that are not free: at most 3 x 3, on the stack (a sweep
// case computes the indices without allocating).
using Block3 = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3>;

// The largest eigenvalue of the length-scaled compliance S C S (S = diag(1,1,1,L,L,L)): the
// reference of the blocked test.
double scaled_reference(const Mat6& C, double L) {
  Vec6 s;
  s << 1, 1, 1, L, L, L;
  const Mat6 Cs = s.asDiagonal() * C * s.asDiagonal();
  return Eigen::SelfAdjointEigenSolver<Mat6>(Cs, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
}

// `v` with its largest component positive (eigenvectors have no sign of their own).
Vec3 signed_direction(const Vec3& v) {
  Eigen::Index i = 0;
  v.cwiseAbs().maxCoeff(&i);
  return v[i] < 0.0 ? Vec3(-v) : v;
}

// The parts (`first`: 0 translational, 3 rotational) of the unbounded directions, as the free
// directions of the block (orthonormal, in `out`) and the eigenvectors of the parts' Gram matrix,
// ascending: the first 3 - free_count span the directions that are not free.
Mat3 split_free(const std::vector<Vec6>& unbounded, int first, double tolerance, BlockIndices& out) {
  Mat3 gram = Mat3::Zero();
  for (const Vec6& n : unbounded) {
    const Vec3 p = n.segment<3>(first);
    gram += p * p.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> es(gram);
  out.free_count = 0;
  for (int i = 2; i >= 0; --i)
    if (es.eigenvalues()[i] > tolerance * tolerance) out.free[out.free_count++] = signed_direction(es.eigenvectors().col(i));
  return es.eigenvectors();
}

// The indices of one block C (3x3, unscaled) whose scaled compliance is `factor` * C (1 for forces,
// L^2 for moments), given the largest scaled compliance `reference`.
BlockIndices block_indices(const Mat3& C, double factor, double reference, const std::vector<Vec6>& unbounded,
                           int first, const StiffnessIndicesOptions& o) {
  BlockIndices b;
  const Mat3 basis = split_free(unbounded, first, o.free_tolerance, b);
  const int k = 3 - b.free_count;  // directions that are not free: basis.leftCols(k)
  // Compliance eigenvalues of the block compressed onto them, ascending (stiffness descending).
  std::array<double, 3> finite{};
  std::array<Vec3, 3> finite_directions{};
  int finite_count = 0;
  if (k > 0) {
    const Block3 Q = basis.leftCols(k);
    const Block3 Cq = Q.transpose() * C * Q;
    const Eigen::SelfAdjointEigenSolver<Block3> es(Cq);
    for (int i = 0; i < k; ++i) {
      const double lambda = es.eigenvalues()[i];
      const Vec3 d = signed_direction(Q * es.eigenvectors().col(i));
      if (lambda * factor <= o.blocked_tolerance * reference) {
        b.blocked[b.blocked_count++] = d;
      } else {
        finite[finite_count] = lambda;
        finite_directions[finite_count++] = d;
      }
    }
  }
  if (b.free_count > 0) {
    b.min = 0.0;
    b.direction_min = b.free[0];
    if (finite_count > 0) {
      b.max = 1.0 / finite[0];
      b.direction_max = finite_directions[0];
    } else {
      b.max = 0.0;
      b.direction_max = b.free[b.free_count - 1];
    }
  } else if (finite_count > 0) {
    b.min = 1.0 / finite[finite_count - 1];
    b.direction_min = finite_directions[finite_count - 1];
    b.max = 1.0 / finite[0];
    b.direction_max = finite_directions[0];
    b.condition = *b.max / *b.min;
  }
  return b;
}

}  // namespace

void StiffnessIndicesOptions::validate() const {
  if (!(blocked_tolerance > 0.0 && blocked_tolerance < 1.0))
    throw Error("StiffnessIndicesOptions: blocked_tolerance must be in (0, 1)");
  if (!(free_tolerance > 0.0 && free_tolerance < 1.0)) throw Error("StiffnessIndicesOptions: free_tolerance must be in (0, 1)");
}

StiffnessIndices stiffness_indices(const Mat6& C, const std::vector<Vec6>& unbounded, double L,
                                   const StiffnessIndicesOptions& options) {
  options.validate();
  const double reference = scaled_reference(C, L);
  StiffnessIndices out;
  out.translational = block_indices(C.topLeftCorner<3, 3>(), 1.0, reference, unbounded, 0, options);
  out.rotational = block_indices(C.bottomRightCorner<3, 3>(), L * L, reference, unbounded, 3, options);
  return out;
}

std::optional<double> stiffness_along(const Mat6& C, const std::vector<Vec6>& unbounded, double L, const Vec3& d,
                                      const StiffnessIndicesOptions& options) {
  options.validate();
  const Vec3 u = d.normalized();
  for (const Vec6& n : unbounded)
    if (std::abs(n.head<3>().dot(u)) > options.free_tolerance) return 0.0;
  const double c = u.dot(C.topLeftCorner<3, 3>() * u);
  if (c <= options.blocked_tolerance * scaled_reference(C, L)) return std::nullopt;
  return 1.0 / c;
}

std::optional<Vec6> deflection_under(const Mat6& C, const std::vector<Vec6>& unbounded, double L, const Vec6& w,
                                     const StiffnessIndicesOptions& options) {
  options.validate();
  Vec6 ws = w;  // (f, m / L): the metric of the unbounded directions
  ws.tail<3>() /= L;
  for (const Vec6& n : unbounded)
    if (std::abs(n.dot(ws)) > options.free_tolerance * ws.norm()) return std::nullopt;
  return Vec6(C * w);
}

ComplianceAxes compliance_axes(const Mat3& C) {
  const Eigen::SelfAdjointEigenSolver<Mat3> es(C);
  ComplianceAxes out;
  for (int i = 0; i < 3; ++i) {
    out.semi_axes[i] = std::max(0.0, es.eigenvalues()[2 - i]);
    out.axes.col(i) = signed_direction(es.eigenvectors().col(2 - i));
  }
  return out;
}

}  // namespace beamfea
