// The prismatic joint (one sliding coordinate along an axis carried by its first node's body) in
// every analysis, run end to end from model documents, against closed forms:
//   - a slider with a spring k between two collinear beams: the tip compliance is the cantilever's
//     (total length) plus a a^T / k along the slider's axis a (the slider moves the outer beam
//     rigidly by a q, q = a.f / k), nothing across;
//   - an actuator force F on the coordinate slides it by F / k; a prescribed slide d between two
//     held beams compresses them by d (bars in series);
//   - a mass m on a prismatic spring k: omega = sqrt(k / m);
//   - a column pinned at its foot whose head is held sideways by a prismatic spring k: the sway
//     mode is a rigid rotation and P_cr = k L exactly while k L < pi^2 EI / L^2 (Timoshenko & Gere,
//     Theory of Elastic Stability, 2nd ed., sec. 2.2, the column with an elastic lateral support);
//   - a rigid arm on a revolute spring kr whose slider (spring k) carries a tip at r = L + q under a
//     large dead force F along y (exact kinematics): F r cos(theta) = kr theta and
//     F sin(theta) = k q, solved here by Newton's method.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "io/run.hpp"
#include "support/models.hpp"

namespace prismatic_joint_test {

using nlohmann::json;

constexpr double E = 2.1e11, G = 8.0e10, A = 1.0e-3, Iy = 2.0e-6, Iz = 3.0e-6, J = 4.0e-6;

beamfea::ojson run_analysis(const json& doc) {
  const beamfea::Model model = beamfea::load_and_check(doc);
  const beamfea::RunReport report = beamfea::run_document(model, doc, {});
  EXPECT_FALSE(report.failed);
  return report.results["analyses"];
}

// Beam A-B (A clamped) of length L1 along x, a slider B-C along `axis` with stiffness k, beam C-D
// of length L2 along x.
json slider_between_beams(double L1, double L2, const std::array<double, 3>& axis, double k) {
  json doc = beamfea::test::cantilever(L1, E, G, A, Iy, Iz, J);
  doc["nodes"].push_back({{"id", "C"}, {"xyz", {L1, 0, 0}}});
  doc["nodes"].push_back({{"id", "D"}, {"xyz", {L1 + L2, 0, 0}}});
  doc["elements"].push_back({{"id", "e2"}, {"type", "beam"}, {"nodes", {"C", "D"}}, {"material", "m"}, {"section", "s"},
                             {"orientation", {0, 0, 1}}});
  doc["joints"] = json::array({{{"id", "slide"}, {"type", "prismatic"}, {"nodes", {"B", "C"}},
                                {"axes", {{axis[0], axis[1], axis[2]}}}, {"stiffness", {k}}}});
  return doc;
}

TEST(PrismaticJoint, SliderSpringAddsItsComplianceAlongTheAxisOnly) {
  const double L1 = 1.2, L2 = 0.8, L = L1 + L2, k = 2.0e5;
  const double c30 = std::cos(M_PI / 6), s30 = std::sin(M_PI / 6);
  json doc = slider_between_beams(L1, L2, {c30, s30, 0.0}, k);
  doc["analyses"] = json::array({{{"id", "k"}, {"type", "stiffness"}, {"node", "D"}}});
  const beamfea::ojson r = run_analysis(doc)["k"];
  ASSERT_EQ(r["status"], "ok") << r.dump();
  // Cantilever of length L (Euler-Bernoulli): ux L/(EA), uy L^3/(3 E Iz), uz L^3/(3 E Iy); plus
  // a a^T / k, a = (cos 30, sin 30, 0).
  const double a[3] = {c30, s30, 0.0};
  const double beam[3] = {L / (E * A), L * L * L / (3 * E * Iz), L * L * L / (3 * E * Iy)};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double want = (i == j ? beam[i] : 0.0) + a[i] * a[j] / k;
      EXPECT_NEAR(r["compliance"][i][j].get<double>(), want, 1e-9 * (1.0 / k)) << i << "," << j;
    }
  // Rotations do not slide: the tip's rotational compliance about z is the cantilever's L/(E Iz).
  EXPECT_NEAR(r["compliance"][5][5].get<double>(), L / (E * Iz), 1e-9 * L / (E * Iz));
}

TEST(PrismaticJoint, ActuatorForceSlidesByForceOverStiffnessAndAPrescribedSlideMovesTheTip) {
  const double L1 = 1.0, L2 = 1.0, k = 5.0e4, F = 30.0, d = 0.01;
  json doc = slider_between_beams(L1, L2, {1.0, 0.0, 0.0}, k);
  doc["loads"] = json::array({{{"joint", "slide"}, {"coordinate", 0}, {"value", F}}});
  doc["analyses"] = json::array({{{"id", "lin"}, {"type", "linear_static"}}});
  const beamfea::ojson r = run_analysis(doc)["lin"];
  ASSERT_EQ(r["status"], "ok") << r.dump();
  // The outer beam is free: the actuator force F only works against the spring, q = F / k; the
  // tip moves by q along x, the clamped beam carries nothing.
  EXPECT_NEAR(r["joints"]["slide"]["coordinates"][0].get<double>(), F / k, 1e-10 * F / k);
  EXPECT_NEAR(r["nodes"]["D"]["displacement"][0].get<double>(), F / k, 1e-10 * F / k);
  EXPECT_NEAR(r["nodes"]["B"]["displacement"][0].get<double>(), 0.0, 1e-12);

  // A prescribed slide d between the clamped beam and the outer beam whose end D is held along x:
  // the slide compresses both beams (equal EA) by N = EA d / (L1 + L2); B moves back by N L1/(EA).
  // The coordinate's reaction is the force the structure puts on it, N (its own spring's k d is
  // in parallel and not part of it).
  json doc2 = slider_between_beams(L1, L2, {1.0, 0.0, 0.0}, k);
  doc2["supports"].push_back({{"node", "D"}, {"fix", {"ux"}}});
  doc2["prescribed"] = json::array({{{"joint", "slide"}, {"coordinate", 0}, {"value", d}}});
  doc2["analyses"] = json::array({{{"id", "lin"}, {"type", "linear_static"}}});
  const beamfea::ojson r2 = run_analysis(doc2)["lin"];
  ASSERT_EQ(r2["status"], "ok") << r2.dump();
  const double N = E * A * d / (L1 + L2);
  EXPECT_NEAR(r2["joints"]["slide"]["coordinates"][0].get<double>(), d, 1e-12);
  EXPECT_NEAR(r2["nodes"]["B"]["displacement"][0].get<double>(), -N * L1 / (E * A), 1e-9 * d);
  EXPECT_NEAR(r2["nodes"]["D"]["displacement"][0].get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(r2["joints"]["slide"]["reaction"][0].get<double>(), N, 1e-9 * N);
}

TEST(PrismaticJoint, MassOnAPrismaticSpringVibratesAtSqrtKOverM) {
  const double k = 4.0e3, m = 2.5;
  json doc = {{"nodes", {{{"id", "G"}, {"xyz", {0, 0, 0}}}, {{"id", "P"}, {"xyz", {0, 0, 0}}}}},
              {"joints", {{{"id", "s"}, {"type", "prismatic"}, {"nodes", {"G", "P"}}, {"axes", {{0, 0.6, 0.8}}}, {"stiffness", {k}}}}},
              {"supports", {{{"node", "G"}, {"fix", "all"}}}},
              {"masses", {{{"node", "P"}, {"mass", m}}}},
              {"analyses", {{{"id", "m"}, {"type", "modal"}, {"modes", 1}}}}};
  const beamfea::ojson r = run_analysis(doc)["m"];
  ASSERT_EQ(r["status"], "ok") << r.dump();
  const double f = std::sqrt(k / m) / (2 * M_PI);
  EXPECT_NEAR(r["frequencies"][0].get<double>(), f, 1e-9 * f);
}

TEST(PrismaticJoint, ColumnHeldSidewaysByAPrismaticSpringBucklesAtKL) {
  // Column A-T along y, pinned at A (rz free), loaded by -P at T. T's head is held by a chain of
  // joints from the ground S: a prismatic spring along x (k), a passive slider along y and a
  // passive revolute about z, so the spring acts on T's sway alone.
  const double L = 3.0, k = 1.0e4, Ec = 2.0e11;
  const double I = 10.0 * k * L * L * L / (M_PI * M_PI * Ec);  // Euler load pi^2 E I / L^2 = 10 k L
  json doc = {{"nodes", {{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "T"}, {"xyz", {0, L, 0}}}, {{"id", "S"}, {"xyz", {0, L, 0}}},
                         {{"id", "S1"}, {"xyz", {0, L, 0}}}, {{"id", "S2"}, {"xyz", {0, L, 0}}}}},
              {"materials", {{{"id", "m"}, {"E", Ec}, {"G", Ec / 2.6}}}},
              {"sections", {{{"id", "s"}, {"A", 1e-2}, {"Iy", 100 * I}, {"Iz", I}, {"J", 100 * I}}}},
              {"elements", {{{"id", "col"}, {"type", "beam"}, {"nodes", {"A", "T"}}, {"material", "m"}, {"section", "s"},
                             {"orientation", {1, 0, 0}}, {"divisions", 4}}}},
              {"joints", {{{"id", "spring"}, {"type", "prismatic"}, {"nodes", {"S", "S1"}}, {"axes", {{1, 0, 0}}}, {"stiffness", {k}}},
                          {{"id", "guide"}, {"type", "prismatic"}, {"nodes", {"S1", "S2"}}, {"axes", {{0, 1, 0}}}},
                          {{"id", "pin"}, {"type", "revolute"}, {"nodes", {"S2", "T"}}, {"axes", {{0, 0, 1}}}}}},
              {"supports", {{{"node", "A"}, {"fix", {"ux", "uy", "uz", "rx", "ry"}}}, {{"node", "S"}, {"fix", "all"}}}},
              {"loads", {{{"node", "T"}, {"force", {0, -1.0, 0}}}}},
              {"analyses", {{{"id", "b"}, {"type", "buckling"}, {"modes", 1}}}}};
  const beamfea::ojson r = run_analysis(doc)["b"];
  ASSERT_EQ(r["status"], "ok") << r.dump();
  EXPECT_NEAR(r["load_factors"][0].get<double>(), k * L, 1e-6 * k * L);
}

TEST(PrismaticJoint, SliderOnARotatingArmFollowsExactKinematicsOnAPath) {
  // Ground O, revolute about z (spring kr) to O2, slider along the arm's x (spring k) to P, a rigid
  // link P-T of length L along x. Dead force F along +y at T.
  const double L = 1.0, kr = 100.0, k = 200.0, F = 60.0;
  json doc = {{"nodes", {{{"id", "O"}, {"xyz", {0, 0, 0}}}, {{"id", "O2"}, {"xyz", {0, 0, 0}}}, {{"id", "P"}, {"xyz", {0, 0, 0}}},
                         {{"id", "T"}, {"xyz", {L, 0, 0}}}}},
              {"elements", {{{"id", "arm"}, {"type", "rigid"}, {"nodes", {"P", "T"}}}}},
              {"joints", {{{"id", "hinge"}, {"type", "revolute"}, {"nodes", {"O", "O2"}}, {"axes", {{0, 0, 1}}}, {"stiffness", {kr}}},
                          {{"id", "slide"}, {"type", "prismatic"}, {"nodes", {"O2", "P"}}, {"axes", {{1, 0, 0}}}, {"stiffness", {k}}}}},
              {"supports", {{{"node", "O"}, {"fix", "all"}}}},
              {"loads", {{{"node", "T"}, {"force", {0, F, 0}}}}},
              {"analyses", {{{"id", "p"}, {"type", "path"}, {"track", {"T"}}, {"stability", false},
                             {"control", {{"load_factor", 1.0}, {"increments", 10}}}}}}};
  const beamfea::ojson r = run_analysis(doc)["p"];
  ASSERT_EQ(r["completed"], true) << r.dump();
  // Closed form: F (L + q) cos(theta) = kr theta, F sin(theta) = k q (Newton on (theta, q)).
  double th = 0.3, q = 0.1;
  for (int it = 0; it < 50; ++it) {
    const double r1 = F * (L + q) * std::cos(th) - kr * th, r2 = F * std::sin(th) - k * q;
    const double a11 = -F * (L + q) * std::sin(th) - kr, a12 = F * std::cos(th), a21 = F * std::cos(th), a22 = -k;
    const double det = a11 * a22 - a12 * a21;
    th -= (a22 * r1 - a12 * r2) / det;
    q -= (-a21 * r1 + a11 * r2) / det;
  }
  ASSERT_GT(th, 0.3);  // a large rotation
  ASSERT_GT(q, 0.1 * L);  // and a large slide
  const auto& u = r["steps"].back()["nodes"]["T"]["displacement"];
  EXPECT_NEAR(u[0].get<double>(), (L + q) * std::cos(th) - L, 1e-7 * L);
  EXPECT_NEAR(u[1].get<double>(), (L + q) * std::sin(th), 1e-7 * L);
  EXPECT_NEAR(u[5].get<double>(), th, 1e-7);
}

}  // namespace prismatic_joint_test
