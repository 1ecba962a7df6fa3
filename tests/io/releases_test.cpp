// Member end releases ("releases": {"start": [...], "end": [...]}, elements/released_element.hpp)
// from the model file through every analysis: closed forms of pinned members, the mechanisms that
// releases make, and bad input (exit 2 naming the field).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "io/run.hpp"
#include "support/cli_case.hpp"
#include "support/models.hpp"

namespace releases_test {

using namespace beamfea;
using nlohmann::json;
using std::numbers::pi;

namespace {

const double L = 2.0, E = 2.1e11, G = 8.1e10, A = 1e-3, Iy = 2e-6, Iz = 3e-6, J = 1e-6;

// A member A-B along x in `divisions` segments, both nodes clamped ("fix": "all"), with `releases`.
json clamped_member(int divisions, const json& releases) {
  json d = test::cantilever(L, E, G, A, Iy, Iz, J, divisions);
  d["supports"] = {{{"node", "A"}, {"fix", "all"}}, {{"node", "B"}, {"fix", "all"}}};
  if (!releases.is_null()) d["elements"][0]["releases"] = releases;
  return d;
}

ojson run(const json& d) {
  const Model m = load_and_check(d);
  return run_document(m, d, RunOptions{}).results;
}

double at(const ojson& v, std::size_t k) { return v[k].get<double>(); }

}  // namespace

// A uniform load q (local -y) on a member clamped at A and pinned at B by "end": ["ry", "rz"] (in
// 4 segments: the last one takes the release) is the propped cantilever: R_B = 3qL/8,
// R_A = 5qL/8, M_A = qL^2/8 (Roark's Formulas for Stress and Strain, 7th ed., Table 8.1 case 2e),
// and no moment at the pinned end. Euler-Bernoulli elements with consistent loads are exact.
TEST(Releases, PinnedEndGivesTheProppedCantileversReactions) {
  const double q = 1500.0;
  json d = clamped_member(4, {{"end", {"ry", "rz"}}});
  d["loads"] = {{{"element", "e"}, {"distributed", {0, -q, 0}}}};
  d["analyses"] = {{{"id", "lin"}, {"type", "linear_static"}}};
  ojson a = run(d)["analyses"]["lin"];
  const ojson& RA = a["nodes"]["A"]["reaction"];
  const ojson& RB = a["nodes"]["B"]["reaction"];
  const double tol = 1e-9 * q * L * L;
  EXPECT_NEAR(at(RB, 1), 3 * q * L / 8, tol);
  EXPECT_NEAR(at(RA, 1), 5 * q * L / 8, tol);
  EXPECT_NEAR(at(RA, 5), q * L * L / 8, tol);  // counter-clockwise on the support: the load turns the beam clockwise
  EXPECT_NEAR(at(RB, 5), 0.0, tol);
  // The member's end force at B and the last station: no moment; the maximum sagging moment
  // 9 q L^2 / 128 at 5L/8 from the clamp lies between stations, the moment at L/2 is q L^2/16.
  EXPECT_NEAR(at(a["elements"]["e"]["end_forces"][1], 5), 0.0, tol);
  const ojson& st = a["elements"]["e"]["stations"];
  EXPECT_NEAR(at(st.back()["forces"], 5), 0.0, tol);
  for (const auto& s : st) {
    if (std::abs(s["x"].get<double>() - L / 2) < 1e-12) {
      EXPECT_NEAR(std::abs(at(s["forces"], 5)), q * L * L / 16, tol);
    }
  }
}

// A beam pinned at both ends by releases (ry, rz at the start and the end; the nodes clamped)
// buckles at Euler's load pi^2 E I / L^2 (I the smaller of Iy, Iz), not at the clamped 4 pi^2 E I / L^2.
// In 8 segments the cubic elements' discretisation error is below 1e-4.
TEST(Releases, ColumnPinnedByReleasesBucklesAtEulersLoad) {
  json d = clamped_member(8, {{"start", {"ry", "rz"}}, {"end", {"ry", "rz"}}});
  d["supports"][1]["fix"] = {"uy", "uz", "rx", "ry", "rz"};
  const double P = 1000.0;
  d["loads"] = {{{"node", "B"}, {"force", {-P, 0, 0}}}};
  d["analyses"] = {{{"id", "b"}, {"type", "buckling"}, {"modes", 2}}};
  ojson a = run(d)["analyses"]["b"];
  const double Pcr = pi * pi * E * Iy / (L * L);
  EXPECT_NEAR(a["load_factors"][0].get<double>(), Pcr / P, 1e-4 * Pcr / P) << a.dump();
  EXPECT_NEAR(a["load_factors"][1].get<double>(), pi * pi * E * Iz / (L * L) / P, 1e-4 * Pcr / P);
}

// A simply supported beam made by releases vibrates at the pinned-pinned frequency of a beam with
// rotary inertia (the consistent mass has it; Rayleigh's beam, whose sine mode is exact):
//   f_1 = (pi / (2 L^2)) sqrt(E I / (rho A)) / sqrt(1 + (pi/L)^2 I/A)
// (Blevins, Formulas for Natural Frequency and Mode Shape, Table 8-1, with Rayleigh's correction;
// Han, Benaroya & Wei, J. Sound Vib. 225 (1999) 935-988, the Rayleigh beam). The condensed mass of
// the end segments converges with the segments (16 here: below 1e-5; asserted 1e-4, where the
// correction is 2.5e-3).
TEST(Releases, BeamPinnedByReleasesVibratesAtTheSimplySupportedFrequency) {
  const double rho = 7850.0;
  json d = clamped_member(16, {{"start", {"ry", "rz"}}, {"end", {"ry", "rz"}}});
  d["materials"][0]["density"] = rho;
  d["analyses"] = {{{"id", "m"}, {"type", "modal"}, {"modes", 2}}};
  ojson a = run(d)["analyses"]["m"];
  for (int k = 0; k < 2; ++k) {
    const double I = k == 0 ? Iy : Iz;
    const double f = pi / (2 * L * L) * std::sqrt(E * I / (rho * A)) / std::sqrt(1 + pi * pi / (L * L) * I / A);
    EXPECT_NEAR(a["frequencies"][k].get<double>(), f, 1e-4 * f) << a["frequencies"].dump();
  }
}

// The stiffness of the pinned end's node: a propped cantilever's tip (fixed at A, pinned at B by
// the release, B free) against a force at B: 3 E I / L^3 (Roark Table 8.1 case 1a), and no
// rotational stiffness about the released axes.
TEST(Releases, StiffnessAtAPinnedEndIsTheCantileversWithoutItsRotation) {
  json d = test::cantilever(L, E, G, A, Iy, Iz, J, 3);
  d["elements"][0]["releases"] = {{"end", {"ry", "rz"}}};
  d["analyses"] = {{{"id", "K"}, {"type", "stiffness"}, {"node", "B"}}};
  ojson a = run(d)["analyses"]["K"];
  EXPECT_NEAR(a["matrix"][1][1].get<double>(), 3 * E * Iz / (L * L * L), 1e-9 * 3 * E * Iz / (L * L * L));
  EXPECT_NEAR(a["matrix"][2][2].get<double>(), 3 * E * Iy / (L * L * L), 1e-9 * 3 * E * Iy / (L * L * L));
  EXPECT_EQ(a["rank"].get<int>(), 4) << a.dump();  // ry, rz of B are held by nothing
}

// A path analysis under a small load follows the linear answer: a propped cantilever (pinned at B
// by the release) with a central point force P (at the internal node e#1) deflects by
// 7 P L^3 / (768 E I) there (Roark Table 8.1 case 1c). The load keeps the deflection near
// L/10^5, where the co-rotational answer differs from the linear one by less than 1e-6.
TEST(Releases, PathAnalysisOfAProppedCantileverFollowsTheLinearDeflection) {
  json d = clamped_member(2, {{"end", {"ry", "rz"}}});
  const double w = 7.0 / 768.0 * L * L * L / (E * Iz), P = 1e-5 * L / w;
  d["loads"] = {{{"node", "e#1"}, {"force", {0, -P, 0}}}};
  d["analyses"] = {{{"id", "p"}, {"type", "path"}, {"track", {"e#1"}}, {"control", {{"load_factor", 1.0}, {"increments", 2}}}}};
  ojson a = run(d)["analyses"]["p"];
  ASSERT_EQ(a["status"], "ok") << a.dump();
  const double v = a["steps"].back()["nodes"]["e#1"]["displacement"][1].get<double>();
  EXPECT_NEAR(v, -P * w, 1e-6 * P * w);
}

// A release that lets the member slide (uy at the clamped start) leaves the tip free to move along
// y: the linear analysis fails (exit 1) naming the member and its release.
TEST(Releases, SlidingReleaseAtTheOnlySupportIsAMechanismNamingTheElement) {
  json d = test::linear_cantilever(-1000.0, 2);
  d["elements"][0]["releases"] = {{"start", {"uy"}}};
  const test::CliCase r = test::run_model("release_mechanism", d);
  EXPECT_EQ(r.code, 1) << r.message;
  ASSERT_TRUE(r.results_written());
  const std::string message = r.results()["analyses"]["lin"]["message"].get<std::string>();
  EXPECT_NE(message.find("mechanism"), std::string::npos) << message;
  EXPECT_NE(message.find("'e' (released start: uy)"), std::string::npos) << message;
}

// Releases that leave the member itself a mechanism (torsion free at both ends): exit 2 at the
// field, naming the element.
TEST(Releases, TorsionReleasedAtBothEndsIsRejected) {
  json d = test::linear_cantilever(-1000.0);
  d["elements"][0]["releases"] = {{"start", {"rx"}}, {"end", {"rx"}}};
  test::expect_bad_input(test::run_model("release_torsion", d),
                         {"/elements/0/releases", "element 'e'", "start: rx; end: rx", "mechanism"});
}

TEST(Releases, BadReleaseFieldsAreRejectedNamingThem) {
  json d = test::linear_cantilever(-1000.0);
  d["elements"][0]["releases"] = {{"start", {"ry", "rq"}}};
  test::expect_bad_input(test::run_model("release_name", d), {"/elements/0/releases/start/1", "rq", "ux uy uz rx ry rz"});
  d["elements"][0]["releases"] = {{"begin", {"ry"}}};
  test::expect_bad_input(test::run_model("release_key", d), {"/elements/0/releases", "begin", "start"});
  d["elements"][0]["releases"] = {{"end", {"rz", "rz"}}};
  test::expect_bad_input(test::run_model("release_twice", d), {"/elements/0/releases/end/1", "twice"});
  d["elements"][0]["releases"] = {{"end", "rz"}};
  test::expect_bad_input(test::run_model("release_array", d), {"/elements/0/releases/end"});
}

// Segments: the start releases go to the first segment, the end releases to the last.
TEST(Releases, DividedMemberReleasesItsFirstAndLastSegments) {
  json d = clamped_member(3, {{"start", {"rz"}}, {"end", {"uy", "rx"}}});
  const Model m = test::model_from(d);
  ASSERT_EQ(m.elements.size(), 3u);
  EXPECT_TRUE(m.elements[0].released[5]);
  EXPECT_EQ(std::count(m.elements[0].released.begin(), m.elements[0].released.end(), true), 1);
  EXPECT_FALSE(m.elements[1].has_releases());
  EXPECT_TRUE(m.elements[2].released[6 + 1] && m.elements[2].released[6 + 3]);
  EXPECT_EQ(std::count(m.elements[2].released.begin(), m.elements[2].released.end(), true), 2);
}

}  // namespace releases_test
