// What a load case does to an actuation scheme (solvers/actuator_load_case.hpp), against closed
// forms: actuator efforts from planar statics and from the closed-form Jacobian of a 2R arm
// (tau = -J^T W for a platform wrench W; Craig, Introduction to Robotics, 3rd ed., eq. 5.105 with
// F = -W), the platform displacement of the frozen arm by the unit-load method, and the loaded
// stiffness of a column on a base spring under a tip weight against the exact beam-column
// solution (derived below from the beam-column equation of Timoshenko & Gere, Theory of Elastic
// Stability, 2nd ed., chapter 1).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "io/model_reader.hpp"
#include "solvers/actuator_allocation.hpp"
#include "solvers/actuator_load_case.hpp"

namespace beamfea::actuator_load_case_test {
namespace {

using json = nlohmann::json;

// 2R planar arm in the x-y plane: J1 at the origin (ground G, link base A), link 1 (length L1, at
// angle t1) to the elbow (E1 end of link 1, E2 start of link 2, joint J2), link 2 (L2, absolute
// angle t1 + t2) to the tip T. Steel tube-like circle r = 0.02 m, density 7850, 4 divisions each.
// Point masses: elbow motor m1 on E1, payload m2 on T. Cases: "dead" (gravity -y), "tool" (a tip
// force), combination "uls" = 1.35 dead + 1.5 tool.
constexpr double L1 = 0.8, L2 = 0.6, t1 = 0.5, t2 = 0.9, kG = 9.81, m1 = 3.0, m2 = 2.0;
constexpr double kE = 2.1e11, kNu = 0.3, kR = 0.02, kRho = 7850.0;
const double kFx = 12.0, kFy = -30.0;

json arm() {
  const double ex = L1 * std::cos(t1), ey = L1 * std::sin(t1);
  const double tx = ex + L2 * std::cos(t1 + t2), ty = ey + L2 * std::sin(t1 + t2);
  return {{"nodes", {{{"id", "G"}, {"xyz", {0, 0, 0}}}, {{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "E1"}, {"xyz", {ex, ey, 0}}},
                     {{"id", "E2"}, {"xyz", {ex, ey, 0}}}, {{"id", "T"}, {"xyz", {tx, ty, 0}}}}},
          {"materials", {{{"id", "steel"}, {"E", kE}, {"nu", kNu}, {"density", kRho}}}},
          {"sections", {{{"id", "s"}, {"shape", "circle"}, {"r", kR}}}},
          {"elements", {{{"id", "L1"}, {"type", "beam"}, {"nodes", {"A", "E1"}}, {"material", "steel"}, {"section", "s"},
                         {"orientation", {0, 0, 1}}, {"divisions", 4}},
                        {{"id", "L2"}, {"type", "beam"}, {"nodes", {"E2", "T"}}, {"material", "steel"}, {"section", "s"},
                         {"orientation", {0, 0, 1}}, {"divisions", 4}}}},
          {"joints", {{{"id", "J1"}, {"type", "revolute"}, {"nodes", {"G", "A"}}, {"axes", {{0, 0, 1}}}},
                      {{"id", "J2"}, {"type", "revolute"}, {"nodes", {"E1", "E2"}}, {"axes", {{0, 0, 1}}}}}},
          {"supports", {{{"node", "G"}, {"fix", "all"}}}},
          {"masses", {{{"node", "E1"}, {"mass", m1}}, {{"node", "T"}, {"mass", m2}}}},
          {"load_cases", {{{"id", "dead"}, {"gravity", {0, -kG, 0}}},
                          {{"id", "tool"}, {"loads", {{{"node", "T"}, {"force", {kFx, kFy, 0}}}}}}}},
          {"combinations", {{{"id", "uls"}, {"factors", {{"dead", 1.35}, {"tool", 1.5}}}}}}};
}

AllocationOptions arm_options(const Model& m, double k1, double k2) {
  AllocationOptions o;
  o.platform_node = m.find_node("T");
  o.directions = {0, 1};  // ux uy
  o.candidates = {{m.find_joint("J1"), 0}, {m.find_joint("J2"), 0}};
  o.actuator_stiffness = {k1, k2};
  return o;
}

// Closed-form efforts: tau_i = -(sum over the loads outboard of joint i of the moment about the
// joint, z component), i.e. the torque the motor applies to hold them.
struct PlanarLoad {
  double x, y, fx, fy;
  int link;  // 1: outboard of J1 only, 2: outboard of J1 and J2
};
Eigen::Vector2d efforts_by_statics(const std::vector<PlanarLoad>& loads) {
  const double ex = L1 * std::cos(t1), ey = L1 * std::sin(t1);
  Eigen::Vector2d tau = Eigen::Vector2d::Zero();
  for (const auto& l : loads) {
    tau[0] -= l.x * l.fy - l.y * l.fx;
    if (l.link == 2) tau[1] -= (l.x - ex) * l.fy - (l.y - ey) * l.fx;
  }
  return tau;
}

std::vector<PlanarLoad> weights(double factor) {
  const double A = M_PI * kR * kR, q = kRho * A * kG;
  const double ex = L1 * std::cos(t1), ey = L1 * std::sin(t1);
  const double tx = ex + L2 * std::cos(t1 + t2), ty = ey + L2 * std::sin(t1 + t2);
  // A uniform link weight acts at the link's midpoint.
  return {{ex / 2, ey / 2, 0, -factor * q * L1, 1},
          {ex, ey, 0, -factor * m1 * kG, 1},
          {(ex + tx) / 2, (ey + ty) / 2, 0, -factor * q * L2, 2},
          {tx, ty, 0, -factor * m2 * kG, 2}};
}

// Efforts agree with statics to rounding of the FEA solve (a determinate frozen arm).
constexpr double kEffortTolerance = 1e-9;

TEST(ActuatorLoadCase, EffortsOfATipForceAreMinusJacobianTransposeTimesTheForce) {
  const Model model = read_model(arm());
  const auto o = arm_options(model, 1e4, 5e3);
  const SchemeLoadResponse r = scheme_load_response(model, o, {0, 1}, model.loads_for("tool"));
  ASSERT_TRUE(r.efforts_ok) << r.efforts_message;
  // Closed-form Jacobian of the 2R arm (Craig eq. 5.66 in the base frame): columns d(tip)/dq_i.
  const double s1 = std::sin(t1), c1 = std::cos(t1), s12 = std::sin(t1 + t2), c12 = std::cos(t1 + t2);
  Eigen::Matrix2d J;
  J << -L1 * s1 - L2 * s12, -L2 * s12, L1 * c1 + L2 * c12, L2 * c12;
  const Eigen::Vector2d W(kFx, kFy);
  const Eigen::Vector2d tau = -J.transpose() * W;
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(r.efforts[i], tau[i], kEffortTolerance * tau.norm()) << "actuator " << i;
  // The same from statics, as a check of the closed form itself.
  const double tx = L1 * c1 + L2 * c12, ty = L1 * s1 + L2 * s12;
  const Eigen::Vector2d st = efforts_by_statics({{tx, ty, kFx, kFy, 2}});
  EXPECT_NEAR((st - tau).norm(), 0.0, 1e-12 * tau.norm());
  // Rigid links and springs: the springs turn by q = -K_I^-1 tau, the platform by J q.
  ASSERT_TRUE(r.actuated.ok) << r.actuated.message;
  const Eigen::Vector2d q(-tau[0] / 1e4, -tau[1] / 5e3);
  const Eigen::Vector2d u = J * q;
  EXPECT_NEAR(r.actuated.platform[0], u[0], 1e-9 * u.norm());
  EXPECT_NEAR(r.actuated.platform[1], u[1], 1e-9 * u.norm());
  EXPECT_NEAR(r.actuated.platform[5], q.sum(), 1e-9 * q.norm());
}

TEST(ActuatorLoadCase, EffortsUnderOwnWeightPointMassesAndACombinationMatchStatics) {
  const Model model = read_model(arm());
  const auto o = arm_options(model, 1e4, 5e3);
  // Self-weight (density x A x g) of both links and the two point masses.
  const SchemeLoadResponse dead = scheme_load_response(model, o, {0, 1}, model.loads_for("dead"));
  ASSERT_TRUE(dead.efforts_ok) << dead.efforts_message;
  const Eigen::Vector2d tau_dead = efforts_by_statics(weights(1.0));
  for (int i = 0; i < 2; ++i)
    EXPECT_NEAR(dead.efforts[i], tau_dead[i], kEffortTolerance * tau_dead.norm()) << "actuator " << i;
  // The motor of J1 lifts the arm: a positive (counter-clockwise) torque for an arm reaching +x.
  EXPECT_GT(dead.efforts[0], 0.0);
  // uls = 1.35 dead + 1.5 tool.
  const SchemeLoadResponse uls = scheme_load_response(model, o, {0, 1}, model.loads_for("uls"));
  ASSERT_TRUE(uls.efforts_ok);
  auto loads = weights(1.35);
  const double tx = L1 * std::cos(t1) + L2 * std::cos(t1 + t2), ty = L1 * std::sin(t1) + L2 * std::sin(t1 + t2);
  loads.push_back({tx, ty, 1.5 * kFx, 1.5 * kFy, 2});
  const Eigen::Vector2d tau_uls = efforts_by_statics(loads);
  for (int i = 0; i < 2; ++i)
    EXPECT_NEAR(uls.efforts[i], tau_uls[i], kEffortTolerance * tau_uls.norm()) << "actuator " << i;
  // The rigid-link model carries the links' weight through nodal equivalents: same statics.
  ASSERT_TRUE(dead.actuated.ok) << dead.actuated.message;
  const double rz = dead.actuated.platform[5];
  EXPECT_NEAR(rz, -tau_dead[0] / 1e4 - tau_dead[1] / 5e3, 1e-9 * std::abs(rz));
  // Frozen arm: determinate, so total = structural + actuated (compliances in series).
  ASSERT_TRUE(dead.total.ok && dead.structural.ok);
  const Vec6 sum = dead.structural.platform + dead.actuated.platform;
  EXPECT_LT((dead.total.platform - sum).norm(), 1e-8 * dead.total.platform.norm());
}

TEST(ActuatorLoadCase, FrozenLShapedArmDeflectsAsTheUnitLoadMethodSays) {
  // t1 = 0, t2 = 90 degrees: link 1 along x, link 2 along y; tip force Fx; massless (tool case).
  json doc = arm();
  doc["nodes"][2]["xyz"] = {L1, 0, 0};
  doc["nodes"][3]["xyz"] = {L1, 0, 0};
  doc["nodes"][4]["xyz"] = {L1, L2, 0};
  const Model model = read_model(doc);
  const auto o = arm_options(model, 1e4, 5e3);
  const SchemeLoadResponse r = scheme_load_response(model, o, {0, 1}, model.loads_for("tool"));
  ASSERT_TRUE(r.structural.ok) << r.structural.message;
  // Unit load in x at the tip of the frozen L frame: link 2 bends with m = L2 - y, link 1 with
  // m = L2 and stretches with N = 1: dx/Fx = (L2^3/3 + L2^2 L1)/EI + L1/EA; dy/Fy likewise.
  const double A = M_PI * kR * kR, I = M_PI * std::pow(kR, 4) / 4;
  const double cxx = (L2 * L2 * L2 / 3 + L2 * L2 * L1) / (kE * I) + L1 / (kE * A);
  const double cyy = (L1 * L1 * L1 / 3) / (kE * I) + L2 / (kE * A);
  const double cxy = -(L2 * L1 * L1 / 2) / (kE * I);  // unit Fx bends link 1 the other way
  const double ux = cxx * kFx + cxy * kFy, uy = cxy * kFx + cyy * kFy;
  EXPECT_NEAR(r.structural.platform[0], ux, 1e-9 * std::hypot(ux, uy));
  EXPECT_NEAR(r.structural.platform[1], uy, 1e-9 * std::hypot(ux, uy));
}

// Column of length H on a base revolute with a spring k (the one actuator), a tip mass m under
// gravity -y: compression P = m g. Exact lateral tip stiffness (linear beam-column, constant P,
// mu^2 = P/EI): EI w'' = H (L - x) + P (delta - w), w(0) = 0, w'(0) = (H L + P delta)/k, w(L) =
// delta give K = P / (1 / (mu cot(mu L) - P/k) - L); k -> infinity: P / (tan(mu L)/mu - L) (the
// frozen structure); EI -> infinity: (k - P L) / L^2 (the rigid inverted pendulum).
json column(double Lc, double mass, int divisions) {
  return {{"nodes", {{{"id", "G"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {0, 0, 0}}}, {{"id", "T"}, {"xyz", {0, Lc, 0}}}}},
          {"materials", {{{"id", "steel"}, {"E", kE}, {"nu", kNu}}}},
          {"sections", {{{"id", "s"}, {"shape", "circle"}, {"r", kR}}}},
          {"elements", {{{"id", "C"}, {"type", "beam"}, {"nodes", {"B", "T"}}, {"material", "steel"}, {"section", "s"},
                         {"orientation", {0, 0, 1}}, {"divisions", divisions}}}},
          {"joints", {{{"id", "J"}, {"type", "revolute"}, {"nodes", {"G", "B"}}, {"axes", {{0, 0, 1}}}}}},
          {"supports", {{{"node", "G"}, {"fix", "all"}}}},
          {"masses", {{{"node", "T"}, {"mass", mass}}}},
          {"load_cases", {{{"id", "payload"}, {"gravity", {0, -kG, 0}}}}}};
}

double beam_column_tip_stiffness(double P, double EI, double Lc, double k) {
  const double mu = std::sqrt(P / EI);
  const double a = k > 0.0 ? mu / std::tan(mu * Lc) - P / k : mu / std::tan(mu * Lc);
  return P / (1.0 / a - Lc);
}

TEST(ActuatorLoadCase, LoadedStiffnessOfAColumnOnASpringMatchesTheExactBeamColumn) {
  const double Lc = 1.0, I = M_PI * std::pow(kR, 4) / 4, EI = kE * I;
  const double Pcr = M_PI * M_PI * EI / (4 * Lc * Lc);  // Euler, cantilever
  const double P = 0.3 * Pcr, mass = P / kG;
  const double k = 3.0 * P * Lc;  // the rigid inverted pendulum keeps 2/3 of its spring
  const Model model = read_model(column(Lc, mass, 16));
  AllocationOptions o;
  o.platform_node = model.find_node("T");
  o.directions = {0};  // ux
  o.candidates = {{model.find_joint("J"), 0}};
  o.actuator_stiffness = {k};
  const SchemeLoadResponse r = scheme_load_response(model, o, {0}, model.loads_for("payload"));
  ASSERT_TRUE(r.actuated.stiffness_ok) << r.actuated.stiffness_message;
  ASSERT_TRUE(r.structural.stiffness_ok) << r.structural.stiffness_message;
  ASSERT_TRUE(r.total.stiffness_ok) << r.total.stiffness_message;
  // Rigid links: exact (one rigid link, the constraint curvature of the tip load).
  EXPECT_NEAR(r.actuated.K_loaded(0, 0), (k - P * Lc) / (Lc * Lc), 1e-9 * k / (Lc * Lc));
  // Beams: K + K_g with 16 cubic elements; the exact second-order stiffness (errors 1.7e-8, 1.3e-8).
  const double Ks = beam_column_tip_stiffness(P, EI, Lc, 0.0), Kt = beam_column_tip_stiffness(P, EI, Lc, k);
  std::printf("column P = 0.3 P_cr, 16 elements: loaded stiffness errors frozen %.2e, sprung %.2e, rigid %.2e\n",
              r.structural.K_loaded(0, 0) / Ks - 1, r.total.K_loaded(0, 0) / Kt - 1,
              r.actuated.K_loaded(0, 0) / ((k - P * Lc) / (Lc * Lc)) - 1);
  EXPECT_NEAR(r.structural.K_loaded(0, 0), Ks, 1e-6 * Ks);
  EXPECT_NEAR(r.total.K_loaded(0, 0), Kt, 1e-6 * Kt);
  // The preload softens: the unloaded frozen cantilever is 3EI/L^3.
  EXPECT_LT(r.structural.K_loaded(0, 0), 3 * EI / (Lc * Lc * Lc));
  // No lateral load: no effort, and the column only shortens.
  ASSERT_TRUE(r.efforts_ok);
  EXPECT_NEAR(r.efforts[0], 0.0, 1e-9 * P * Lc);
  EXPECT_NEAR(r.total.platform[1], -P * Lc / (kE * M_PI * kR * kR), 1e-9 * P * Lc / (kE * M_PI * kR * kR));
}

}  // namespace
}  // namespace beamfea::actuator_load_case_test

namespace beamfea::actuator_load_case_test {
namespace {

// Five-bar (a closed loop): bases A1 = (-0.3, 0), A2 = (0.3, 0), proximal links l1 = 0.5 driven
// at the bases, distal links l2 = 0.7 meeting at the platform point P = (0.05, 0.8) in a passive
// revolute joint; elbows outward. Closed-form velocity kinematics: from |P - B_i| = l2,
// (P - B_i) . (dP - dB_i) = 0 with dB_i = dq_i z x (B_i - A_i), so A dP = D dq with rows
// A_i = (P - B_i)^T and D_ii = (P - B_i) . (z x (B_i - A_i)): J = A^-1 D (derived here from the
// loop-closure constraints). The frozen structure (bases clamped) is determinate in the plane: the
// efforts are exactly -J^T F for a platform force F.
struct FiveBar {
  Eigen::Vector2d A1{-0.3, 0.0}, A2{0.3, 0.0}, P{0.05, 0.8}, B1, B2;
  double l1 = 0.5, l2 = 0.7;
  FiveBar() {
    auto elbow = [&](const Eigen::Vector2d& A, bool left) {
      const double d = (P - A).norm(), a = (l1 * l1 - l2 * l2 + d * d) / (2 * d), h = std::sqrt(l1 * l1 - a * a);
      const Eigen::Vector2d m = A + a * (P - A) / d, n = Eigen::Vector2d(-(P - A).y(), (P - A).x()) / d;
      const Eigen::Vector2d p = m + h * n, q = m - h * n;
      return (p.x() < q.x()) == left ? p : q;
    };
    B1 = elbow(A1, true);
    B2 = elbow(A2, false);
  }
  Eigen::Matrix2d jacobian() const {
    Eigen::Matrix2d A, D = Eigen::Matrix2d::Zero();
    const Eigen::Vector2d B[2] = {B1, B2}, Ab[2] = {A1, A2};
    for (int i = 0; i < 2; ++i) {
      A.row(i) = (P - B[i]).transpose();
      const Eigen::Vector2d r = B[i] - Ab[i];
      D(i, i) = (P - B[i]).dot(Eigen::Vector2d(-r.y(), r.x()));  // z x r
    }
    return A.inverse() * D;
  }
  json model() const {
    auto xyz = [](const Eigen::Vector2d& p) { return json{p.x(), p.y(), 0.0}; };
    auto beam = [](const char* id, const char* a, const char* b) {
      return json{{"id", id}, {"type", "beam"}, {"nodes", {a, b}}, {"material", "steel"}, {"section", "s"},
                  {"orientation", {0, 0, 1}}, {"divisions", 2}};
    };
    auto rev = [](const char* id, const char* a, const char* b) {
      return json{{"id", id}, {"type", "revolute"}, {"nodes", {a, b}}, {"axes", {{0, 0, 1}}}};
    };
    return {{"nodes", {{{"id", "G1"}, {"xyz", xyz(A1)}}, {{"id", "A1"}, {"xyz", xyz(A1)}}, {{"id", "B1a"}, {"xyz", xyz(B1)}},
                       {{"id", "B1b"}, {"xyz", xyz(B1)}}, {{"id", "P1"}, {"xyz", xyz(P)}}, {{"id", "G2"}, {"xyz", xyz(A2)}},
                       {{"id", "A2"}, {"xyz", xyz(A2)}}, {{"id", "B2a"}, {"xyz", xyz(B2)}}, {{"id", "B2b"}, {"xyz", xyz(B2)}},
                       {{"id", "P2"}, {"xyz", xyz(P)}}}},
            {"materials", {{{"id", "steel"}, {"E", kE}, {"nu", kNu}}}},
            {"sections", {{{"id", "s"}, {"shape", "circle"}, {"r", kR}}}},
            {"elements", {beam("L1", "A1", "B1a"), beam("D1", "B1b", "P1"), beam("L2", "A2", "B2a"), beam("D2", "B2b", "P2")}},
            {"joints", {rev("Q1", "G1", "A1"), rev("E1", "B1a", "B1b"), rev("Q2", "G2", "A2"), rev("E2", "B2a", "B2b"),
                        rev("JP", "P1", "P2")}},
            {"supports", {{{"node", "G1"}, {"fix", "all"}}, {{"node", "G2"}, {"fix", "all"}}}},
            {"load_cases", {{{"id", "tool"}, {"loads", {{{"node", "P1"}, {"force", {kFx, kFy, 0}}}}}}}}};
  }
};

TEST(ActuatorLoadCase, FiveBarEffortsAreMinusJacobianTransposeTimesThePlatformForce) {
  const FiveBar fb;
  const Model model = read_model(fb.model());
  AllocationOptions o;
  o.platform_node = model.find_node("P1");
  o.directions = {0, 1};
  o.candidates = {{model.find_joint("Q1"), 0}, {model.find_joint("Q2"), 0}};
  o.actuator_stiffness = {2e3, 2e3};
  const Eigen::Matrix2d J = fb.jacobian();
  // beamfea's own Jacobian (rigid links, constraints alone) against the closed form.
  const ActuatedStiffness a = actuated_stiffness(model, o, {0, 1});
  ASSERT_TRUE(a.jacobian_ok) << a.jacobian_message;
  EXPECT_LT((a.J - J).cwiseAbs().maxCoeff(), 1e-9 * J.cwiseAbs().maxCoeff());
  const SchemeLoadResponse r = scheme_load_response(model, o, {0, 1}, model.loads_for("tool"));
  ASSERT_TRUE(r.efforts_ok) << r.efforts_message;
  const Eigen::Vector2d tau = -J.transpose() * Eigen::Vector2d(kFx, kFy);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(r.efforts[i], tau[i], kEffortTolerance * tau.norm()) << "actuator " << i;
  // Springs with rigid links: the platform moves by J q, q = -K_I^-1 tau.
  const Eigen::Vector2d u = J * (-tau / 2e3);
  ASSERT_TRUE(r.actuated.ok) << r.actuated.message;
  EXPECT_NEAR(r.actuated.platform[0], u[0], 1e-9 * u.norm());
  EXPECT_NEAR(r.actuated.platform[1], u[1], 1e-9 * u.norm());
}

}  // namespace
}  // namespace beamfea::actuator_load_case_test
