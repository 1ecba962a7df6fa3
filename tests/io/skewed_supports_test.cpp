// Skewed supports ("axes" on a support): an inclined roller against statics, the reaction in both
// frames, and a column whose support frames are turned about its axis against the same column on
// plain supports (linear, modal and buckling analyses).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.hpp"
#include "io/run.hpp"

namespace skewed_supports_test {

using namespace beamfea;
using nlohmann::json;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double E = 2.0e11, G = 8.0e10, A = 1.0e-3, I = 2.0e-6, J = 1.0e-6;

// The analyses of a document, run in memory as `beamfea run` runs them.
ojson analyses(const json& doc) {
  const Model m = load_and_check(doc);
  return run_document(m, doc, RunOptions{}).results["analyses"];
}

std::vector<double> numbers(const ojson& v) { return v.get<std::vector<double>>(); }

// Rows: the axes of a frame turned by `angle` about global z.
json frame_about_z(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return json{{c, s, 0.0}, {-s, c, 0.0}, {0.0, 0.0, 1.0}};
}

// A simply supported beam A-C-B along x (length L, C at mid-span) loaded by P along -y at C: A is
// pinned (ux uy uz rx), B rolls on a plane of the x-y plane inclined by `alpha`: the support frame
// is turned by alpha about z and holds its uy (the plane's normal) and uz.
json inclined_roller(double L, double P, double alpha) {
  return json{
      {"nodes", {{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "C"}, {"xyz", {L / 2, 0, 0}}}, {{"id", "B"}, {"xyz", {L, 0, 0}}}}},
      {"materials", {{{"id", "m"}, {"E", E}, {"G", G}}}},
      {"sections", {{{"id", "s"}, {"A", A}, {"Iy", I}, {"Iz", I}, {"J", J}}}},
      {"elements",
       {{{"id", "e1"}, {"type", "beam"}, {"nodes", {"A", "C"}}, {"material", "m"}, {"section", "s"}, {"orientation", {0, 0, 1}}},
        {{"id", "e2"}, {"type", "beam"}, {"nodes", {"C", "B"}}, {"material", "m"}, {"section", "s"}, {"orientation", {0, 0, 1}}}}},
      {"supports",
       {{{"node", "A"}, {"fix", {"ux", "uy", "uz", "rx"}}}, {{"node", "B"}, {"fix", {"uy", "uz"}}, {"axes", frame_about_z(alpha)}}}},
      {"loads", {{{"node", "C"}, {"force", {0, -P, 0}}}}},
      {"analyses", {{{"id", "lin"}, {"type", "linear_static"}}}}};
}

// A column along z from the base A to the top B (length H, `divisions` elements) on a circular
// section; A is fixed, B is held against one horizontal translation. `turn`: the angle by which
// both support frames are turned about the column's axis (z); the top holds its frame's uy, whose
// direction is (-sin turn, cos turn, 0). An axial load -P at B for the buckling analysis.
json column(double H, double turn, bool skewed, int divisions) {
  json d{{"nodes", {{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {0, 0, H}}}}},
         {"materials", {{{"id", "m"}, {"E", E}, {"G", G}, {"density", 7850.0}}}},
         {"sections", {{{"id", "s"}, {"A", A}, {"Iy", I}, {"Iz", 3 * I}, {"J", J}}}},
         {"elements",
          {{{"id", "c"}, {"type", "beam"}, {"nodes", {"A", "B"}}, {"material", "m"}, {"section", "s"},
            {"orientation", {1, 0, 0}}, {"divisions", divisions}}}},
         {"loads", {{{"node", "B"}, {"force", {0, 0, -1000.0}}}}},
         {"analyses",
          {{{"id", "b"}, {"type", "buckling"}, {"modes", 3}},
           {{"id", "f"}, {"type", "modal"}, {"modes", 4}},
           {{"id", "lin"}, {"type", "linear_static"}}}}};
  if (skewed) {
    d["supports"] = {{{"node", "A"}, {"fix", "all"}, {"axes", frame_about_z(turn)}},
                     {{"node", "B"}, {"fix", {"uy"}}, {"axes", frame_about_z(turn)}}};
  } else {
    d["supports"] = {{{"node", "A"}, {"fix", "all"}}, {{"node", "B"}, {"fix", {"uy"}}}};
  }
  return d;
}

}  // namespace

TEST(SkewedSupports, InclinedRollerReactionsFollowFromStatics) {
  // Statics of the beam: the roller's reaction N is along the plane's normal n = (-sin a, cos a, 0);
  // moments about A: N cos(a) L = P L / 2, so N = P / (2 cos a); then A takes (P tan(a) / 2, P / 2).
  const double L = 4.0, P = 1000.0, alpha = kPi / 6;
  const ojson lin = analyses(inclined_roller(L, P, alpha))["lin"];
  ASSERT_EQ(lin["status"], "ok") << lin.dump();
  const double N = P / (2 * std::cos(alpha));
  const auto rB = numbers(lin["nodes"]["B"]["reaction"]);
  const auto rB_local = numbers(lin["nodes"]["B"]["reaction_local"]);
  const auto rA = numbers(lin["nodes"]["A"]["reaction"]);
  constexpr double tol = 1e-9 * 1000.0;
  EXPECT_NEAR(rB[0], -N * std::sin(alpha), tol);
  EXPECT_NEAR(rB[1], N * std::cos(alpha), tol);
  EXPECT_NEAR(rB[2], 0.0, tol);
  // In the support's frame: all along its y (the normal), nothing along the plane.
  EXPECT_NEAR(rB_local[0], 0.0, tol);
  EXPECT_NEAR(rB_local[1], N, tol);
  EXPECT_NEAR(rB_local[2], 0.0, tol);
  EXPECT_NEAR(rA[0], P * std::tan(alpha) / 2, tol);
  EXPECT_NEAR(rA[1], P / 2, tol);
  EXPECT_FALSE(lin["nodes"]["A"].contains("reaction_local"));  // a support in global axes
  // The beam is squeezed by the horizontal reactions: N_x = -P tan(a) / 2, so B moves by
  // u_x = N_x L / EA, and along the plane: u_y = tan(a) u_x (B stays on it).
  const auto uB = numbers(lin["nodes"]["B"]["displacement"]);
  const double ux = -P * std::tan(alpha) / 2 * L / (E * A);
  EXPECT_NEAR(uB[0] / ux, 1.0, 1e-9);
  EXPECT_NEAR(uB[1] / (std::tan(alpha) * ux), 1.0, 1e-9);
}

TEST(SkewedSupports, APathKeepsTheRollerOnItsPlane) {
  // The path holds the roller's row as a constraint on the displacement: B stays on the plane
  // (n . u = 0 to the corrector's tolerance). Under a small load the mid-span deflection is the
  // linear one: P L^3 / 48 E I, plus half of B's drop along the plane, tan(a) u_x(B) / 2 with
  // u_x(B) = -P tan(a) L / (2 E A); the axial force's P-delta (N / N_cr ~ 1e-5) and the bow's
  // shortening (slope^2 ~ 1e-9) stay below the tolerance.
  const double L = 4.0, P = 10.0, alpha = kPi / 6;
  json d = inclined_roller(L, P, alpha);
  d["analyses"] = {{{"id", "p"}, {"type", "path"}, {"control", {{"load_factor", 1.0}, {"increments", 2}}}, {"track", {"B", "C"}}}};
  const ojson p = analyses(d)["p"];
  ASSERT_EQ(p["status"], "ok") << p.dump();
  const auto uB = numbers(p["steps"].back()["nodes"]["B"]["displacement"]);
  const auto uC = numbers(p["steps"].back()["nodes"]["C"]["displacement"]);
  EXPECT_NEAR(-std::sin(alpha) * uB[0] + std::cos(alpha) * uB[1], 0.0, 1e-10 * L);
  const double uxB = -P * std::tan(alpha) / 2 * L / (E * A);
  EXPECT_NEAR(uC[1] / (-P * L * L * L / (48 * E * I) + std::tan(alpha) * uxB / 2), 1.0, 1e-4);
}

TEST(SkewedSupports, AFrameTurnedAboutTheColumnAxisIsTheSameColumn) {
  // A quarter turn: the top's frame-uy is global -x, so the skewed top holds ux, and the column
  // equals the plain one holding ux (and the base frame is a rotation of a fixed support: fixed).
  const double H = 3.0;
  json plain = column(H, 0.0, false, 8);
  plain["supports"][1]["fix"] = {"ux"};
  const ojson turned = analyses(column(H, kPi / 2, true, 8));
  const ojson same = analyses(plain);
  for (const char* a : {"b", "f"}) ASSERT_EQ(turned[a]["status"], "ok") << turned[a].dump();
  const auto fb = numbers(turned["b"]["load_factors"]), fp = numbers(same["b"]["load_factors"]);
  ASSERT_EQ(fb.size(), fp.size());
  for (std::size_t k = 0; k < fb.size(); ++k) EXPECT_NEAR(fb[k] / fp[k], 1.0, 1e-9) << "buckling mode " << k;
  const auto wb = numbers(turned["f"]["frequencies"]), wp = numbers(same["f"]["frequencies"]);
  ASSERT_EQ(wb.size(), wp.size());
  for (std::size_t k = 0; k < wb.size(); ++k) EXPECT_NEAR(wb[k] / wp[k], 1.0, 1e-9) << "mode " << k;
  // The lowest buckling load: held along x (the weak plane: local z = global x, so sway along x
  // bends about local y, Iy = I), the column sways along y as a cantilever bending about local z
  // (Iz = 3I): Euler's P = pi^2 E Iz / (4 H^2) = 0.75 pi^2 E I / H^2, below the propped weak
  // plane's 2.05 pi^2 E I / H^2.
  const double EI_sway = 3 * E * I;
  EXPECT_NEAR(fb[0] * 1000.0 / (kPi * kPi * EI_sway / (4 * H * H)), 1.0, 1e-4);
}

TEST(SkewedSupports, ATopHeldAlongAnInclinedDirectionSwaysAlongTheOther) {
  // Turned by 30 degrees about the axis, the top is held along n = (-sin 30, cos 30, 0) and the
  // column sways along t = (cos 30, sin 30, 0) under a lateral load F t at the top: a cantilever
  // whose sway along global x bends it about local y (Iy = I) and along y about local z (Iz = 3I),
  // loaded along t but held along n: the top's reaction is along n only, the displacement has no
  // n part.
  const double H = 3.0, F = 500.0, turn = kPi / 6;
  json d = column(H, turn, true, 4);
  d["loads"] = {{{"node", "B"}, {"force", {F * std::cos(turn), F * std::sin(turn), 0.0}}}};
  d["analyses"] = {{{"id", "lin"}, {"type", "linear_static"}}};
  const ojson lin = analyses(d)["lin"];
  ASSERT_EQ(lin["status"], "ok") << lin.dump();
  const auto u = numbers(lin["nodes"]["B"]["displacement"]);
  const double un = -std::sin(turn) * u[0] + std::cos(turn) * u[1];
  EXPECT_NEAR(un, 0.0, 1e-12);
  const auto r = numbers(lin["nodes"]["B"]["reaction_local"]);
  EXPECT_NEAR(r[0], 0.0, 1e-9 * F);  // along the free direction t: nothing
  // Equilibrium along the frame's y: the base takes F t - R n, the top R n; with u = s t, the
  // cantilever's tip force K u (K = 3 E diag(Iy_x, Iz_y) / H^3 for the two bending planes) equals
  // F t + R n (R n: the reaction on the top), so R = n . K t s and s from t . K t s = F.
  const double kx = 3 * E * I / (H * H * H), ky = 3 * E * 3 * I / (H * H * H);
  const double tx = std::cos(turn), ty = std::sin(turn), nx = -ty, ny = tx;
  const double s = F / (tx * kx * tx + ty * ky * ty);
  EXPECT_NEAR(u[0] / (s * tx), 1.0, 1e-9);
  EXPECT_NEAR(r[1] / ((nx * kx * tx + ny * ky * ty) * s), 1.0, 1e-9);
}

TEST(SkewedSupports, AxesThatAreNotOrthonormalAreBadInputNamingTheSupport) {
  json d = inclined_roller(4.0, 1000.0, 0.3);
  d["supports"][1]["axes"] = {{1, 0, 0}, {0.1, 1, 0}, {0, 0, 1}};
  try {
    load_and_check(d);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.pointer(), "/supports/1/axes");
    EXPECT_NE(std::string(e.what()).find("orthonormal"), std::string::npos) << e.what();
  }
}

}  // namespace skewed_supports_test
