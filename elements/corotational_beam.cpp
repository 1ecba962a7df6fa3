#include "elements/corotational_beam.hpp"

#include <cmath>

#include "core/errors.hpp"
#include "elements/beam_mass.hpp"
#include "elements/span_loads.hpp"

// Derivation, in the notation of Battini & Pacoste (2002), with every variation written in
// global spatial spins d = [du1 dw1 du2 dw2]:
//
//   frame spin      dRr = [Rr G^T d]x Rr, G^T (3x12, co-rotated components):
//     row 1 (about r1) = [ eta r3/ln, (q1 x r3)/(2 beta), -eta r3/ln, (q2 x r3)/(2 beta) ],
//     row 2 (about r2) = [ r3/ln, 0, -r3/ln, 0 ],     row 3 (about r3) = [ -r2/ln, 0, r2/ln, 0 ],
//     with beta = q.r2 and eta = (q.r1)/beta  (the paper's q2 and q1/q2, in local components),
//     from r2.dr1 = w3, -r3.dr1 = w2, r3.dr2 = w1 and r3 = r1 x q / |r1 x q|;
//   elongation      d ubar = r.d,  r = [-r1, 0, r1, 0];
//   local spin      Rbar_i = Rr^T R_i E0  =>  dRbar_i = [P_i d]x Rbar_i,  P_i = Rr^T E_i - G^T;
//   local rotation  d thetabar_i = Ts(thetabar_i)^{-1} P_i d;
//   force           f = r N + sum_i P_i^T Ts^{-T} m_i,  (N, m_i) = dU/d(ubar, thetabar_i);
//   tangent         K = B^T k B                                                       (material)
//                     + N * [A 0 -A 0; 0; -A 0 A 0; 0],  A = (I - r1 r1^T)/ln   (d r)
//                     + sum_i P_i^T Kh(thetabar_i, m_i) Ts^{-1} P_i                 (d Ts^{-T})
//                     - sum_i E_i^T [Rr v_i]x Rr G^T                                 (d Rr in P_i)
//                     - d(G v)/dd,  v = v_1 + v_2,  v_i = Ts^{-T} m_i                (d G in P_i)
// where Kh(theta, m) = d(Ts^{-T}(theta) m)/d theta. The last term is differentiated directly
// from the expressions of G above (the paper gives the same in a condensed form).

namespace beamfea {
namespace {

using Mat3x12 = Eigen::Matrix<double, 3, 12>;
using Row12 = Eigen::Matrix<double, 1, 12>;

// The selection E_i: the spin of node i out of d (i = 0, 1).
Mat3x12 spin_selector(int i) {
  Mat3x12 E = Mat3x12::Zero();
  E.block<3, 3>(0, 6 * i + 3) = Mat3::Identity();
  return E;
}

// Kh(theta, m) = d/d theta [Ts^{-T}(theta) m], Ts^{-T} = I + [t]/2 + c(a) [t]^2,
// c(a) = (1 - (a/2) cot(a/2)) / a^2 (the coefficient of tangent_so3_inverse).
Mat3 tangent_inverse_transpose_derivative(const Vec3& theta, const Vec3& m) {
  const double a2 = theta.squaredNorm();
  double c, dc_over_a;  // c(a), c'(a)/a
  if (a2 < 0.04) {
    // c = sum_n |B_2n| a^(2n-2) / (2n)!  (series of 1 - h cot h, h = a/2), to a^6; the closed form
    // below loses digits to cancellation as a -> 0 (about 1e-10 relative at a = 0.2).
    c = 1.0 / 12.0 + a2 / 720.0 + a2 * a2 / 30240.0 + a2 * a2 * a2 / 1209600.0;
    dc_over_a = 1.0 / 360.0 + a2 / 7560.0 + a2 * a2 / 201600.0 + a2 * a2 * a2 / 5987520.0;
  } else {
    const double a = std::sqrt(a2), h = 0.5 * a;
    const double s = std::sin(h);
    c = (1.0 - h * std::cos(h) / s) / a2;
    // d/da [1 - h cot h] = (-cot h + h / sin^2 h) / 2
    dc_over_a = (0.5 * (-std::cos(h) / s + h / (s * s))) / (a2 * a) - 2.0 * c / a2;
  }
  const Vec3 txm = theta.cross(m);
  const Vec3 ttxm = theta.cross(txm);
  return -0.5 * skew(m) +
         c * (theta.dot(m) * Mat3::Identity() + theta * m.transpose() - 2.0 * m * theta.transpose()) +
         dc_over_a * ttxm * theta.transpose();
}

// Everything about one configuration that force and tangent share.
struct Frame {
  Vec3 r1, r2, r3, q1, q2, q;
  Mat3 Rr;
  double ln = 0.0, beta = 0.0, eta = 0.0;
  Vec3 theta1, theta2;
};

Frame corotated_frame(const Mat3& E0, const Vec3& x1, const Mat3& R1, const Vec3& x2, const Mat3& R2) {
  Frame F;
  const Vec3 d = x2 - x1;
  F.ln = d.norm();
  if (!(F.ln > 0.0)) throw Error("co-rotational beam: the current chord length is zero");
  F.r1 = d / F.ln;
  // The co-rotated frame of Battini & Pacoste (2002).
  F.q1 = R1 * E0.col(1);
  F.q2 = R2 * E0.col(1);
  F.q = 0.5 * (F.q1 + F.q2);
  const Vec3 n = F.r1.cross(F.q);
  const double nn = n.norm();
  if (!(nn > 1e-8 * F.q.norm()) || !(F.q.norm() > 1e-8))
    throw Error("co-rotational beam: the nodal y axes are parallel to the chord (local rotation ~90 deg); "
                         "the co-rotated frame is undefined");
  F.r3 = n / nn;
  F.r2 = F.r3.cross(F.r1);
  F.Rr.col(0) = F.r1;
  F.Rr.col(1) = F.r2;
  F.Rr.col(2) = F.r3;
  F.beta = F.q.dot(F.r2);  // = |r1 x q| > 0
  F.eta = F.q.dot(F.r1) / F.beta;
  // Local rotations: Rbar_i = Rr^T R_i E0.
  F.theta1 = log_so3(F.Rr.transpose() * R1 * E0);
  F.theta2 = log_so3(F.Rr.transpose() * R2 * E0);
  return F;
}

// G^T: the frame spin in co-rotated components, Rr^T w_r = G^T d.
Mat3x12 frame_spin_rows(const Frame& F) {
  const double ln = F.ln;
  const Vec3 &r2 = F.r2, &r3 = F.r3;
  Mat3x12 GT = Mat3x12::Zero();
  GT.block<1, 3>(0, 0) = (F.eta / ln) * r3.transpose();
  GT.block<1, 3>(0, 3) = F.q1.cross(r3).transpose() / (2.0 * F.beta);
  GT.block<1, 3>(0, 6) = -(F.eta / ln) * r3.transpose();
  GT.block<1, 3>(0, 9) = F.q2.cross(r3).transpose() / (2.0 * F.beta);
  GT.block<1, 3>(1, 0) = r3.transpose() / ln;
  GT.block<1, 3>(1, 6) = -r3.transpose() / ln;
  GT.block<1, 3>(2, 0) = -r2.transpose() / ln;
  GT.block<1, 3>(2, 6) = r2.transpose() / ln;
  return GT;
}

// K -= d(G v)/dd at fixed v (the derivation's last term), Wr = Rr G^T the frame spin (global),
// r the row of d ubar (= d ln).
void subtract_frame_spin_derivative(const Frame& F, const Mat3x12& Wr, const Row12& r, const Vec3& vs, Mat12& K) {
  const double ln = F.ln;
  const Vec3 &r1 = F.r1, &r2 = F.r2, &r3 = F.r3;
  const Mat3x12 E[2] = {spin_selector(0), spin_selector(1)};
  const Mat3x12 Dr2 = -skew(r2) * Wr, Dr3 = -skew(r3) * Wr, Dr1 = -skew(r1) * Wr;
  const Mat3x12 Dq1 = -skew(F.q1) * E[0], Dq2 = -skew(F.q2) * E[1];
  const Mat3x12 Dq = 0.5 * (Dq1 + Dq2);
  const Row12 Dbeta = r2.transpose() * Dq + F.q.transpose() * Dr2;
  const Row12 Dqr1 = r1.transpose() * Dq + F.q.transpose() * Dr1;
  const Row12 Deta = (Dqr1 - F.eta * Dbeta) / F.beta;
  const Row12& Dln = r;
  const double ln2 = ln * ln;
  // Block of G v at node 1's translation: vs0 eta r3/ln + vs1 r3/ln - vs2 r2/ln (node 2: minus).
  const Mat3x12 Db0 = vs(0) * (r3 * (Deta / ln - F.eta * Dln / ln2) + (F.eta / ln) * Dr3) +
                      vs(1) * (Dr3 / ln - r3 * Dln / ln2) - vs(2) * (Dr2 / ln - r2 * Dln / ln2);
  // Blocks at the spins: vs0 (q_i x r3) / (2 beta).
  const double w = vs(0) / (2.0 * F.beta);
  const Mat3x12 Db1 = w * (-skew(r3) * Dq1 + skew(F.q1) * Dr3) - (w / F.beta) * F.q1.cross(r3) * Dbeta;
  const Mat3x12 Db3 = w * (-skew(r3) * Dq2 + skew(F.q2) * Dr3) - (w / F.beta) * F.q2.cross(r3) * Dbeta;
  K.middleRows<3>(0) -= Db0;
  K.middleRows<3>(3) -= Db1;
  K.middleRows<3>(6) += Db0;
  K.middleRows<3>(9) -= Db3;
}

}  // namespace

CorotationalBeam::CorotationalBeam(const BeamSection& section, const Vec3& X1, const Vec3& X2,
                                   const Vec3& orientation)
    : BeamElement(section, X1, X2, orientation), E0_(R_.transpose()) {}

CorotationalKinematics CorotationalBeam::kinematics(const Vec3& x1, const Mat3& R1, const Vec3& x2,
                                                    const Mat3& R2) const {
  const Frame F = corotated_frame(E0_, x1, R1, x2, R2);
  return {F.Rr, F.ln, F.ln - L_, F.theta1, F.theta2};
}

CorotationalResponse CorotationalBeam::evaluate(const Vec3& x1, const Mat3& R1, const Vec3& x2, const Mat3& R2,
                                                bool with_tangent) const {
  const Frame F = corotated_frame(E0_, x1, R1, x2, R2);
  const double ln = F.ln;
  const Vec3& r1 = F.r1;

  // The linear local element on dl = [0 0 0 thetabar_1  ubar 0 0 thetabar_2].
  Vec12 dl = Vec12::Zero();
  dl.segment<3>(3) = F.theta1;
  dl(6) = ln - L_;
  dl.segment<3>(9) = F.theta2;
  CorotationalResponse out;
  const Mat12 kl = local_stiffness();
  out.local_end_forces = kl * dl;
  out.energy = 0.5 * dl.dot(out.local_end_forces);
  const double N = out.local_end_forces(6);
  const Vec3 m[2] = {out.local_end_forces.segment<3>(3), out.local_end_forces.segment<3>(9)};
  const Vec3 theta[2] = {F.theta1, F.theta2};

  // r: d ubar = r.d
  Row12 r = Row12::Zero();
  r.segment<3>(0) = -r1.transpose();
  r.segment<3>(6) = r1.transpose();

  const Mat3x12 GT = frame_spin_rows(F);
  const Mat3x12 Wr = F.Rr * GT;  // frame spin, global components

  const Mat3x12 E[2] = {spin_selector(0), spin_selector(1)};
  Mat3x12 P[2], TP[2];
  Mat3 Tinv[2];
  Vec3 v[2];
  for (int i = 0; i < 2; ++i) {
    P[i] = F.Rr.transpose() * E[i] - GT;
    Tinv[i] = tangent_so3_inverse(theta[i]);
    TP[i] = Tinv[i] * P[i];                // d thetabar_i = TP_i d
    v[i] = Tinv[i].transpose() * m[i];
  }

  // Internal force.
  out.force = r.transpose() * N + P[0].transpose() * v[0] + P[1].transpose() * v[1];
  if (!with_tangent) {
    out.tangent.setZero();
    return out;
  }

  // Material tangent: B^T k B with B = [r; TP_1; TP_2] and k the (ubar, thetabar) block of kl.
  constexpr int rot[6] = {3, 4, 5, 9, 10, 11};
  Eigen::Matrix<double, 6, 6> k_rot;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) k_rot(a, b) = kl(rot[a], rot[b]);
  Eigen::Matrix<double, 6, 12> Brot;
  Brot.topRows<3>() = TP[0];
  Brot.bottomRows<3>() = TP[1];
  Mat12 K = kl(6, 6) * r.transpose() * r + Brot.transpose() * k_rot * Brot;

  // Geometric part 1: d r.
  const Mat3 A = (Mat3::Identity() - r1 * r1.transpose()) / ln;
  K.block<3, 3>(0, 0) += N * A;
  K.block<3, 3>(0, 6) -= N * A;
  K.block<3, 3>(6, 0) -= N * A;
  K.block<3, 3>(6, 6) += N * A;

  // Geometric parts 2 and 3: d Ts^{-T}(thetabar_i) and d Rr inside P_i.
  for (int i = 0; i < 2; ++i) {
    K += P[i].transpose() * tangent_inverse_transpose_derivative(theta[i], m[i]) * TP[i];
    K -= E[i].transpose() * skew(F.Rr * v[i]) * Wr;
  }

  // Geometric part 4: d(G v), v = v_1 + v_2 held fixed.
  subtract_frame_spin_derivative(F, Wr, r, v[0] + v[1], K);

  out.tangent = K;
  return out;
}

Mat3 CorotationalBeam::axes_at(const NodalPoses& p) const {
  return kinematics(p.x1, p.R1, p.x2, p.R2).Rr.transpose();
}

ElementResponse CorotationalBeam::respond(const NodalPoses& p, Evaluate what) const {
  return evaluate(p.x1, p.R1, p.x2, p.R2, what == Evaluate::ForceAndTangent);
}

NodalPoses CorotationalBeam::advance(const NodalPoses& p, const Vec12& d) const {
  return {p.x1 + d.segment<3>(0), p.x2 + d.segment<3>(6), exp_so3(d.segment<3>(3)) * p.R1,
          exp_so3(d.segment<3>(9)) * p.R2};
}

Mat12 CorotationalBeam::mass_at(const NodalPoses& p, MassKind kind, double density) const {
  // The reference length's local mass in the co-rotated axes: mass is conserved.
  const Mat12 T = beam_transformation(axes_at(p));
  return T.transpose() * beam_local_mass(section_, density, L_, kind) * T;
}

Vec12 CorotationalBeam::fixed_end_forces_at(const NodalPoses& p, const ElementLoads& loads) const {
  // Reference local -> global (E0, columns the reference axes) -> current local (Rr^T): the load
  // keeps its direction in space; over the reference length (loads per unit reference length).
  const Mat3 Q = axes_at(p) * E0_;
  ElementLoads now;
  for (const auto& d : loads.distributed) now.distributed.push_back({d.a, d.b, Q * d.q_a, Q * d.q_b});
  for (const auto& pt : loads.points) now.points.push_back({pt.a, Q * pt.force, Q * pt.moment});
  return fixed_end_forces(L_, now);
}

Vec3 CorotationalBeam::displacement_at(const NodalPoses& p, double xi) const {
  // The chord, plus the cubic deflection of the local end rotations in the co-rotated plane.
  const CorotationalKinematics k = kinematics(p.x1, p.R1, p.x2, p.R2);
  const Vec3 X = (1.0 - xi) * X1_ + xi * X2_;
  const double ln = k.length;
  const double h1 = xi * (1 - xi) * (1 - xi), h2 = -xi * xi * (1 - xi);
  const double v = ln * (h1 * k.theta1.z() + h2 * k.theta2.z());
  const double w = -ln * (h1 * k.theta1.y() + h2 * k.theta2.y());
  const Vec3 x = p.x1 + xi * (p.x2 - p.x1) + k.Rr * Vec3(0.0, v, w);
  return x - X;
}

}  // namespace beamfea
