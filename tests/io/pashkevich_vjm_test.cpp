// The engine's stiffness and stability verdict on lumped (VJM) models against the paper's own
// equations evaluated directly: Pashkevich, Klimchik & Chablat (2010), eqs. 6-7 (equilibrium),
// 22-23 (stability), 28 (loaded Cartesian stiffness), and Table 1 (energies of the model-A chain).
// The VJM side is a small dense implementation (pashkevich_vjm.hpp) sharing nothing with beamfea.
// Reference values: docs/notes/pashkevich-reference.md (the "computed" ones, never the printed).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "io/analysis.hpp"
#include "io/model_reader.hpp"
#include "io/run.hpp"
#include "pashkevich_vjm.hpp"
#include "support/files.hpp"
#include "solvers/condensed_stiffness.hpp"

namespace pashkevich_vjm_test {

namespace {

using nlohmann::json;
constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

std::string example(const std::string& name) {
  return beamfea::test::source_path("examples/05_pashkevich_chain/models/" + name).string();
}

// The example model with the end node E released (no supports, no load): its condensed
// stiffness is the Cartesian stiffness of eq. 28 at zero load.
beamfea::Model unloaded_model(const std::string& file) {
  json doc = beamfea::read_json_file(example(file));
  json supports = json::array();
  for (const auto& s : doc["supports"])
    if (s["node"] != "E") supports.push_back(s);
  doc["supports"] = supports;
  doc.erase("loads");
  return beamfea::read_model(doc);
}

// Posture constants (reference note, section 2).
struct Posture {
  double qa1, qa2, q10;
};
const Posture kPosturePi{-30 * kDeg, -30 * kDeg, 30 * kDeg};
const Posture kPostureZ{-30 * kDeg, 30 * kDeg, std::atan(0.5 / (2.0 + std::cos(30 * kDeg)))};

// Sections of generate.py (E = 1, I_z = 1 so that K_theta = E I_z / L = 1; b = 0.05 L).
Eigen::MatrixXd spring_b() { return vjm::cantilever(1.0, 1.0 / 2.6, 4800.0, 100.0, 1.0, 260.0, 1.0); }
Eigen::MatrixXd spring_c() {
  const double a = 0.02, b = 0.05, r = a / b;
  const double J = b * a * a * a * (1.0 / 3.0 - 0.21 * r * (1.0 - std::pow(r, 4) / 12.0)) / (a * b * b * b / 12.0);
  return vjm::cantilever(1.0, 1.0 / 2.6, 4800.0, r * r, 1.0, J, 1.0);
}

void expect_unloaded_stiffness_matches_eq28(const vjm::Chain& chain, const std::string& file, double kxx_reference) {
  const Eigen::VectorXd z = Eigen::VectorXd::Zero(chain.n), F = Eigen::VectorXd::Zero(3);
  const Eigen::MatrixXd KF = chain.loaded_stiffness(z, F);
  const beamfea::Model m = unloaded_model(file);
  const beamfea::CondensedStiffness k = beamfea::linear_node_stiffness(m, m.find_node("E"));
  ASSERT_TRUE(k.ok) << k.message;
  const double scale = KF.cwiseAbs().maxCoeff();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(k.K(i, j), KF(i, j), 1e-7 * scale) << file << " entry " << i << j;
  // Reference note, sections 6-7 (exact or 5-digit values).
  EXPECT_NEAR(KF(0, 0), kxx_reference, 2e-4 * std::abs(kxx_reference)) << file;
}

}  // namespace

TEST(PashkevichVjm, UnloadedStiffnessOfModelAMatchesEq28AndClosedForms) {
  // Pi: 2 (exact); Z: 10 + 4 sqrt(3) (reference note, section 6).
  expect_unloaded_stiffness_matches_eq28(vjm::chain_a(kPosturePi.qa1, kPosturePi.qa2, kPosturePi.q10, 1.0),
                                         "A_Pi_lumped.json", 2.0);
  expect_unloaded_stiffness_matches_eq28(vjm::chain_a(kPostureZ.qa1, kPostureZ.qa2, kPostureZ.q10, 1.0),
                                         "A_Z_lumped.json", 10.0 + 4.0 * std::sqrt(3.0));
}

TEST(PashkevichVjm, UnloadedStiffnessOfModelsBAndCMatchesEq28) {
  // B and C share the in-plane part: 2.3970 (Pi), 33.195 (Z) (reference note, section 7).
  expect_unloaded_stiffness_matches_eq28(vjm::chain_bc(kPosturePi.qa1, kPosturePi.qa2, kPosturePi.q10, spring_b()),
                                         "B_Pi_lumped.json", 2.3970);
  expect_unloaded_stiffness_matches_eq28(vjm::chain_bc(kPostureZ.qa1, kPostureZ.qa2, kPostureZ.q10, spring_b()),
                                         "B_Z_lumped.json", 33.195);
  expect_unloaded_stiffness_matches_eq28(vjm::chain_bc(kPosturePi.qa1, kPosturePi.qa2, kPosturePi.q10, spring_c()),
                                         "C_Pi_lumped.json", 2.3970);
  expect_unloaded_stiffness_matches_eq28(vjm::chain_bc(kPostureZ.qa1, kPostureZ.qa2, kPostureZ.q10, spring_c()),
                                         "C_Z_lumped.json", 33.195);
  // Straight chain: the axial stiffness of three axial springs in series, E A / (3 L) = 1600.
  expect_unloaded_stiffness_matches_eq28(vjm::chain_bc(0, 0, 0, spring_c()), "C_S_lumped.json", 1600.0);
}

// Table 1 (S posture, delta = L/10): the twelve configurations closing the planar model-A chain,
// their energies (in delta K_theta / L) and which are equilibria, stable or not (eqs. 22-23).
TEST(PashkevichVjm, Table1EnergiesAndStabilityOfTheTwelveConfigurations) {
  const double D = 0.1;  // Delta = delta / L
  const double p1 = std::acos(1 - D / 2), p2 = std::acos(1 - 1.5 * D + D * D / 4), p3 = 2 * p1;
  const double X = 3 - D;
  const double p4 = std::acos((12 - 6 * D + D * D) / (4 * X)), p5 = std::acos((6 - 6 * D + D * D) / (2 * X));
  // phi_3 printed as arccos(1 - 2 Delta + Delta^2/4): a typo, the closing angle is 2 phi_1
  // = arccos(1 - 2 Delta + Delta^2/2) (reference note, section 4).
  EXPECT_NEAR(p3, std::acos(1 - 2 * D + D * D / 2), 1e-12);
  struct Row {
    double q, t1, t2, energy;  // energy computed (reference note, Table 1)
    int kind;                  // 0: not an equilibrium, 1: stable, -1: unstable
  };
  // Rows 4 and 12 with +phi_3 (the printed -phi_3 does not close the chain).
  const Row rows[12] = {{-p5, p2, 0, 1.5128, 0},  {-p1, p1, p1, 1.0084, 1},   {-p4, 0, p2, 1.5128, 0},
                        {0, -p1, p3, 2.5211, 0},  {p4, -p2, p2, 3.0255, -1},  {p1, -p3, p1, 2.5211, 0},
                        {p5, -p2, 0, 1.5128, 0},  {p1, -p1, -p1, 1.0084, 1},  {p4, 0, -p2, 1.5128, 0},
                        {0, p1, -p3, 2.5211, 0},  {-p4, p2, -p2, 3.0255, -1}, {-p1, p3, -p1, 2.5211, 0}};
  const double printed[12] = {1.5, 1.0, 1.5, 2.5, 3.0, 2.5, 1.5, 1.0, 1.5, 2.5, 3.0, 2.5};
  const vjm::Chain c = vjm::chain_a_planar(1.0);
  const Eigen::Vector2d t(X, 0.0);
  for (int i = 0; i < 12; ++i) {
    Eigen::VectorXd z(3);
    z << rows[i].q, rows[i].t1, rows[i].t2;
    EXPECT_NEAR((c.position(z) - t).norm(), 0.0, 1e-9) << "row " << i + 1 << " does not close the chain";
    const double e = c.energy(z) / D;
    EXPECT_NEAR(e, rows[i].energy, 1e-4) << "row " << i + 1;
    EXPECT_NEAR(e, printed[i], 0.03) << "row " << i + 1 << " against the printed (rounded) value";
    // Equilibrium (eqs. 6-7): K z = J^T F solvable for F (least squares residual ~ 0).
    const Eigen::MatrixXd J = c.jacobian(z);
    const Eigen::VectorXd Kz = c.K * z;
    const Eigen::VectorXd F = J.transpose().colPivHouseholderQr().solve(Kz);
    const double residual = (J.transpose() * F - Kz).norm();
    if (rows[i].kind == 0) {
      EXPECT_GT(residual, 1e-3) << "row " << i + 1 << " should not be an equilibrium";
      continue;
    }
    EXPECT_LT(residual, 1e-9) << "row " << i + 1 << " should be an equilibrium";
    const double margin = c.stability_margin(z, F);
    if (rows[i].kind > 0) {
      EXPECT_GT(margin, 1e-3) << "row " << i + 1 << " should be stable";
    } else {
      EXPECT_LT(margin, -1e-3) << "row " << i + 1 << " should be unstable";
    }
    // Compression along x: eq. 43 (stable, F = phi/sin phi) and eq. 44 (unstable, X theta / sin theta).
    const double P = -F[0];
    if (rows[i].kind > 0) {
      EXPECT_NEAR(P, p1 / std::sin(p1), 1e-9);
    } else {
      EXPECT_NEAR(P, X * p2 / std::sin(p2), 1e-9);
    }
  }
  EXPECT_NEAR(p1 * p1, 0.100845, 1e-6);
  EXPECT_NEAR(p2 * p2, 0.302552, 1e-6);
}

// Under load: the engine's path analysis ("path") on the lumped model against eqs. 6-7,
// 22-23 and 28 evaluated on the same chain at the same end displacement.
namespace {

struct EngineStep {
  double delta, P;
  bool stable;
};

// Imposed motion of the end (displacement control without loads, the lumped-model use case of
// the path analysis): E pushed to x = X0 - to, y = z = 0 held; the force is the reaction of the
// controlled DOF and the stability is that of eq. 22, with the end position held.
std::vector<EngineStep> engine_path(const std::string& file, double to, int increments) {
  json doc = beamfea::read_json_file(example(file));
  doc.erase("loads");
  doc["analyses"] = json::array({json{{"id", "path"},
                                      {"type", "path"},
                                      {"track", {"E"}},
                                      {"control", {{"node", "E"}, {"dof", "ux"}, {"to", -to}, {"increments", increments}}}}});
  const beamfea::Model m = beamfea::load_and_check(doc);
  beamfea::RunOptions opt;
  opt.write_vtk = false;
  const auto report = beamfea::run_document(m, doc, opt);
  std::vector<EngineStep> out;
  for (const auto& s : report.results["analyses"]["path"]["steps"]) {
    EngineStep e{};
    e.delta = -s["nodes"]["E"]["displacement"][0].get<double>();
    e.P = -s["reaction"].get<double>();  // the reaction on E along x; compression P > 0
    e.stable = s["stable"].get<bool>();
    out.push_back(e);
  }
  return out;
}

// Follows the fundamental branch of the VJM chain by Newton continuation to delta.
void vjm_state(const vjm::Chain& c, double x0, double delta, Eigen::VectorXd& z, Eigen::VectorXd& F) {
  z = Eigen::VectorXd::Zero(c.n);
  F = Eigen::VectorXd::Zero(3);
  const int n = std::max(1, static_cast<int>(std::ceil(delta / 0.01)));
  for (int k = 1; k <= n; ++k) {
    const Eigen::Vector3d t(x0 - delta * k / n, 0, 0);
    ASSERT_TRUE(c.equilibrium(t, z, F)) << "VJM Newton failed at delta " << delta * k / n;
  }
}

bool have_path_analysis() { return beamfea::find_analysis_type("path") != nullptr; }

}  // namespace

TEST(PashkevichVjm, ImposedEndMotionGivesTheForceAndStabilityOfEqs6To7And22) {
  ASSERT_TRUE(have_path_analysis()) << "analysis 'path' is not registered";
  // Model B, Pi posture: stable throughout (reference note, section 7: P(0.4) = 0.5893).
  const vjm::Chain c = vjm::chain_bc(kPosturePi.qa1, kPosturePi.qa2, kPosturePi.q10, spring_b());
  const double x0 = 1.0 + std::sqrt(3.0);
  const auto steps = engine_path("B_Pi_lumped.json", 0.4, 8);
  ASSERT_GT(steps.size(), 3u);
  int compared = 0;
  for (const auto& s : steps) {
    if (s.delta < 0.01) continue;
    Eigen::VectorXd z, F;
    vjm_state(c, x0, s.delta, z, F);
    EXPECT_NEAR(s.P, -F[0], 1e-6 * (1 + std::abs(F[0]))) << "delta " << s.delta;
    EXPECT_TRUE(s.stable) << "delta " << s.delta;
    EXPECT_GT(c.stability_margin(z, F), 0) << "delta " << s.delta;
    ++compared;
  }
  EXPECT_GE(compared, 4);
  EXPECT_NEAR(steps.back().P, 0.5893, 2e-4);
}

// Loaded Cartesian stiffness (eq. 28): K_F[x,x] = dP/ddelta with y, z held. The engine's
// steps[].stiffness condenses to a node none of whose DOFs is held, which the end node here is not
// (y and z are held), so the engine's value is the slope of its own imposed-motion curve: the
// three-point (second-order) derivative on its adaptive steps.
TEST(PashkevichVjm, LoadedStiffnessAlongThePathMatchesEq28) {
  ASSERT_TRUE(have_path_analysis()) << "analysis 'path' is not registered";
  const vjm::Chain c = vjm::chain_bc(kPosturePi.qa1, kPosturePi.qa2, kPosturePi.q10, spring_b());
  const double x0 = 1.0 + std::sqrt(3.0);
  const auto steps = engine_path("B_Pi_lumped.json", 0.4, 400);  // first step 0.001 L; the engine grows it
  ASSERT_GE(steps.size(), 6u);
  int compared = 0;
  for (std::size_t i = 1; i + 1 < steps.size(); ++i) {
    const auto &s0 = steps[i - 1], &s1 = steps[i], &s2 = steps[i + 1];
    const double h1 = s1.delta - s0.delta, h2 = s2.delta - s1.delta;
    if (s1.delta < 0.05 || h1 <= 0 || h2 <= 0) continue;
    const double k_engine =
        (-s0.P * h2 / (h1 * (h1 + h2)) + s1.P * (h2 - h1) / (h1 * h2) + s2.P * h1 / (h2 * (h1 + h2)));
    Eigen::VectorXd z, F;
    vjm_state(c, x0, s1.delta, z, F);
    const double k_vjm = c.loaded_stiffness(z, F)(0, 0);
    // Truncation error of the three-point formula ~ h1 h2 |d3P/ddelta3| / 6 with |d3P/ddelta3| < ~60
    // here: < 3e-4 relative for steps <= 0.005 L (0.3 % at 0.04 L, as seen with coarser steps).
    if (h1 > 0.005 || h2 > 0.005) continue;
    EXPECT_NEAR(k_engine, k_vjm, 1e-3 * k_vjm) << "delta " << s1.delta << " (steps " << h1 << ", " << h2 << ")";
    ++compared;
  }
  EXPECT_GE(compared, 3);
  // Reference note, section 1.4: k = 1.137710 at delta = 0.3 (model B, Pi).
  Eigen::VectorXd z, F;
  vjm_state(c, x0, 0.3, z, F);
  EXPECT_NEAR(c.loaded_stiffness(z, F)(0, 0), 1.137710, 1e-5);
}

TEST(PashkevichVjm, LossOfStabilityOnTheFundamentalBranchMatchesEq22) {
  ASSERT_TRUE(have_path_analysis()) << "analysis 'path' is not registered";
  // Model C, Pi posture, no branch switching: the planar branch loses stability out of plane at
  // delta_cr = 0.14074 L, P = 0.2720 (reference note, section 7).
  const vjm::Chain c = vjm::chain_bc(kPosturePi.qa1, kPosturePi.qa2, kPosturePi.q10, spring_c());
  const double x0 = 1.0 + std::sqrt(3.0);
  const auto steps = engine_path("C_Pi_lumped.json", 0.2, 20);
  ASSERT_GT(steps.size(), 3u);
  bool saw_stable = false, saw_unstable = false;
  for (const auto& s : steps) {
    if (s.delta < 0.02 || std::abs(s.delta - 0.14074) < 0.005) continue;
    Eigen::VectorXd z, F;
    vjm_state(c, x0, s.delta, z, F);
    const bool stable = c.stability_margin(z, F) > 0;
    EXPECT_EQ(stable, s.delta < 0.14074) << "VJM eq. 22 at delta " << s.delta;
    EXPECT_EQ(s.stable, stable) << "engine at delta " << s.delta;
    EXPECT_NEAR(s.P, -F[0], 1e-6 * (1 + std::abs(F[0])));
    saw_stable = saw_stable || stable;
    saw_unstable = saw_unstable || !stable;
  }
  EXPECT_TRUE(saw_stable && saw_unstable);
}

}  // namespace pashkevich_vjm_test
