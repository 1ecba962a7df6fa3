// Rigid end zones and offsets ("rigid_ends": [r_start, r_end], "offsets": {"start": [..], "end": [..]},
// elements/offset_element.hpp) from the model file through the analyses: closed forms of a member
// seen through rigid arms, an eccentric cantilever's torsion, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "io/run.hpp"
#include "support/cli_case.hpp"
#include "support/models.hpp"

namespace offsets_test {

using namespace beamfea;
using nlohmann::json;
using std::numbers::pi;

namespace {

const double L = 2.0, E = 2.1e11, G = 8.1e10, A = 1e-3, Iy = 2e-6, Iz = 3e-6, J = 1e-6;

ojson run(const json& d) {
  const Model m = load_and_check(d);
  return run_document(m, d, RunOptions{}).results;
}

double at(const ojson& v, std::size_t k) { return v[k].get<double>(); }

}  // namespace

// A cantilever (A clamped) with rigid ends r1 at A and r2 at B, a force P (y) at B: the flexible
// part, Lf = L - r1 - r2 long, is clamped through the rigid arm at A and carries at its end the
// shear P and the moment P r2 of the arm at B, so (Timoshenko & Gere, Mechanics of Materials,
// App. G, cases of a tip force and a tip moment)
//   v_f = P Lf^3 / (3 E I) + P r2 Lf^2 / (2 E I),  theta_f = P Lf^2 / (2 E I) + P r2 Lf / (E I),
// and node B, rigidly r2 beyond it, moves by v_f + r2 theta_f.
TEST(Offsets, CantileverWithRigidEndsDeflectsAsItsFlexibleLength) {
  const double r1 = 0.3, r2 = 0.2, P = 1000.0, Lf = L - r1 - r2;
  json d = test::cantilever(L, E, G, A, Iy, Iz, J, 3);
  d["elements"][0]["rigid_ends"] = {r1, r2};
  d["loads"] = {{{"node", "B"}, {"force", {0, P, 0}}}};
  d["analyses"] = {{{"id", "lin"}, {"type", "linear_static"}}};
  ojson a = run(d)["analyses"]["lin"];
  const double EI = E * Iz;
  const double vf = P * Lf * Lf * Lf / (3 * EI) + P * r2 * Lf * Lf / (2 * EI);
  const double tf = P * Lf * Lf / (2 * EI) + P * r2 * Lf / EI;
  const ojson& u = a["nodes"]["B"]["displacement"];
  EXPECT_NEAR(at(u, 1), vf + r2 * tf, 1e-9 * vf);
  EXPECT_NEAR(at(u, 5), tf, 1e-9 * tf);
  // Section forces at the flexible ends: the moment P (r2 + Lf) at the flexible start (the clamp
  // carries P L through the arm), P r2 at the flexible end; the stations span the flexible length.
  const ojson& st = a["elements"]["e"]["stations"];
  EXPECT_NEAR(std::abs(at(st.front()["forces"], 5)), P * (r2 + Lf), 1e-9 * P * L);
  EXPECT_NEAR(std::abs(at(st.back()["forces"], 5)), P * r2, 1e-9 * P * L);
  EXPECT_NEAR(st.back()["x"].get<double>(), Lf, 1e-12 * L);
  EXPECT_NEAR(at(a["nodes"]["A"]["reaction"], 5), -P * L, 1e-9 * P * L);
}

// The stiffness at B of the same member with rigid ends r at both ends is the flexible length's
// tip stiffness seen through the arm r (x_f = x_B - r, v_f = v_B - r theta_B):
//   K_vv = 12 E I / Lf^3, K_v theta = -(12 E I r / Lf^3 + 6 E I / Lf^2),
//   K_theta theta = 12 E I r^2 / Lf^3 + 12 E I r / Lf^2 + 4 E I / Lf  (Lf = L - 2 r).
TEST(Offsets, StiffnessThroughRigidEndsIsTheShorterBeamsSeenThroughTheArms) {
  const double r = 0.25, Lf = L - 2 * r, EI = E * Iz;
  json d = test::cantilever(L, E, G, A, Iy, Iz, J, 1);
  d["elements"][0]["rigid_ends"] = {r, r};
  d["analyses"] = {{{"id", "K"}, {"type", "stiffness"}, {"node", "B"}}};
  ojson K = run(d)["analyses"]["K"]["matrix"];
  const double kvv = 12 * EI / std::pow(Lf, 3), kvt = -(12 * EI * r / std::pow(Lf, 3) + 6 * EI / (Lf * Lf));
  const double ktt = 12 * EI * r * r / std::pow(Lf, 3) + 12 * EI * r / (Lf * Lf) + 4 * EI / Lf;
  // Local y is global y, rz global z: the x-y plane's terms (the sign of K_v,rz: Przemieniecki's
  // -6 E I / L^2 at the j end).
  EXPECT_NEAR(K[1][1].get<double>(), kvv, 1e-9 * kvv);
  EXPECT_NEAR(K[1][5].get<double>(), kvt, 1e-9 * std::abs(kvt));
  EXPECT_NEAR(K[5][5].get<double>(), ktt, 1e-9 * ktt);
  EXPECT_NEAR(K[0][0].get<double>(), E * A / Lf, 1e-9 * E * A / Lf);
}

// An eccentric cantilever: its axis runs at the offset e (global z) from the nodes' line, and a
// force P (y) at node B acts on the flexible end through the arm: a torque e P, so
//   v_B = P L^3 / (3 E Iz) + e^2 P L / (G J),
// the member's torque is e P, and the support, on the nodes' line, takes no torque (statics).
TEST(Offsets, EccentricCantileverTwistsByTheLeverArm) {
  const double e = 0.15, P = 1000.0;
  json d = test::cantilever(L, E, G, A, Iy, Iz, J, 2);
  d["elements"][0]["offsets"] = {{"start", {0, 0, e}}, {"end", {0, 0, e}}};
  d["loads"] = {{{"node", "B"}, {"force", {0, P, 0}}}};
  d["analyses"] = {{{"id", "lin"}, {"type", "linear_static"}}};
  ojson a = run(d)["analyses"]["lin"];
  const double v = P * L * L * L / (3 * E * Iz) + e * e * P * L / (G * J);
  EXPECT_NEAR(at(a["nodes"]["B"]["displacement"], 1), v, 1e-9 * v);
  EXPECT_NEAR(at(a["nodes"]["B"]["displacement"], 3), e * P * L / (G * J), 1e-9 * e * P * L / (G * J));
  EXPECT_NEAR(at(a["elements"]["e"]["end_forces"][1], 3), e * P, 1e-9 * e * P);
  const ojson& RA = a["nodes"]["A"]["reaction"];
  EXPECT_NEAR(at(RA, 3), 0.0, 1e-9 * P * L);
  EXPECT_NEAR(at(RA, 5), -P * L, 1e-9 * P * L);
}

// The same eccentric cantilever in a path analysis under a small load (v_B ~ 1e-5 L): the finite
// rigid arms of the co-rotational element give the linear answer to 1e-6.
TEST(Offsets, PathAnalysisOfTheEccentricCantileverFollowsTheLinearAnswer) {
  const double e = 0.15;
  json d = test::cantilever(L, E, G, A, Iy, Iz, J, 2);
  d["elements"][0]["offsets"] = {{"start", {0, 0, e}}, {"end", {0, 0, e}}};
  const double w = L * L * L / (3 * E * Iz) + e * e * L / (G * J), P = 1e-5 * L / w;
  d["loads"] = {{{"node", "B"}, {"force", {0, P, 0}}}};
  d["analyses"] = {{{"id", "p"}, {"type", "path"}, {"track", {"B"}}, {"control", {{"load_factor", 1.0}, {"increments", 2}}}}};
  ojson a = run(d)["analyses"]["p"];
  ASSERT_EQ(a["status"], "ok") << a.dump();
  EXPECT_NEAR(a["steps"].back()["nodes"]["B"]["displacement"][1].get<double>(), P * w, 1e-6 * P * w);
}

// A member clamped at both nodes with rigid ends r: its flexible part, Lf = L - 2 r, is a
// clamped-clamped beam: buckling load 4 pi^2 E I / Lf^2 under an axial force (the far node free
// along the axis; Timoshenko & Gere, Theory of Elastic Stability, 2.3), and the frequencies of the
// same beam built Lf long between clamped nodes (the arms carry no mass), to round-off.
TEST(Offsets, RigidEndsShortenTheMembersFrequencyAndBucklingLength) {
  const double r = 0.2, Lf = L - 2 * r, rho = 7850.0, P = 1000.0;
  json d = test::cantilever(L, E, G, A, Iy, Iz, J, 16);
  d["elements"][0]["rigid_ends"] = {r, r};
  d["materials"][0]["density"] = rho;
  d["supports"] = {{{"node", "A"}, {"fix", "all"}}, {{"node", "B"}, {"fix", {"uy", "uz", "rx", "ry", "rz"}}}};
  d["loads"] = {{{"node", "B"}, {"force", {-P, 0, 0}}}};
  d["analyses"] = {{{"id", "m"}, {"type", "modal"}, {"modes", 4}}, {{"id", "b"}, {"type", "buckling"}, {"modes", 1}}};
  ojson res = run(d)["analyses"];
  const double Pcr = 4 * pi * pi * E * Iy / (Lf * Lf);
  EXPECT_NEAR(res["b"]["load_factors"][0].get<double>(), Pcr / P, 1e-4 * Pcr / P);
  json s = test::cantilever(Lf, E, G, A, Iy, Iz, J, 16);
  s["materials"][0]["density"] = rho;
  s["supports"] = d["supports"];
  s["analyses"] = {{{"id", "m"}, {"type", "modal"}, {"modes", 4}}};
  ojson short_beam = run(s)["analyses"]["m"];
  for (int k = 0; k < 4; ++k) {
    const double f = short_beam["frequencies"][k].get<double>();
    EXPECT_NEAR(res["m"]["frequencies"][k].get<double>(), f, 1e-9 * f) << "mode " << k + 1;
  }
}

// The .vtu draws each rigid arm as a line from its node to the flexible end: a member in 2
// segments (8 lines each, 9 points) with arms at both ends has 2 arm lines and 2 node points more;
// the segments' shared internal node has no arm.
TEST(Offsets, VtuDrawsTheArmsAsLinesFromTheNodes) {
  json d = test::linear_cantilever(1000.0, 2);
  d["elements"][0]["offsets"] = {{"start", {0, 0, 0.15}}, {"end", {0, 0, 0.15}}};
  const test::CliCase r = test::run_model("offsets_vtu", d);
  ASSERT_EQ(r.code, 0) << r.message;
  const std::string vtu = test::read_text(r.out() / "lin.vtu");
  const auto count = [&](const std::string& key) {
    const auto at = vtu.find(key + "=\"");
    return at == std::string::npos ? -1 : std::stoi(vtu.substr(at + key.size() + 2));
  };
  EXPECT_EQ(count("NumberOfPoints"), 2 * 9 + 2);
  EXPECT_EQ(count("NumberOfCells"), 2 * 8 + 2);
}

TEST(Offsets, BadRigidEndsAndOffsetsAreRejectedNamingThem) {
  json d = test::linear_cantilever(-1000.0);
  d["elements"][0]["rigid_ends"] = {1.5, 0.5};
  test::expect_bad_input(test::run_model("rigid_ends_long", d), {"/elements/0/rigid_ends", "element 'e'", "nothing flexible"});
  d["elements"][0]["rigid_ends"] = {-0.1, 0.0};
  test::expect_bad_input(test::run_model("rigid_ends_negative", d), {"/elements/0/rigid_ends/0", ">= 0"});
  d["elements"][0]["rigid_ends"] = {0.1};
  test::expect_bad_input(test::run_model("rigid_ends_one", d), {"/elements/0/rigid_ends", "[r_start, r_end]"});
  d["elements"][0].erase("rigid_ends");
  d["elements"][0]["offsets"] = {{"begin", {0, 0, 0.1}}};
  test::expect_bad_input(test::run_model("offsets_key", d), {"/elements/0/offsets", "begin", "start"});
  d["elements"][0]["offsets"] = {{"start", {0, 0}}};
  test::expect_bad_input(test::run_model("offsets_vec", d), {"/elements/0/offsets/start"});
  d["elements"][0]["offsets"] = {{"end", {-2.0, 0, 0}}};
  test::expect_bad_input(test::run_model("offsets_collapse", d), {"/elements/0/offsets", "together"});
  d["elements"][0].erase("offsets");
  d["elements"].push_back({{"id", "r"}, {"type", "rigid"}, {"nodes", {"A", "B"}}, {"rigid_ends", {0.1, 0.1}}});
  test::expect_bad_input(test::run_model("rigid_link_ends", d), {"/elements/1/rigid_ends", "rigid link"});
}

// A path analysis does not take member loads on a member with rigid arms: exit 2 naming the
// analysis and the element; the linear analysis of the same model runs.
TEST(Offsets, PathRejectsMemberLoadsOnAMemberWithArms) {
  json d = test::linear_cantilever(-1000.0);
  d["elements"][0]["rigid_ends"] = {0.1, 0.0};
  d["loads"].push_back({{"element", "e"}, {"distributed", {0, -100, 0}}});
  EXPECT_EQ(test::run_model("arms_member_load_linear", d).code, 0);
  d["analyses"] = {{{"id", "p"}, {"type", "path"}, {"control", {{"load_factor", 1.0}, {"increments", 2}}}}};
  test::expect_bad_input(test::run_model("arms_member_load_path", d), {"/analyses/0", "element 'e'", "path"});
}

}  // namespace offsets_test
