#include "elements/released_element.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <string>
#include <vector>

#include "core/errors.hpp"

namespace beamfea {

namespace {

// Smallest eigenvalue of the Jacobi-scaled k_cc (unit diagonal) below which the released DOFs
// move without strain: a rigid-body mode of the element gives an exact zero (round-off 1e-16
// times the condition of k), a genuine stiffness of a slender member is above 1e-8.
constexpr double kReleaseMechanism = 1e-10;

}  // namespace

std::string describe_releases(const Releases& released) {
  std::string out;
  for (int end = 0; end < 2; ++end) {
    std::string names;
    for (int c = 0; c < 6; ++c)
      if (released[6 * end + c]) names += (names.empty() ? "" : ", ") + std::string(kDofNames[c]);
    if (names.empty()) continue;
    out += (out.empty() ? "" : "; ") + std::string(end == 0 ? "start: " : "end: ") + names;
  }
  return out;
}

Mat12 release_condensation(const Mat12& k, const Releases& released) {
  std::vector<int> c, r;
  for (int i = 0; i < 12; ++i) (released[i] ? c : r).push_back(i);
  Mat12 C = Mat12::Zero();
  for (int i : r) C(i, i) = 1.0;
  const int m = static_cast<int>(c.size());
  if (m == 0) return C;
  Eigen::MatrixXd kcc(m, m), kcr(m, static_cast<int>(r.size()));
  for (int a = 0; a < m; ++a) {
    for (int b = 0; b < m; ++b) kcc(a, b) = k(c[a], c[b]);
    for (std::size_t b = 0; b < r.size(); ++b) kcr(a, static_cast<int>(b)) = k(c[a], r[b]);
  }
  Eigen::VectorXd s(m);
  for (int a = 0; a < m; ++a) s[a] = kcc(a, a) > 0.0 ? 1.0 / std::sqrt(kcc(a, a)) : 0.0;
  const Eigen::MatrixXd scaled = s.asDiagonal() * kcc * s.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(scaled, Eigen::EigenvaluesOnly);
  if (s.minCoeff() == 0.0 || !(es.eigenvalues()[0] > kReleaseMechanism))
    throw Error("the end releases (" + describe_releases(released) +
                ") leave the element a mechanism: the released ends can move without straining it");
  const Eigen::MatrixXd X = -kcc.lu().solve(kcr);  // u_c = X u_r
  for (int a = 0; a < m; ++a)
    for (std::size_t b = 0; b < r.size(); ++b) C(c[a], r[b]) = X(a, static_cast<int>(b));
  return C;
}

ReleasedElement::ReleasedElement(std::unique_ptr<BeamElement> beam, const Releases& released)
    : beam_(std::move(beam)), released_(released), C_(release_condensation(beam_->local_stiffness(), released)) {
  beam_->condense_local(C_);
}

Mat12 ReleasedElement::condensed(const Mat12& A, const Mat3& axes) const {
  const Mat12 T = beam_transformation(axes);
  return T.transpose() * (C_.transpose() * (T * A * T.transpose()) * C_) * T;
}

Mat12 ReleasedElement::geometric_stiffness(const Vec12& f, GeometricStiffness kind) const {
  return condensed(beam_->geometric_stiffness(f, kind), beam_->axes());
}

Mat12 ReleasedElement::mass(MassKind kind, double density) const {
  return condensed(beam_->mass(kind, density), beam_->axes());
}

Mat12 ReleasedElement::mass_at(const NodalPoses& p, MassKind kind, double density) const {
  return condensed(beam_->mass_at(p, kind, density), beam_->axes_at(p));
}

Vec3 ReleasedElement::displacement_at(const NodalPoses& p, double xi) const {
  // The local deformations at the state (Q the local axes at p, E at the reference): end rotations
  // log(Q R_i E^T) and the relative translation of the ends; for a linear beam (Q = E) the small
  // displacements in local axes, node 1's translation removed (a rigid translation, which C
  // keeps); for a co-rotational one its deformational displacements.
  const Mat3 Q = beam_->axes_at(p), E = beam_->axes();
  Vec12 u = Vec12::Zero();
  u.segment<3>(3) = log_so3(Q * p.R1 * E.transpose());
  u.segment<3>(6) = Q * (p.x2 - p.x1) - E * (reference_poses().x2 - reference_poses().x1);
  u.segment<3>(9) = log_so3(Q * p.R2 * E.transpose());
  Vec12 relax = (C_ - Mat12::Identity()) * u;
  // The released rotations only: the drawn member keeps meeting its nodes.
  relax.segment<3>(0).setZero();
  relax.segment<3>(6).setZero();
  return beam_->displacement_at(beam_->advance(p, beam_transformation(Q).transpose() * relax), xi);
}

}  // namespace beamfea
