// Ties (OpenSees' equalDOF) and linear multi-point constraints, exact in every analysis: three
// cantilever columns tied at the roof against the closed forms (linear, buckling, path), a general
// constraint satisfied exactly with its multiplier, redundant and contradictory rows refused naming
// them, and a node carried by springs alone.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.hpp"
#include "io/run.hpp"

namespace ties_and_constraints_test {

using namespace beamfea;
using nlohmann::json;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double E = 2.0e11, G = 8.0e10, A = 1.0e-2, I = 1.0e-5, J = 1.0e-5, H = 3.0, bay = 4.0;

ojson analyses(const json& doc) {
  const Model m = load_and_check(doc);
  return run_document(m, doc, RunOptions{}).results["analyses"];
}

std::vector<double> numbers(const ojson& v) { return v.get<std::vector<double>>(); }

// Three cantilever columns along z (bases B1 B2 B3 fixed at x = 0, bay, 2 bay; tops T1 T2 T3 at
// height H), `divisions` elements each. Sway along x bends column i about its local y (orientation
// x: local z = global x) with Iy = iy[i]; along y about local z with Iz = 4 I. The roof is the ties
// T1-T2 and T2-T3 on ux (two bays), when `tied`.
json columns(std::array<double, 3> iy, bool tied, int divisions = 1) {
  json d{{"materials", {{{"id", "m"}, {"E", E}, {"G", G}}}}, {"analyses", json::array()}};
  for (int i = 0; i < 3; ++i) {
    const std::string k = std::to_string(i + 1);
    d["nodes"].push_back({{"id", "B" + k}, {"xyz", {i * bay, 0, 0}}});
    d["nodes"].push_back({{"id", "T" + k}, {"xyz", {i * bay, 0, H}}});
    d["sections"].push_back({{"id", "s" + k}, {"A", A}, {"Iy", iy[i]}, {"Iz", 4 * I}, {"J", J}});
    d["elements"].push_back({{"id", "c" + k}, {"type", "beam"}, {"nodes", {"B" + k, "T" + k}}, {"material", "m"},
                             {"section", "s" + k}, {"orientation", {1, 0, 0}}, {"divisions", divisions}});
    d["supports"].push_back({{"node", "B" + k}, {"fix", "all"}});
  }
  if (tied) d["ties"] = {{{"nodes", {"T1", "T2"}}, {"dofs", {"ux"}}}, {{"nodes", {"T2", "T3"}}, {"dofs", {"ux"}}}};
  return d;
}

// Lateral stiffness of a cantilever column at its free top (rotation free): 3 E I / H^3.
double k_cantilever(double iy) { return 3 * E * iy / (H * H * H); }

}  // namespace

TEST(Ties, ThreeColumnsTiedAtTheRoofSwayTogether) {
  // The roof makes the tops move alike along x: u = F / (k1 + k2 + k3), the column cantilevers'
  // stiffnesses in parallel; the tie T1-T2 passes on (k2 + k3) u to T2, the tie T2-T3 passes k3 u.
  const double F = 2.0e4;
  json d = columns({I, 2 * I, 3 * I}, true);
  d["loads"] = {{{"node", "T1"}, {"force", {F, 0, 0}}}};
  d["analyses"] = {{{"id", "lin"}, {"type", "linear_static"}}};
  const ojson lin = analyses(d)["lin"];
  ASSERT_EQ(lin["status"], "ok") << lin.dump();
  const double k1 = k_cantilever(I), k2 = k_cantilever(2 * I), k3 = k_cantilever(3 * I);
  const double u = F / (k1 + k2 + k3);
  for (const char* t : {"T1", "T2", "T3"}) EXPECT_NEAR(numbers(lin["nodes"][t]["displacement"])[0] / u, 1.0, 1e-9) << t;
  const auto ties = lin["tie_forces"];
  ASSERT_EQ(ties.size(), 2u);
  EXPECT_NEAR(numbers(ties[0])[0] / ((k2 + k3) * u), 1.0, 1e-9);
  EXPECT_NEAR(numbers(ties[1])[0] / (k3 * u), 1.0, 1e-9);
  // Each base takes its column's share: -k_i u.
  EXPECT_NEAR(numbers(lin["nodes"]["B3"]["reaction"])[0] / (-k3 * u), 1.0, 1e-9);
  // Rotations are not tied: a column's top turns by its own cantilever's F_i H^2 / 2 E I_i = 3 u / 2 H.
  EXPECT_NEAR(numbers(lin["nodes"]["T2"]["displacement"])[4] / (1.5 * u / H), 1.0, 1e-9);
}

TEST(Ties, TheStiffnessAtATiedTopIsTheColumnsInParallel) {
  // The compliance along x at T1 (a unit force there, the top's rotations free): the three
  // cantilevers in parallel, 1 / (k1 + k2 + k3).
  json d = columns({I, 2 * I, 3 * I}, true);
  d["analyses"] = {{{"id", "K"}, {"type", "stiffness"}, {"node", "T1"}}};
  const ojson K = analyses(d)["K"];
  ASSERT_EQ(K["status"], "ok") << K.dump();
  const double c = K["compliance"][0][0].get<double>();
  EXPECT_NEAR(c * (k_cantilever(I) + k_cantilever(2 * I) + k_cantilever(3 * I)), 1.0, 1e-9);
}

TEST(Ties, TiedColumnsBuckleTogether) {
  // Only T1 carries the axial load P. Tied, the sway along x needs the tops' shears to balance:
  // k(P) + k2 + k3 = 0, with the loaded cantilever's lateral stiffness k(P) = mu^3 E I / (tan(mu H) -
  // mu H), mu = sqrt(P / E I) (the tip deflection H_l (tan(mu H) - mu H) / (mu^3 E I) of a cantilever
  // with a lateral load H_l and an axial load P; Timoshenko & Gere, Theory of Elastic Stability,
  // sec. 1.11). All three columns alike (I): x = mu H solves x^3 / (tan x - x) = -6, in (pi/2, pi).
  auto f = [](double x) { return x * x * x / (std::tan(x) - x) + 6.0; };
  double lo = kPi / 2 + 1e-9, hi = kPi - 1e-9;  // f: from 0 + 6 ... falling below 0 towards pi
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > 0.0 ? lo : hi) = mid;
  }
  const double x = 0.5 * (lo + hi);
  const double P_cr = x * x * E * I / (H * H);
  const double P = 1.0e5;
  json d = columns({I, I, I}, true, 8);
  d["loads"] = {{{"node", "T1"}, {"force", {0, 0, -P}}}};
  d["analyses"] = {{{"id", "b"}, {"type", "buckling"}, {"modes", 2}}};
  const ojson b = analyses(d)["b"];
  ASSERT_EQ(b["status"], "ok") << b.dump();
  // Eight cubic elements per column: the discretisation error is far below 1e-5 of the load.
  EXPECT_NEAR(numbers(b["load_factors"])[0] * P / P_cr, 1.0, 1e-5);
  // Untied, T1 alone buckles as Euler's cantilever: pi^2 E I / (4 H^2), lower.
  json untied = columns({I, I, I}, false, 8);
  untied["loads"] = d["loads"];
  untied["analyses"] = d["analyses"];
  EXPECT_NEAR(numbers(analyses(untied)["b"]["load_factors"])[0] * P / (kPi * kPi * E * I / (4 * H * H)), 1.0, 1e-5);
}

TEST(Ties, APathKeepsTheTiesAndMeetsTheLinearAnswerUnderASmallLoad) {
  // The path keeps the ties as constraints on the displacements, exact at every step: under a load
  // a thousandth of the one that would move the roof by 1 % of H, the geometric nonlinearity is
  // below 1e-6 of the linear closed form F / (k1 + k2 + k3).
  const double k = k_cantilever(I) + k_cantilever(2 * I) + k_cantilever(3 * I);
  const double F = 1e-5 * H * k;
  json d = columns({I, 2 * I, 3 * I}, true, 2);
  d["loads"] = {{{"node", "T1"}, {"force", {F, 0, 0}}}};
  d["analyses"] = {{{"id", "p"}, {"type", "path"}, {"control", {{"load_factor", 1.0}, {"increments", 2}}}, {"track", {"T1", "T3"}}}};
  const ojson p = analyses(d)["p"];
  ASSERT_EQ(p["status"], "ok") << p.dump();
  const ojson& last = p["steps"].back();
  const double u1 = numbers(last["nodes"]["T1"]["displacement"])[0], u3 = numbers(last["nodes"]["T3"]["displacement"])[0];
  EXPECT_NEAR(u1 / (F / k), 1.0, 1e-5);
  // The tie is a constraint equation of the corrector, held to its tolerance (the displacement of a
  // converged step: 1e-10 of the model's size at most).
  EXPECT_NEAR(u3, u1, 1e-10 * H);
}

TEST(LinearConstraints, AGeneralConstraintHoldsExactlyWithItsMultiplier) {
  // 2 u1 + u2 = v on the tops' ux, no load: the tops settle where the cantilevers' energy
  // 1/2 k1 u1^2 + 1/2 k2 u2^2 is least on the constraint: k1 u1 = 2 lambda, k2 u2 = lambda, so
  // lambda = v / (4 / k1 + 1 / k2) (Lagrange), the force coefficient * lambda on each DOF.
  const double v = 0.01;
  json d = columns({I, 2 * I, 3 * I}, false);
  d["constraints"] = {{{"terms", {{{"node", "T1"}, {"dof", "ux"}, {"coefficient", 2.0}},
                                  {{"node", "T2"}, {"dof", "ux"}, {"coefficient", 1.0}}}},
                       {"value", v}}};
  d["analyses"] = {{{"id", "lin"}, {"type", "linear_static"}}, {{"id", "f"}, {"type", "modal"}, {"modes", 1}}};
  d["materials"][0]["density"] = 7850.0;
  const ojson res = analyses(d);
  const ojson& lin = res["lin"];
  ASSERT_EQ(lin["status"], "ok") << lin.dump();
  const double k1 = k_cantilever(I), k2 = k_cantilever(2 * I);
  const double lambda = v / (4 / k1 + 1 / k2);
  const double u1 = numbers(lin["nodes"]["T1"]["displacement"])[0], u2 = numbers(lin["nodes"]["T2"]["displacement"])[0];
  EXPECT_NEAR(2 * u1 + u2, v, 1e-15);
  EXPECT_NEAR(u1 / (2 * lambda / k1), 1.0, 1e-9);
  EXPECT_NEAR(u2 / (lambda / k2), 1.0, 1e-9);
  EXPECT_NEAR(numbers(lin["constraint_forces"])[0] / lambda, 1.0, 1e-9);
  EXPECT_EQ(res["f"]["status"], "ok") << res["f"].dump();  // the homogeneous row in a modal analysis
}

TEST(LinearConstraints, RedundantAndContradictoryRowsAreBadInputNamingThem) {
  auto refused = [](const json& d, const std::string& pointer, const std::string& word) {
    try {
      load_and_check(d);
      ADD_FAILURE() << "accepted: " << pointer;
    } catch (const InputError& e) {
      EXPECT_EQ(e.pointer(), pointer) << e.what();
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  // The same tie twice, written the other way round: the second is implied by the first.
  json d = columns({I, I, I}, true);
  d["ties"].push_back({{"nodes", {"T2", "T1"}}, {"dofs", {"ux"}}});
  refused(d, "/ties/2", "redundant");
  // A tie between two supported DOFs holds already.
  d = columns({I, I, I}, false);
  d["ties"] = {{{"nodes", {"B1", "B2"}}, {"dofs", {"uz"}}}};
  refused(d, "/ties/0", "redundant");
  // A prescribed settlement of B1 tied to the fixed B2: they cannot both hold.
  d = columns({I, I, I}, false);
  d["supports"][0]["fix"] = {"ux", "uy", "rx", "ry", "rz"};
  d["prescribed"] = {{{"node", "B1"}, {"dof", "uz"}, {"value", -0.01}}};
  d["ties"] = {{{"nodes", {"B1", "B2"}}, {"dofs", {"uz"}}}};
  refused(d, "/ties/0", "contradicts");
  // Two constraints that hold one DOF at two values.
  d = columns({I, I, I}, false);
  d["constraints"] = {{{"terms", {{{"node", "T1"}, {"dof", "ux"}, {"coefficient", 1.0}}}}, {"value", 0.01}},
                      {{"terms", {{{"node", "T1"}, {"dof", "ux"}, {"coefficient", 2.0}}}}, {"value", 0.03}}};
  refused(d, "/constraints/1", "contradicts");
  d["constraints"][1]["value"] = 0.02;
  refused(d, "/constraints/1", "redundant");
}

TEST(Springs, ANodeOnSpringsAloneCarriesItsLoad) {
  // A node N held only by a virtual spring of stiffness k to the fixed node G (no elements): the
  // spring carries the load, u = F / k, and G takes -F.
  const double k = 2.0e6, kr = 5.0e4, F = 300.0, M = 20.0;
  json d{{"nodes", {{{"id", "G"}, {"xyz", {0, 0, 0}}}, {{"id", "N"}, {"xyz", {0, 0, 0}}}}},
         {"joints", {{{"id", "s"}, {"type", "virtual_spring"}, {"nodes", {"G", "N"}}, {"stiffness", {k, k, k, kr, kr, kr}}}}},
         {"supports", {{{"node", "G"}, {"fix", "all"}}}},
         {"loads", {{{"node", "N"}, {"force", {F, 0, 0}}, {"moment", {0, 0, M}}}}},
         {"analyses", {{{"id", "lin"}, {"type", "linear_static"}}}}};
  const ojson lin = analyses(d)["lin"];
  ASSERT_EQ(lin["status"], "ok") << lin.dump();
  const auto u = numbers(lin["nodes"]["N"]["displacement"]);
  EXPECT_NEAR(u[0] / (F / k), 1.0, 1e-12);
  EXPECT_NEAR(u[5] / (M / kr), 1.0, 1e-12);
  EXPECT_NEAR(numbers(lin["nodes"]["G"]["reaction"])[0], -F, 1e-9 * F);
  // Nothing that carries a load (the joint passive): still refused.
  d["joints"][0].erase("stiffness");
  try {
    load_and_check(d);
    ADD_FAILURE() << "a model of passive joints alone was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.pointer(), "/elements") << e.what();
  }
}

}  // namespace ties_and_constraints_test
