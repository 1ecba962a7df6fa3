// The chain U_p R_a R_a S_p of Pashkevich, Klimchik & Chablat (2010), eq. 33, solved by beamfea's
// ordinary path, stability and buckling analyses on the example models
// (examples/05_pashkevich_chain/models, written by generate.py): lumped (VJM) and beam.
// Reference values: docs/notes/pashkevich-reference.md, the verified ("computed") values of
// sections 4, 6, 7 and 8 - never the printed table entries where they disagree.
// GCC 12 reports -Wrestrict false positives inside std::string concatenation with literals
// (GCC bug 105329); the code here is plain string building.
#pragma GCC diagnostic ignored "-Wrestrict"
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "io/analysis.hpp"
#include "io/model_reader.hpp"
#include "io/run.hpp"
#include "pashkevich_vjm.hpp"
#include "support/files.hpp"

namespace pashkevich_chain_test {

namespace {

using nlohmann::json;
constexpr double kPi = std::numbers::pi;

std::string example(const std::string& name) {
  return beamfea::test::source_path("examples/05_pashkevich_chain/models/" + name).string();
}

bool have(const char* type) { return beamfea::find_analysis_type(type) != nullptr; }

struct Step {
  double delta, P;
  bool stable;
  double kxx;  // NaN when the engine gave no stiffness
};
struct Path {
  std::vector<Step> steps;
  std::vector<std::pair<std::string, double>> critical;  // type, load factor
};

// Runs the example's path analysis up to delta = `to` (and, optionally, with an edited spec).
Path run_path(const std::string& file, double to, const json& patch = json::object()) {
  json doc = beamfea::read_json_file(example(file));
  json path = doc["analyses"][0];
  if (path["control"].contains("to")) path["control"]["to"] = -to;
  path["stop"]["beyond"] = -to;
  for (const auto& [k, v] : patch.items()) path[k] = v;
  doc["analyses"] = json::array({path});
  const beamfea::Model m = beamfea::load_and_check(doc);
  beamfea::RunOptions opt;
  opt.write_vtk = false;
  const auto report = beamfea::run_document(m, doc, opt);
  const auto& a = report.results["analyses"]["path"];
  Path out;
  for (const auto& s : a["steps"])
    out.steps.push_back({-s["nodes"]["E"]["displacement"][0].get<double>(), s["load_factor"].get<double>(),
                         s["stable"].get<bool>(),
                         s.contains("stiffness") ? s["stiffness"][0][0].get<double>() : std::nan("")});
  if (a.contains("critical_points"))
    for (const auto& c : a["critical_points"])
      out.critical.push_back({c.value("type", std::string()), c["load_factor"].get<double>()});
  return out;
}

// Lowest load factor of the "buckling" analysis of a model file (S posture: the straight chain).
double buckling_load(const std::string& file, const std::string& dir = "models/") {
  json doc = beamfea::read_json_file(beamfea::test::source_path("examples/05_pashkevich_chain/" + dir + file).string());
  json b;
  for (const auto& a : doc["analyses"])
    if (a["type"] == "buckling") b = a;
  doc["analyses"] = json::array({b});
  const beamfea::Model m = beamfea::load_and_check(doc);
  beamfea::RunOptions opt;
  opt.write_vtk = false;
  const auto report = beamfea::run_document(m, doc, opt);
  return report.results["analyses"][b["id"].get<std::string>()]["load_factors"][0].get<double>();
}

// The force at deflection delta, interpolated between converged steps on the stable branch.
double force_at(const Path& p, double delta) {
  for (std::size_t i = 1; i < p.steps.size(); ++i) {
    const auto &a = p.steps[i - 1], &b = p.steps[i];
    if ((a.delta - delta) * (b.delta - delta) <= 0 && a.delta != b.delta)
      return a.P + (delta - a.delta) / (b.delta - a.delta) * (b.P - a.P);
  }
  return std::nan("");
}

double first_critical(const Path& p) { return p.critical.empty() ? std::nan("") : p.critical.front().second; }

}  // namespace

// ---------------------------------------------------------------- model A (Table 2, eqs. 43-44)

TEST(PashkevichChain, ModelAStraightChainBucklesAtKthetaOverLAndFollowsEq43) {
  ASSERT_TRUE(have("path")) << "analysis 'path' is not registered";
  const Path p = run_path("A_S_lumped.json", 1.0);
  ASSERT_FALSE(p.steps.empty());
  // F_cr = K_theta / L (reference note, section 6: closed form).
  EXPECT_NEAR(first_critical(p), 1.0, 2e-3);
  // Eq. 43 along the stable post-buckled branch: F = (K_theta/L) phi / sin phi, phi = acos(1 - delta/2L).
  int n = 0;
  for (const auto& s : p.steps) {
    if (s.delta < 0.02) continue;
    const double phi = std::acos(1.0 - s.delta / 2.0);
    EXPECT_NEAR(s.P, phi / std::sin(phi), 1e-5) << "delta " << s.delta;
    EXPECT_TRUE(s.stable) << "delta " << s.delta;
    if (!std::isnan(s.kxx)) {  // its tangent (sin phi - phi cos phi) / (2 sin^3 phi)
      const double k = (std::sin(phi) - phi * std::cos(phi)) / (2 * std::pow(std::sin(phi), 3));
      EXPECT_NEAR(s.kxx, k, 1e-4) << "delta " << s.delta;
    }
    ++n;
  }
  EXPECT_GT(n, 5);
  // Table 2 at delta = L (tangent 0.2636, P = 1.2092; reference note, section 6).
  EXPECT_NEAR(force_at(p, 1.0), 1.2092, 1e-3);
}

TEST(PashkevichChain, ModelAZPostureBifurcatesAt1p0330) {
  ASSERT_TRUE(have("path")) << "analysis 'path' is not registered";
  const Path p = run_path("A_Z_lumped.json", 0.4);
  // delta_cr = 0.11093 L, F_cr = 1.0330 K_theta/L; P(0.2) = 1.0520, P(0.4) = 1.0976 on the
  // non-symmetric stable branch (reference note, section 6).
  EXPECT_NEAR(first_critical(p), 1.0330, 2e-3);
  EXPECT_NEAR(force_at(p, 0.10), 0.9719, 2e-3);
  EXPECT_NEAR(force_at(p, 0.20), 1.0520, 2e-3);
  EXPECT_NEAR(force_at(p, 0.40), 1.0976, 2e-3);
}

TEST(PashkevichChain, ModelAPiPostureIsStableWithTable2Stiffness) {
  ASSERT_TRUE(have("path")) << "analysis 'path' is not registered";
  const Path p = run_path("A_Pi_lumped.json", 1.0);
  EXPECT_TRUE(p.critical.empty());
  for (const auto& s : p.steps) EXPECT_TRUE(s.stable) << "delta " << s.delta;
  EXPECT_NEAR(force_at(p, 0.10), 0.1604, 1e-3);
  EXPECT_NEAR(force_at(p, 1.00), 0.7226, 1e-3);
}

// Eq. 44 (the unstable Z-shaped equilibria of the straight chain) and eq. 43, as closed forms
// against the VJM equilibrium equations and eq. 22, along the curve 0.05 <= delta <= 1.
TEST(PashkevichChain, ClosedFormsEq43AndEq44AreEquilibriaOfStatedStability) {
  const vjm::Chain c = vjm::chain_a_planar(1.0);
  for (double D = 0.05; D <= 1.0 + 1e-12; D += 0.05) {
    const double X = 3 - D;
    const double p1 = std::acos(1 - D / 2), p2 = std::acos(1 - 1.5 * D + D * D / 4);
    const double p4 = std::acos((12 - 6 * D + D * D) / (4 * X));
    const Eigen::Vector2d t(X, 0);
    struct Case {
      double q, t1, t2, P;
      bool stable;
    } cases[2] = {{-p1, p1, p1, p1 / std::sin(p1), true}, {p4, -p2, p2, X * p2 / std::sin(p2), false}};
    for (const auto& k : cases) {
      Eigen::VectorXd z(3), F(2);
      z << k.q, k.t1, k.t2;
      F << -k.P, 0.0;
      ASSERT_NEAR((c.position(z) - t).norm(), 0, 1e-9) << D;
      EXPECT_NEAR((c.K * z - c.jacobian(z).transpose() * F).norm(), 0, 1e-9) << "not in equilibrium at Delta " << D;
      EXPECT_EQ(c.stability_margin(z, F) > 0, k.stable) << "Delta " << D;
    }
  }
}

// ---------------------------------------------------------------- models B and C (Tables 3, 4)

TEST(PashkevichChain, ModelBStraightLumpedChainBucklesAtSqrt21Minus3) {
  ASSERT_TRUE(have("buckling")) << "analysis 'buckling' is not registered";
  // One 6-D spring per link, T_3D = Tx Ty Rz: det = 0 at P = sqrt(21) - 3 (reference note, 8.1).
  // (The paper's Table 3 prints K_theta/L, carried over from model A.)
  EXPECT_NEAR(buckling_load("B_S_lumped.json"), std::sqrt(21.0) - 3.0, 2e-3);
  // Model C: out of plane, k_I (sqrt(21) - 3), k_I = (a/b)^2 = 0.16 (printed: 0.16).
  EXPECT_NEAR(buckling_load("C_S_lumped.json"), 0.16 * (std::sqrt(21.0) - 3.0), 2e-3 * 0.16);
}

TEST(PashkevichChain, StraightBeamChainBucklesAsAnEulerColumnOfLength3L) {
  ASSERT_TRUE(have("buckling")) << "analysis 'buckling' is not registered";
  // Pinned-pinned column of length 3L: P_E = pi^2 E I / (3L)^2 = (pi^2/9) K_theta/L in plane
  // (model B) and k_I times that out of plane (model C). N = 8 elements per link (24 in all):
  // cubic Euler-Bernoulli elements are within ~1e-6 there.
  EXPECT_NEAR(buckling_load("B_S_beam.json"), kPi * kPi / 9.0, 1e-4);
  EXPECT_NEAR(buckling_load("C_S_beam.json"), 0.16 * kPi * kPi / 9.0, 1e-4 * 0.16);
}

TEST(PashkevichChain, ModelBPathsMatchTheReferenceCurves) {
  ASSERT_TRUE(have("path")) << "analysis 'path' is not registered";
  {  // S: bifurcation at sqrt(21) - 3, then P(0.4) = 1.6832 (reference note, section 7).
    const Path p = run_path("B_S_lumped.json", 0.4);
    EXPECT_NEAR(first_critical(p), std::sqrt(21.0) - 3.0, 2e-3);
    EXPECT_NEAR(force_at(p, 0.20), 1.6319, 2e-3);
    EXPECT_NEAR(force_at(p, 0.40), 1.6832, 2e-3);
  }
  {  // Pi: no instability; P(0.4) = 0.5893.
    const Path p = run_path("B_Pi_lumped.json", 0.4);
    EXPECT_TRUE(p.critical.empty());
    EXPECT_NEAR(force_at(p, 0.20), 0.3591, 1e-3);
    EXPECT_NEAR(force_at(p, 0.40), 0.5893, 1e-3);
  }
  {  // Z: an imperfect bifurcation (a knee, no true critical point); P(0.2) = 1.6708, P(0.4) = 1.7513.
    const Path p = run_path("B_Z_lumped.json", 0.4);
    EXPECT_NEAR(force_at(p, 0.20), 1.6708, 2e-3);
    EXPECT_NEAR(force_at(p, 0.40), 1.7513, 2e-3);
  }
}

TEST(PashkevichChain, ModelCBucklesOutOfPlaneInAllPostures) {
  ASSERT_TRUE(have("path")) << "analysis 'path' is not registered";
  // Reference note, section 7 (nu = 0.3, Roark J): S 0.25321, Pi 0.2720, Z 0.2679.
  EXPECT_NEAR(first_critical(run_path("C_S_lumped.json", 0.2)), 0.25321, 1e-3);
  const Path pi = run_path("C_Pi_lumped.json", 0.4);
  EXPECT_NEAR(first_critical(pi), 0.2720, 2e-3);
  EXPECT_NEAR(force_at(pi, 0.40), 0.2794, 2e-3);
  const Path z = run_path("C_Z_lumped.json", 0.4);
  EXPECT_NEAR(first_critical(z), 0.2679, 2e-3);
  EXPECT_NEAR(force_at(z, 0.40), 0.2882, 2e-3);
}

// ---------------------------------------------------------------- convergence (straight chain)

namespace {

// The S chain of model B with n virtual springs per link (each the cantilever of a segment L/n,
// at the segment's end), as examples/05_pashkevich_chain/generate.py writes it.
json straight_lumped_chain(int n) {
  json doc = beamfea::read_json_file(example("B_S_lumped.json"));
  json nodes = json::array({json{{"id", "B"}, {"xyz", {0, 0, 0}}}, json{{"id", "P0"}, {"xyz", {0, 0, 0}}}});
  json elements = json::array(), joints = json::array({doc["joints"][0]});
  std::string start = "P0";
  for (int k = 1; k <= 3 * n; ++k) {
    const double x = static_cast<double>(k) / n;
    const std::string a = "L" + std::to_string(k), b = a + "s";
    nodes.push_back(json{{"id", a}, {"xyz", {x, 0, 0}}});
    nodes.push_back(json{{"id", b}, {"xyz", {x, 0, 0}}});
    elements.push_back(json{{"id", "r" + std::to_string(k)}, {"type", "rigid"}, {"nodes", {start, a}}});
    joints.push_back(json{{"id", "s" + std::to_string(k)},
                          {"type", "virtual_spring"},
                          {"nodes", {a, b}},
                          {"stiffness_from_beam", {{"material", "mat"}, {"section", "link"}, {"length", 1.0 / n}}}});
    start = b;
  }
  nodes.push_back(json{{"id", "E"}, {"xyz", {3, 0, 0}}});
  joints.push_back(json{{"id", "S"}, {"type", "spherical"}, {"nodes", {start, "E"}}});
  doc["nodes"] = nodes;
  doc["elements"] = elements;
  doc["joints"] = joints;
  doc["analyses"] = json::array({json{{"id", "buckling"}, {"type", "buckling"}, {"modes", 1}}});
  return doc;
}

double first_load_factor(const json& doc) {
  const beamfea::Model m = beamfea::load_and_check(doc);
  beamfea::RunOptions opt;
  opt.write_vtk = false;
  return beamfea::run_document(m, doc, opt).results["analyses"]["buckling"]["load_factors"][0].get<double>();
}

}  // namespace

TEST(PashkevichChain, BeamMeshAndLumpedSpringCountConvergeToTheEulerLoad) {
  ASSERT_TRUE(have("buckling")) << "analysis 'buckling' is not registered";
  const double PE = kPi * kPi / 9.0;  // pinned-pinned column of length 3L, E I = K_theta L
  // Beam model: N elements per link; cubic elements converge as O(N^-4) on the Euler load.
  double previous = 1.0;
  for (int N : {1, 2, 4, 8}) {
    json doc = beamfea::read_json_file(example("B_S_beam.json"));
    for (auto& e : doc["elements"]) e["divisions"] = N;
    json b;
    for (const auto& a : doc["analyses"])
      if (a["type"] == "buckling") b = a;
    doc["analyses"] = json::array({b});
    const double err = std::abs(first_load_factor(doc) - PE) / PE;
    EXPECT_LT(err, previous / 8) << "N = " << N;  // at least O(N^-3) between refinements
    previous = err;
  }
  EXPECT_LT(previous, 1e-6);
  // Lumped model, n springs per link: from above, O(1/n^2), to the same Euler load (reference note,
  // section 8.2: 1.58258, 1.20280, 1.12205, 1.10291 for n = 1, 2, 4, 8).
  const double expected[4] = {1.58258, 1.20280, 1.12205, 1.10291};
  int i = 0;
  for (int n : {1, 2, 4, 8}) {
    const double P = first_load_factor(straight_lumped_chain(n));
    EXPECT_NEAR(P, expected[i++], 2e-5) << "n = " << n;
    EXPECT_GT(P, PE);
  }
}

}  // namespace pashkevich_chain_test
