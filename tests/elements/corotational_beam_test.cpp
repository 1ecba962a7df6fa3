// The element contract suite for CorotationalBeam (STYLE.md, "Tests"): force = d(energy),
// tangent = d(force) by finite differences along the element's own increments (translations and
// SPATIAL spins, R <- exp(dw) R), zero force under rigid motion, objectivity, the small-displacement
// limit, the exact skew part of the tangent, rotation edge cases near 0 and pi, and one
// large-rotation benchmark solved with a small Newton loop (the pattern the global solver uses).
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/errors.hpp"
#include "elements/corotational_beam.hpp"

namespace beamfea::corotational_beam_test {
namespace {

using std::numbers::pi;

struct State {
  Vec3 x1, x2;
  Mat3 R1, R2;
};

BeamSection test_section() {
  BeamSection s;
  s.E = 100.0;
  s.G = 40.0;
  s.A = 1.0;
  s.Iy = 0.05;
  s.Iz = 0.08;
  s.J = 0.1;
  return s;
}

const Vec3 kX1(0.1, -0.2, 0.3);
const Vec3 kX2(1.3, 0.6, -0.3);
const Vec3 kOrientation(0.0, 0.0, 1.0);

CorotationalBeam test_beam() { return CorotationalBeam(test_section(), kX1, kX2, kOrientation); }

CorotationalResponse evaluate(const CorotationalBeam& b, const State& s) {
  return b.evaluate(s.x1, s.R1, s.x2, s.R2);
}

// A moderate local deformation (stretch, bending, twist) superposed on the rigid motion
// x -> Q x + t, R -> Q.
State deformed_state(const Mat3& Q, const Vec3& t, double scale = 1.0) {
  State s;
  s.x1 = Q * kX1 + t;
  s.x2 = Q * (kX2 + scale * Vec3(0.03, -0.05, 0.04)) + t;
  s.R1 = Q * exp_so3(scale * Vec3(0.1, -0.05, 0.08));
  s.R2 = Q * exp_so3(scale * Vec3(-0.07, 0.12, 0.05));
  return s;
}

State rigid_state(const Mat3& Q, const Vec3& t) {
  return {Q * kX1 + t, Q * kX2 + t, Q, Q};
}

// The state after the increment h e_j, e_j the j-th of [du1 dw1 du2 dw2].
State perturbed(State s, int j, double h) {
  Vec3 e = Vec3::Zero();
  e(j % 3) = h;
  switch (j / 3) {
    case 0: s.x1 += e; break;
    case 1: s.R1 = exp_so3(e) * s.R1; break;
    case 2: s.x2 += e; break;
    default: s.R2 = exp_so3(e) * s.R2; break;
  }
  return s;
}

Vec12 fd_energy_gradient(const CorotationalBeam& b, const State& s, double h) {
  Vec12 g;
  for (int j = 0; j < 12; ++j)
    g(j) = (evaluate(b, perturbed(s, j, h)).energy - evaluate(b, perturbed(s, j, -h)).energy) / (2 * h);
  return g;
}

Mat12 fd_force_jacobian(const CorotationalBeam& b, const State& s, double h) {
  Mat12 K;
  for (int j = 0; j < 12; ++j)
    K.col(j) = (evaluate(b, perturbed(s, j, h)).force - evaluate(b, perturbed(s, j, -h)).force) / (2 * h);
  return K;
}

Mat12 block_rotation(const Mat3& Q) { return beam_transformation(Q); }  // diag(Q, Q, Q, Q)

// The rigid motions exercised below: small, generic large, near and at pi, and beyond 2 pi.
std::vector<Mat3> rigid_rotations() {
  const Vec3 n = Vec3(1.0, -2.0, 0.5).normalized();
  return {Mat3::Identity(),       exp_so3(1e-9 * n),           exp_so3(1.3 * n),
          exp_so3((pi - 1e-9) * n), exp_so3(pi * Vec3::UnitZ()), exp_so3(pi * n),
          exp_so3((2 * pi + 0.3) * n)};
}

const Vec3 kTranslation(0.7, -1.1, 2.0);

TEST(CorotationalBeam, InternalForceIsTheDerivativeOfStrainEnergy) {
  const CorotationalBeam b = test_beam();
  for (const Mat3& Q : rigid_rotations()) {
    const State s = deformed_state(Q, kTranslation);
    const CorotationalResponse r = evaluate(b, s);
    ASSERT_GT(r.energy, 1e-3);
    const Vec12 g = fd_energy_gradient(b, s, 1e-6);
    EXPECT_LT((g - r.force).norm(), 1e-7 * r.force.norm()) << "FD gradient\n" << g.transpose() << "\nforce\n"
                                                           << r.force.transpose();
  }
}

TEST(CorotationalBeam, TangentMatchesFiniteDifferenceOfInternalForce) {
  const CorotationalBeam b = test_beam();
  for (double scale : {1.0, 3.0}) {  // local rotations up to ~0.5 rad
    for (const Mat3& Q : rigid_rotations()) {
      const State s = deformed_state(Q, kTranslation, scale);
      const CorotationalResponse r = evaluate(b, s);
      const Mat12 Kfd = fd_force_jacobian(b, s, 1e-6);
      const double err = (Kfd - r.tangent).cwiseAbs().maxCoeff();
      EXPECT_LT(err, 1e-7 * r.tangent.cwiseAbs().maxCoeff()) << "scale " << scale << "\nFD - tangent\n"
                                                             << (Kfd - r.tangent);
    }
  }
}

// The check above is sharp enough to see the geometric (stress-dependent) terms: the skew part of
// the tangent, purely geometric, is a thousand times the finite-difference error.
TEST(CorotationalBeam, FiniteDifferenceCheckIsSharpEnoughToSeeTheGeometricTerms) {
  const CorotationalBeam b = test_beam();
  const State s = deformed_state(exp_so3(Vec3(0.3, 0.2, -0.1)), kTranslation, 3.0);
  const CorotationalResponse r = evaluate(b, s);
  const Mat12 Kfd = fd_force_jacobian(b, s, 1e-6);
  const Mat12 K_sym = 0.5 * (r.tangent + r.tangent.transpose());
  EXPECT_GT((r.tangent - K_sym).cwiseAbs().maxCoeff(), 1e3 * (Kfd - r.tangent).cwiseAbs().maxCoeff());
}

TEST(CorotationalBeam, RigidBodyMotionProducesNoForceAndNoEnergy) {
  const CorotationalBeam b = test_beam();
  const double k_scale = b.local_stiffness().cwiseAbs().maxCoeff();
  for (const Mat3& Q : rigid_rotations()) {
    const CorotationalResponse r = evaluate(b, rigid_state(Q, kTranslation));
    EXPECT_LT(r.force.norm(), 1e-12 * k_scale);
    EXPECT_LT(r.local_end_forces.norm(), 1e-12 * k_scale);
    EXPECT_LT(r.energy, 1e-24 * k_scale);
    // The unloaded tangent is the rotated linear stiffness.
    const LinearBeam lin(test_section(), kX1, kX2, kOrientation);
    const Mat12 G = block_rotation(Q);
    EXPECT_LT((r.tangent - G * lin.stiffness() * G.transpose()).cwiseAbs().maxCoeff(), 1e-11 * k_scale);
  }
}

TEST(CorotationalBeam, SuperposedFiniteRotationRotatesForcesAndKeepsEnergy) {
  const CorotationalBeam b = test_beam();
  const State s = deformed_state(exp_so3(Vec3(0.4, -0.3, 0.2)), Vec3(0.1, 0.2, 0.3));
  const CorotationalResponse r = evaluate(b, s);
  const double f_scale = r.force.norm(), k_scale = r.tangent.cwiseAbs().maxCoeff();
  for (const Mat3& Q : rigid_rotations()) {
    const State sq{Q * s.x1 + kTranslation, Q * s.x2 + kTranslation, Q * s.R1, Q * s.R2};
    const CorotationalResponse rq = evaluate(b, sq);
    const Mat12 G = block_rotation(Q);
    EXPECT_NEAR(rq.energy, r.energy, 1e-13 * r.energy);
    EXPECT_LT((rq.force - G * r.force).norm(), 1e-12 * f_scale);
    EXPECT_LT((rq.tangent - G * r.tangent * G.transpose()).cwiseAbs().maxCoeff(), 1e-12 * k_scale);
    EXPECT_LT((rq.local_end_forces - r.local_end_forces).norm(), 1e-12 * f_scale);
  }
}

TEST(CorotationalBeam, TangentAtReferenceEqualsLinearBeamStiffness) {
  const CorotationalBeam b = test_beam();
  const LinearBeam lin(test_section(), kX1, kX2, kOrientation);
  const CorotationalResponse r = evaluate(b, rigid_state(Mat3::Identity(), Vec3::Zero()));
  const double k_scale = lin.stiffness().cwiseAbs().maxCoeff();
  EXPECT_LT((r.tangent - lin.stiffness()).cwiseAbs().maxCoeff(), 1e-13 * k_scale);
  EXPECT_LT((b.reference_axes().transpose() - lin.axes()).norm(), 1e-15);
}

// Small displacements u ~ eps: force, energy and local end forces equal the linear beam's to O(eps^2).
TEST(CorotationalBeam, SmallDisplacementResponseEqualsLinearBeam) {
  const CorotationalBeam b = test_beam();
  const LinearBeam lin(test_section(), kX1, kX2, kOrientation);
  Vec12 u;
  u << 0.3, -0.2, 0.5, 0.1, -0.4, 0.2, -0.1, 0.6, 0.2, -0.3, 0.1, 0.4;
  for (double eps : {1e-4, 1e-6, 1e-9}) {
    const Vec12 ue = eps * u;
    const State s{kX1 + ue.segment<3>(0), kX2 + ue.segment<3>(6), exp_so3(ue.segment<3>(3)),
                  exp_so3(ue.segment<3>(9))};
    const CorotationalResponse r = evaluate(b, s);
    const Vec12 f_lin = lin.internal_force(ue);
    // Relative deviation O(eps) (nonlinear terms) plus round-off O(1e-16 / eps).
    const double tol = 10.0 * eps + 1e-15 / eps;
    EXPECT_LT((r.force - f_lin).norm(), tol * f_lin.norm()) << "eps " << eps;
    EXPECT_NEAR(r.energy, lin.strain_energy(ue), tol * lin.strain_energy(ue)) << "eps " << eps;
    const Vec12 fl_lin = lin.local_end_forces(ue);
    EXPECT_LT((r.local_end_forces - fl_lin).norm(), tol * fl_lin.norm()) << "eps " << eps;
  }
}

// For spatial-spin increments the tangent is the covariant Hessian plus half a Lie bracket:
// K - K^T = -[m_i]x on each node's rotation block and zero elsewhere (m_i the nodal moment of
// `force`). Hence the part K + blockdiag(0, [m1]x/2, 0, [m2]x/2) is symmetric, always.
TEST(CorotationalBeam, TangentSkewPartIsExactlyTheSpinBracketOfTheNodalMoments) {
  const CorotationalBeam b = test_beam();
  for (const Mat3& Q : rigid_rotations()) {
    const CorotationalResponse r = evaluate(b, deformed_state(Q, kTranslation, 3.0));
    Mat12 bracket = Mat12::Zero();
    bracket.block<3, 3>(3, 3) = skew(r.force.segment<3>(3));
    bracket.block<3, 3>(9, 9) = skew(r.force.segment<3>(9));
    const double k_scale = r.tangent.cwiseAbs().maxCoeff();
    ASSERT_GT(bracket.norm(), 1e-2 * k_scale);  // the skew part is genuinely there
    EXPECT_LT((r.tangent - r.tangent.transpose() + bracket).cwiseAbs().maxCoeff(), 1e-12 * k_scale);
    const Mat12 Ks = r.tangent + 0.5 * bracket;
    EXPECT_LT((Ks - Ks.transpose()).cwiseAbs().maxCoeff(), 1e-12 * k_scale);
  }
}

// With no end moments (pure stretch, any rigid rotation) the tangent itself is symmetric.
TEST(CorotationalBeam, TangentIsSymmetricUnderPureAxialForce) {
  const CorotationalBeam b = test_beam();
  for (const Mat3& Q : rigid_rotations()) {
    State s = rigid_state(Q, kTranslation);
    s.x2 += 0.01 * Q * (kX2 - kX1);
    const CorotationalResponse r = evaluate(b, s);
    ASSERT_GT(std::abs(r.local_end_forces(6)), 0.1);
    EXPECT_LT((r.tangent - r.tangent.transpose()).cwiseAbs().maxCoeff(), 1e-12 * r.tangent.cwiseAbs().maxCoeff());
  }
}

// Local rotations near zero (|thetabar| ~ 1e-9, on top of a large rigid rotation): the series
// branches of log, Ts^{-1} and its derivative. Energy and moments are the linear beam's.
TEST(CorotationalBeam, TinyLocalRotationsGiveLinearResponseAndAConsistentTangent) {
  const CorotationalBeam b = test_beam();
  const LinearBeam lin(test_section(), kX1, kX2, kOrientation);
  const Mat3 Q = exp_so3(Vec3(0.5, 1.0, -0.7));
  const Vec3 w0(1e-9, -2e-9, 3e-9);
  State s = rigid_state(Q, kTranslation);
  s.R2 = Q * exp_so3(w0);
  const CorotationalResponse r = evaluate(b, s);
  Vec12 u = Vec12::Zero();
  u.segment<3>(9) = w0;
  EXPECT_NEAR(r.energy, lin.strain_energy(u), 1e-6 * lin.strain_energy(u));
  EXPECT_LT((r.local_end_forces - lin.local_end_forces(u)).norm(), 1e-6 * lin.local_end_forces(u).norm());
  EXPECT_LT((r.force - block_rotation(Q) * lin.internal_force(u)).norm(), 1e-6 * lin.internal_force(u).norm());
  const Mat12 Kfd = fd_force_jacobian(b, s, 1e-6);
  EXPECT_LT((Kfd - r.tangent).cwiseAbs().maxCoeff(), 1e-7 * r.tangent.cwiseAbs().maxCoeff());
}

// A relative rotation of the two nodal triads near pi is beyond the element's range (moderate
// local deformation), but the total rotations R_i may be anything: here they are half-turns
// about different axes, with a small deformation between them.
TEST(CorotationalBeam, NodalRotationsAtAndNearHalfTurnAreHandledExactly) {
  const CorotationalBeam b = test_beam();
  const State s0 = deformed_state(Mat3::Identity(), Vec3::Zero(), 0.5);
  const CorotationalResponse r0 = evaluate(b, s0);
  for (double angle : {pi, pi - 1e-9, pi + 1e-9}) {
    const Mat3 Q = exp_so3(angle * Vec3(0.0, 1.0, 1.0).normalized());
    const State s{Q * s0.x1, Q * s0.x2, Q * s0.R1, Q * s0.R2};
    const CorotationalResponse r = evaluate(b, s);
    EXPECT_NEAR(r.energy, r0.energy, 1e-13 * r0.energy);
    const Mat12 Kfd = fd_force_jacobian(b, s, 1e-6);
    EXPECT_LT((Kfd - r.tangent).cwiseAbs().maxCoeff(), 1e-7 * r.tangent.cwiseAbs().maxCoeff());
  }
}

TEST(CorotationalBeam, ThrowsWhenTheCorotatedFrameIsUndefined) {
  const CorotationalBeam b = test_beam();
  State s = rigid_state(Mat3::Identity(), Vec3::Zero());
  // Turn both nodal y axes onto the chord: 90 deg about the local z axis at both nodes.
  const Vec3 ez = b.reference_axes().col(2);
  s.R1 = s.R2 = exp_so3(0.5 * pi * ez);
  EXPECT_THROW(evaluate(b, s), Error);
}

// Benchmark: a cantilever of length L under an end moment M about a fixed axis bends into a
// circular arc of radius EI/M; at M = 2 pi EI/L it closes into a full circle, tip back at the
// root and tip rotation 2 pi (the classical roll-up test, e.g. Simo & Vu-Quoc 1986, Comput.
// Meth. Appl. Mech. Eng. 58; used by Crisfield 1990 and Battini & Pacoste 2002). With n
// co-rotational elements the nodes lie on a regular polygon with sides L/n (the exact element solution: N = 0, uniform moment), so the tip closes exactly and
// the mid-node sits at 2 r, r = (L/n) / (2 sin(pi/n)). Solved here by load steps and Newton with
// the element's tangent and the increment R <- exp(dw) R, as the global solver does.
TEST(CorotationalBeam, CantileverUnderEndMomentRollsIntoAFullCircleAndBeyond) {
  BeamSection sec;
  sec.E = 1.0e4, sec.G = 4.0e3, sec.A = 1.0, sec.Iy = 2.0e-4, sec.Iz = 1.0e-4, sec.J = 1.5e-4;  // L/r = 100
  const double L = 1.0;
  const int n = 16, ndof = 6 * (n + 1);
  std::vector<CorotationalBeam> elems;
  std::vector<Vec3> x(n + 1);
  std::vector<Mat3> R(n + 1, Mat3::Identity());
  for (int i = 0; i <= n; ++i) x[i] = Vec3(L * i / n, 0, 0);
  for (int e = 0; e < n; ++e) elems.emplace_back(sec, x[e], x[e + 1], Vec3(0, 0, 1));
  const double EI = sec.E * sec.Iz;  // bending in the global x-y plane (local y = global y)

  // Assembled internal force and tangent of the current state (node 0 included).
  auto assemble = [&](Eigen::VectorXd& fint, Eigen::MatrixXd& K) {
    fint = Eigen::VectorXd::Zero(ndof);
    K = Eigen::MatrixXd::Zero(ndof, ndof);
    for (int e = 0; e < n; ++e) {
      const CorotationalResponse r = elems[e].evaluate(x[e], R[e], x[e + 1], R[e + 1]);
      fint.segment<12>(6 * e) += r.force;
      K.block<12, 12>(6 * e, 6 * e) += r.tangent;
    }
  };
  auto solve_to = [&](double M, int steps, double M0) -> int {
    int worst_iterations = 0;
    for (int step = 1; step <= steps; ++step) {
      Eigen::VectorXd fext = Eigen::VectorXd::Zero(ndof);
      fext(6 * n + 5) = M0 + (M - M0) * step / steps;
      int it = 0;
      for (;; ++it) {
        Eigen::VectorXd fint;
        Eigen::MatrixXd K;
        assemble(fint, K);
        const Eigen::VectorXd rf = (fint - fext).tail(ndof - 6);
        if (rf.norm() < 1e-10 * EI / L) break;
        if (it >= 30) {
          ADD_FAILURE() << "no convergence at M = " << fext(6 * n + 5) << ", |r| = " << rf.norm();
          return it;
        }
        const Eigen::VectorXd d = K.bottomRightCorner(ndof - 6, ndof - 6).partialPivLu().solve(-rf);
        for (int i = 1; i <= n; ++i) {
          x[i] += d.segment<3>(6 * (i - 1));
          R[i] = exp_so3(d.segment<3>(6 * (i - 1) + 3)) * R[i];
        }
      }
      worst_iterations = std::max(worst_iterations, it);
    }
    return worst_iterations;
  };

  // Full circle.
  EXPECT_LE(solve_to(2 * pi * EI / L, 8, 0.0), 10);  // 8 Newton iterations per step here
  EXPECT_LT((x[n] - x[0]).norm(), 1e-9 * L);
  EXPECT_LT((R[n] - Mat3::Identity()).norm(), 1e-9);  // tip rotation 2 pi
  const double radius_h = (L / n) / (2 * std::sin(pi / n));
  EXPECT_NEAR(x[n / 2].y(), 2 * radius_h, 1e-9 * L);
  EXPECT_NEAR(x[n / 2].x(), 0.0, 1e-9 * L);
  // ... which is the continuum's diameter L/pi to O((pi/n)^2): 0.6 % for n = 16.
  EXPECT_NEAR(x[n / 2].y(), L / pi, 0.01 * L / pi);
  // At equilibrium the assembled tangent's skew part is -[M_ext]x / 2 at the loaded node only
  // (see the header): symmetric at the free interior nodes.
  {
    Eigen::VectorXd fint;
    Eigen::MatrixXd K;
    assemble(fint, K);
    Eigen::MatrixXd skew_part = 0.5 * (K - K.transpose());
    skew_part.block<3, 3>(6 * n + 3, 6 * n + 3) += 0.5 * skew(Vec3(0, 0, 2 * pi * EI / L));
    skew_part.topLeftCorner<6, 6>().setZero();  // the support node carries the reaction moment
    EXPECT_LT(skew_part.cwiseAbs().maxCoeff(), 1e-8 * K.cwiseAbs().maxCoeff());
  }

  // Beyond: 2.5 turns' worth of moment, tip rotation 5 pi = pi about z (mod 2 pi).
  EXPECT_LE(solve_to(5 * pi * EI / L, 12, 2 * pi * EI / L), 10);
  EXPECT_LT((R[n] - exp_so3(pi * Vec3::UnitZ())).norm(), 1e-9);
  // Closed form of the polygon: tip = sum of chords at angles (k + 1/2) alpha, alpha = 5 pi / n.
  const double alpha = 5 * pi / n;
  Vec3 tip = Vec3::Zero();
  for (int k = 0; k < n; ++k) tip += (L / n) * Vec3(std::cos((k + 0.5) * alpha), std::sin((k + 0.5) * alpha), 0);
  EXPECT_LT((x[n] - tip).norm(), 1e-9 * L);
  for (int i = 0; i <= n; ++i) EXPECT_NEAR(x[i].z(), 0.0, 1e-12);
}

}  // namespace
}  // namespace beamfea::corotational_beam_test
