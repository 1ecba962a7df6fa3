#pragma once
// Closed-loop mechanisms for the loop tests, written as input JSON, and their closed-form kinematics
// (computed here, independently of the code under test).
#include <Eigen/Core>
#include <cmath>
#include <string>

#include "nl_models.hpp"

namespace beamfea::test {

// A point of the plane z = 0.
inline json xyz(double x, double y) { return json::array({x, y, 0.0}); }

// Intersection of the circles |P - P1| = r1 and |P - P2| = r2 on the left of P1 -> P2 ("elbow up"
// for P1 left of P2).
inline Eigen::Vector2d circle_intersection(const Eigen::Vector2d& P1, double r1, const Eigen::Vector2d& P2, double r2) {
  const Eigen::Vector2d d = P2 - P1;
  const double l = d.norm();
  const double a = (r1 * r1 - r2 * r2 + l * l) / (2 * l);
  const double h = std::sqrt(std::max(0.0, r1 * r1 - a * a));
  const Eigen::Vector2d e = d / l, n(-e.y(), e.x());
  return P1 + a * e + h * n;
}

// Planar four-bar linkage in the plane z = 0: ground pivots A = (0, 0) and D = (g, 0), crank AB of
// length a at angle theta0, coupler BC of length b, rocker DC of length c (C above the ground line).
// Rigid links, revolute joints about z (a spring k at the crank, the others passive), both ground
// nodes fixed. The loop closes through the ground (the supports of D act on a slave) and, with
// `ground_link`, also through a rigid link A-D (then only A is supported). `released`: the coupler's
// joints are a universal (z, then the in-plane normal of BC) at B and a spherical at C, so that the
// closure has no redundant row (Gruebler: 6 x 3 - (5 + 4 + 3 + 5) = 1); otherwise all four axes are
// parallel and three closure rows are redundant.
struct FourBar {
  double a = 0.3, b = 0.8, c = 0.6, g = 0.7, theta0 = 1.2, k = 5.0;
  Eigen::Vector2d A() const { return {0, 0}; }
  Eigen::Vector2d D() const { return {g, 0}; }
  Eigen::Vector2d B(double t) const { return {a * std::cos(t), a * std::sin(t)}; }
  Eigen::Vector2d C(double t) const { return circle_intersection(D(), c, B(t), b); }
  // dC/dtheta by the derivative of the two circle equations: (C-B).(dC-dB) = 0, (C-D).dC = 0.
  Eigen::Vector2d dC(double t) const {
    const Eigen::Vector2d Bp = B(t), Cp = C(t), dB(-a * std::sin(t), a * std::cos(t));
    Eigen::Matrix2d M;
    M.row(0) = (Cp - Bp).transpose();
    M.row(1) = (Cp - D()).transpose();
    return M.inverse() * Eigen::Vector2d((Cp - Bp).dot(dB), 0.0);
  }
};

inline json four_bar_model(const FourBar& fb, bool ground_link, bool released) {
  const Eigen::Vector2d A = fb.A(), B = fb.B(fb.theta0), C = fb.C(fb.theta0), D = fb.D();
  json d;
  d["nodes"] = json::array({{{"id", "A"}, {"xyz", xyz(A.x(), A.y())}}, {{"id", "A1"}, {"xyz", xyz(A.x(), A.y())}},
                            {{"id", "B"}, {"xyz", xyz(B.x(), B.y())}}, {{"id", "B1"}, {"xyz", xyz(B.x(), B.y())}},
                            {{"id", "C"}, {"xyz", xyz(C.x(), C.y())}}, {{"id", "C1"}, {"xyz", xyz(C.x(), C.y())}},
                            {{"id", "D"}, {"xyz", xyz(D.x(), D.y())}}, {{"id", "D1"}, {"xyz", xyz(D.x(), D.y())}}});
  d["elements"] = json::array({{{"id", "crank"}, {"type", "rigid"}, {"nodes", {"A1", "B"}}},
                               {{"id", "coupler"}, {"type", "rigid"}, {"nodes", {"B1", "C"}}},
                               {{"id", "rocker"}, {"type", "rigid"}, {"nodes", {"D1", "C1"}}}});
  const Eigen::Vector2d e = (C - B).normalized();
  const json z = json::array({0, 0, 1});
  d["joints"] = json::array({{{"id", "jA"}, {"type", "revolute"}, {"nodes", {"A", "A1"}}, {"axes", {z}}, {"stiffness", {fb.k}}},
                             {{"id", "jD"}, {"type", "revolute"}, {"nodes", {"D", "D1"}}, {"axes", {z}}}});
  if (released) {
    d["joints"].push_back({{"id", "jB"}, {"type", "universal"}, {"nodes", {"B", "B1"}},
                           {"axes", {z, json::array({-e.y(), e.x(), 0.0})}}});
    d["joints"].push_back({{"id", "jC"}, {"type", "spherical"}, {"nodes", {"C", "C1"}},
                           {"axes", {json::array({1, 0, 0}), json::array({0, 1, 0}), z}}});
  } else {
    d["joints"].push_back({{"id", "jB"}, {"type", "revolute"}, {"nodes", {"B", "B1"}}, {"axes", {z}}});
    d["joints"].push_back({{"id", "jC"}, {"type", "revolute"}, {"nodes", {"C", "C1"}}, {"axes", {z}}});
  }
  d["supports"] = json::array({fix("A", {"ux", "uy", "uz", "rx", "ry", "rz"})});
  if (ground_link) {
    d["elements"].push_back({{"id", "ground"}, {"type", "rigid"}, {"nodes", {"A", "D"}}});
  } else {
    d["supports"].push_back(fix("D", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  }
  d["loads"] = json::array();
  return d;
}

// Planar five-bar parallel manipulator (2 DOF) in z = 0: actuated pivots A1 = (0, 0), A2 = (g, 0),
// proximal links l1 at angles q1, q2 with actuator springs k1, k2, distal links l2 joined at the end
// point E (above). Rigid links, revolute joints about z. Both pivots fixed: the loop closes through
// the ground (supports on a slave); with `ground_link` only A1 is fixed and a rigid link A1-A2 carries
// A2, and the loop closes at E's joint (a joint closure).
struct FiveBar {
  double g = 0.4, l1 = 0.35, l2 = 0.5, q1 = 2.0, q2 = 1.1, k1 = 40.0, k2 = 60.0;
  Eigen::Vector2d A(int i) const { return {i == 0 ? 0.0 : g, 0.0}; }
  Eigen::Vector2d B(int i, double q) const { return A(i) + l1 * Eigen::Vector2d(std::cos(q), std::sin(q)); }
  Eigen::Vector2d E(double a, double b) const { return circle_intersection(B(0, a), l2, B(1, b), l2); }
  // dE/dq (2 x 2): (E - B_i).(dE - dB_i) = 0.
  Eigen::Matrix2d J(double a, double b) const {
    const Eigen::Vector2d e = E(a, b), b1 = B(0, a), b2 = B(1, b);
    Eigen::Matrix2d M, R = Eigen::Matrix2d::Zero();
    M.row(0) = (e - b1).transpose();
    M.row(1) = (e - b2).transpose();
    R(0, 0) = (e - b1).dot(l1 * Eigen::Vector2d(-std::sin(a), std::cos(a)));
    R(1, 1) = (e - b2).dot(l1 * Eigen::Vector2d(-std::sin(b), std::cos(b)));
    return M.inverse() * R;
  }
  // Equilibrium under a force F at E: k_i (q_i - q_i0) = (J^T F)_i, solved by Newton on q with a
  // central-difference Jacobian; returns q.
  Eigen::Vector2d equilibrium(const Eigen::Vector2d& F) const {
    Eigen::Vector2d q(q1, q2);
    const Eigen::Vector2d q0(q1, q2), k(k1, k2);
    auto res = [&](const Eigen::Vector2d& x) { return Eigen::Vector2d(k.cwiseProduct(x - q0) - J(x[0], x[1]).transpose() * F); };
    for (int it = 0; it < 50; ++it) {
      const Eigen::Vector2d r = res(q);
      if (r.norm() < 1e-14 * (1 + F.norm())) break;
      Eigen::Matrix2d H;
      for (int j = 0; j < 2; ++j) {
        Eigen::Vector2d e = Eigen::Vector2d::Zero();
        e[j] = 1e-6;
        H.col(j) = (res(q + e) - res(q - e)) / 2e-6;
      }
      q -= H.inverse() * r;
    }
    return q;
  }
};

inline json five_bar_model(const FiveBar& fb, bool ground_link = false) {
  const Eigen::Vector2d A1 = fb.A(0), A2 = fb.A(1), B1 = fb.B(0, fb.q1), B2 = fb.B(1, fb.q2), E = fb.E(fb.q1, fb.q2);
  json d;
  d["nodes"] = json::array();
  auto node = [&](const std::string& id, const Eigen::Vector2d& p) { d["nodes"].push_back({{"id", id}, {"xyz", xyz(p.x(), p.y())}}); };
  node("A1", A1); node("A1p", A1); node("B1", B1); node("B1p", B1);
  node("A2", A2); node("A2p", A2); node("B2", B2); node("B2p", B2);
  node("E", E); node("Ep", E);
  const json z = json::array({0, 0, 1});
  d["elements"] = json::array({{{"id", "prox1"}, {"type", "rigid"}, {"nodes", {"A1p", "B1"}}},
                               {{"id", "dist1"}, {"type", "rigid"}, {"nodes", {"B1p", "E"}}},
                               {{"id", "prox2"}, {"type", "rigid"}, {"nodes", {"A2p", "B2"}}},
                               {{"id", "dist2"}, {"type", "rigid"}, {"nodes", {"B2p", "Ep"}}}});
  d["joints"] = json::array(
      {{{"id", "act1"}, {"type", "revolute"}, {"nodes", {"A1", "A1p"}}, {"axes", {z}}, {"stiffness", {fb.k1}}},
       {{"id", "act2"}, {"type", "revolute"}, {"nodes", {"A2", "A2p"}}, {"axes", {z}}, {"stiffness", {fb.k2}}},
       {{"id", "pB1"}, {"type", "revolute"}, {"nodes", {"B1", "B1p"}}, {"axes", {z}}},
       {{"id", "pB2"}, {"type", "revolute"}, {"nodes", {"B2", "B2p"}}, {"axes", {z}}},
       {{"id", "pE"}, {"type", "revolute"}, {"nodes", {"E", "Ep"}}, {"axes", {z}}}});
  d["supports"] = json::array({fix("A1", {"ux", "uy", "uz", "rx", "ry", "rz"})});
  if (ground_link) {
    d["elements"].push_back({{"id", "ground"}, {"type", "rigid"}, {"nodes", {"A1", "A2"}}});
  } else {
    d["supports"].push_back(fix("A2", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  }
  d["loads"] = json::array();
  return d;
}

// Sway frame: two rigid columns of height h on revolute base springs k (about z) at x = 0 and x = w,
// tied at the top by a rigid beam pinned (revolute z) to both column tops; a vertical load -P on each
// column top. Energy 2 (k th^2 / 2) - 2 P h (1 - cos th): buckling at P = k / h, post-buckling
// P = k th / (h sin th), stable (Bazant & Cedolin 1991, sec. 1.2, the rigid-bar column on a spring).
// Both bases fixed (the loop closes through the ground), or with `ground_link` only G1 fixed and a
// rigid link G1-G2 (the loop closes at the rigid beam).
inline json sway_frame_model(double h, double w, double k, double P, bool ground_link = false) {
  json d;
  d["nodes"] = json::array({{{"id", "G1"}, {"xyz", xyz(0, 0)}}, {{"id", "B1"}, {"xyz", xyz(0, 0)}},
                            {{"id", "T1"}, {"xyz", xyz(0, h)}}, {{"id", "T1b"}, {"xyz", xyz(0, h)}},
                            {{"id", "G2"}, {"xyz", xyz(w, 0)}}, {{"id", "B2"}, {"xyz", xyz(w, 0)}},
                            {{"id", "T2"}, {"xyz", xyz(w, h)}}, {{"id", "T2b"}, {"xyz", xyz(w, h)}}});
  const json z = json::array({0, 0, 1});
  d["elements"] = json::array({{{"id", "col1"}, {"type", "rigid"}, {"nodes", {"B1", "T1"}}},
                               {{"id", "col2"}, {"type", "rigid"}, {"nodes", {"B2", "T2"}}},
                               {{"id", "beam"}, {"type", "rigid"}, {"nodes", {"T1b", "T2b"}}}});
  d["joints"] = json::array({{{"id", "base1"}, {"type", "revolute"}, {"nodes", {"G1", "B1"}}, {"axes", {z}}, {"stiffness", {k}}},
                             {{"id", "base2"}, {"type", "revolute"}, {"nodes", {"G2", "B2"}}, {"axes", {z}}, {"stiffness", {k}}},
                             {{"id", "pin1"}, {"type", "revolute"}, {"nodes", {"T1", "T1b"}}, {"axes", {z}}},
                             {{"id", "pin2"}, {"type", "revolute"}, {"nodes", {"T2", "T2b"}}, {"axes", {z}}}});
  d["supports"] = json::array({fix("G1", {"ux", "uy", "uz", "rx", "ry", "rz"})});
  if (ground_link) {
    d["elements"].push_back({{"id", "ground"}, {"type", "rigid"}, {"nodes", {"G1", "G2"}}});
  } else {
    d["supports"].push_back(fix("G2", {"ux", "uy", "uz", "rx", "ry", "rz"}));
  }
  d["loads"] = json::array({load("T1", 0, -P, 0), load("T2", 0, -P, 0)});
  return d;
}

}  // namespace beamfea::test
