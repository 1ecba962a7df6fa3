// Temperature loads: a material's thermal expansion "alpha" and member loads {"element",
// "temperature": {"uniform", "gradient_y", "gradient_z"}}, through the model file and the analyses,
// against the closed forms of restrained and free thermal deformation.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/errors.hpp"
#include "io/analysis.hpp"
#include "io/run.hpp"
#include "support/cli_case.hpp"
#include "support/errors.hpp"
#include "support/models.hpp"

namespace temperature_loads_test {

using namespace beamfea;
using nlohmann::json;

namespace {

constexpr double E = 2.1e11, G = 8.1e10, A = 1e-3, Iy = 2e-6, Iz = 3e-6, J = 1e-6, L = 2.0;
constexpr double alpha = 1.2e-5;

// A steel cantilever A (fixed) - B in `divisions` segments, alpha given, no loads.
json heated_cantilever(int divisions) {
  json d = test::cantilever(L, E, G, A, Iy, Iz, J, divisions);
  d["materials"][0]["alpha"] = alpha;
  return d;
}

json run(const json& d) {
  const Model m = load_and_check(d);
  const RunReport rep = run_document(m, d, RunOptions{});
  EXPECT_FALSE(rep.failed);
  return rep.results;
}

std::string error_pointer(const json& doc) { return test::input_error_pointer(doc); }

}  // namespace

// A bar clamped at both ends and heated by dT cannot lengthen: N = -E A alpha dT (compression), the
// same at every station, and the supports push with E A alpha dT (any textbook on thermal stress,
// e.g. Timoshenko & Goodier, Theory of Elasticity, sec. 150's restrained bar).
TEST(TemperatureLoads, AClampedBarHeatedUniformlyCarriesEAAlphaDeltaT) {
  const double dT = 40.0;
  json d = heated_cantilever(3);
  d["supports"].push_back({{"node", "B"}, {"fix", "all"}});
  d["loads"] = {{{"element", "e"}, {"temperature", {{"uniform", dT}}}}};
  d["analyses"] = {{{"id", "lin"}, {"type", "linear_static"}}};
  const json r = run(d)["analyses"]["lin"];
  const double N = -E * A * alpha * dT;
  for (const auto& s : r["elements"]["e"]["stations"]) EXPECT_NEAR(s["forces"][0].get<double>(), N, 1e-9 * std::abs(N));
  EXPECT_NEAR(r["nodes"]["A"]["reaction"][0].get<double>(), -N, 1e-9 * std::abs(N));  // pushes the bar towards +x
  EXPECT_NEAR(r["nodes"]["B"]["reaction"][0].get<double>(), N, 1e-9 * std::abs(N));
  EXPECT_NEAR(r["nodes"]["e#1"]["displacement"][0].get<double>(), 0.0, 1e-15);
}

// A free cantilever with a gradient g = dT/dy curves by kappa = alpha g towards -y, stress-free:
// v(x) = -alpha g x^2 / 2, rz = v' = -alpha g x; gradient_z bends it towards -z, w = -alpha g x^2/2,
// ry = -w' = alpha g x. Exact at every node, however many segments.
TEST(TemperatureLoads, AGradientCurvesAFreeCantileverByAlphaTimesTheGradient) {
  const double gy = 50.0, gz = -30.0, dT = 10.0;
  json d = heated_cantilever(4);
  d["loads"] = {{{"element", "e"}, {"temperature", {{"uniform", dT}, {"gradient_y", gy}, {"gradient_z", gz}}}}};
  d["analyses"] = {{{"id", "lin"}, {"type", "linear_static"}}};
  const json r = run(d)["analyses"]["lin"];
  for (const auto& [id, x] : {std::pair<std::string, double>{"e#2", L / 2}, {"B", L}}) {
    const auto& u = r["nodes"][id]["displacement"];
    SCOPED_TRACE(id);
    EXPECT_NEAR(u[0].get<double>(), alpha * dT * x, 1e-12 * L);
    EXPECT_NEAR(u[1].get<double>(), -alpha * gy * x * x / 2, 1e-12 * L);
    EXPECT_NEAR(u[2].get<double>(), -alpha * gz * x * x / 2, 1e-12 * L);
    EXPECT_NEAR(u[4].get<double>(), alpha * gz * x, 1e-12);
    EXPECT_NEAR(u[5].get<double>(), -alpha * gy * x, 1e-12);
  }
  // Statically determinate: no reaction, no section force.
  for (const auto& s : r["elements"]["e"]["stations"])
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(s["forces"][k].get<double>(), 0.0, 1e-6) << k;
}

// Propped cantilever (fixed at A, B held in y only) with a gradient g = dT/dy: the prop cancels the
// free tip deflection alpha g L^2 / 2, R L^3 / (3 E Iz) = alpha g L^2 / 2, so R = 3 E Iz alpha g /
// (2 L) and the moment at the clamp is R L = 3 E Iz alpha g / 2. In a combination at factor 2.
TEST(TemperatureLoads, APropResistsTheThermalCurvatureAsTheClosedFormSays) {
  const double g = 25.0;
  json d = heated_cantilever(2);
  d["supports"].push_back({{"node", "B"}, {"fix", {"uy"}}});
  d["load_cases"] = {{{"id", "sun"}, {"loads", {{{"element", "e"}, {"temperature", {{"gradient_y", g}}}}}}}};
  d["combinations"] = {{{"id", "twice"}, {"factors", {{"sun", 2.0}}}}};
  d["analyses"] = {{{"id", "one"}, {"type", "linear_static"}, {"load_case", "sun"}},
                   {{"id", "two"}, {"type", "linear_static"}, {"load_case", "twice"}}};
  const json r = run(d)["analyses"];
  const double R = 3 * E * Iz * alpha * g / (2 * L);
  EXPECT_NEAR(std::abs(r["one"]["nodes"]["B"]["reaction"][1].get<double>()), R, 1e-9 * R);
  EXPECT_NEAR(std::abs(r["one"]["nodes"]["A"]["reaction"][5].get<double>()), R * L, 1e-9 * R * L);
  EXPECT_NEAR(std::abs(r["two"]["nodes"]["B"]["reaction"][1].get<double>()), 2 * R, 2e-9 * R);
  EXPECT_NEAR(r["one"]["nodes"]["B"]["displacement"][1].get<double>(), 0.0, 1e-15);
}

// The thermal force is a preload like any other: a bar clamped at both ends buckles when
// E A alpha dT reaches the Euler load of a clamped-clamped column in its weaker plane,
// 4 pi^2 E Iy / L^2 (Iy < Iz here), so the load factor of a heating dT is 4 pi^2 Iy / (A alpha dT L^2).
TEST(TemperatureLoads, HeatingAClampedColumnBucklesItAtTheEulerLoad) {
  const double dT = 30.0;
  json d = heated_cantilever(16);
  d["supports"].push_back({{"node", "B"}, {"fix", "all"}});
  d["loads"] = {{{"element", "e"}, {"temperature", {{"uniform", dT}}}}};
  d["analyses"] = {{{"id", "b"}, {"type", "buckling"}, {"modes", 1}}};
  const json r = run(d)["analyses"]["b"];
  const double expected = 4 * std::numbers::pi * std::numbers::pi * Iy / (A * alpha * dT * L * L);
  EXPECT_NEAR(r["load_factors"][0].get<double>(), expected, 1e-4 * expected);
}

TEST(TemperatureLoads, BadInputNamesTheField) {
  json d = heated_cantilever(1);
  d["materials"][0].erase("alpha");
  d["loads"] = {{{"element", "e"}, {"temperature", {{"uniform", 10.0}}}}};
  EXPECT_EQ(error_pointer(d), "/loads/0/temperature");
  d = heated_cantilever(1);
  d["loads"] = {{{"element", "e"}, {"temperature", {{"uniforn", 10.0}}}}};
  EXPECT_EQ(error_pointer(d), "/loads/0/temperature/uniforn");
  d["loads"] = {{{"element", "e"}, {"temperature", {{"uniform", 10.0}}}, {"at", 0.5}}};
  EXPECT_EQ(error_pointer(d), "/loads/0/at");
  d["loads"] = {{{"element", "e"}, {"temperature", json::object()}}};
  EXPECT_EQ(error_pointer(d), "/loads/0/temperature");
  d = heated_cantilever(1);
  d["materials"][0]["alpha"] = -1.0;
  EXPECT_EQ(error_pointer(d), "/materials/0/alpha");
  // A path has no thermal strain: exit 2 at its load case, nothing written.
  d = heated_cantilever(1);
  d["loads"] = {{{"element", "e"}, {"temperature", {{"uniform", 10.0}}}}};
  d["analyses"] = {{{"id", "p"}, {"type", "path"}, {"control", {{"load_factor", 1.0}, {"increments", 2}}}}};
  test::expect_bad_input(test::run_model("thermal_path", d), {"/analyses/0/load_case", "temperature change on element 'e'"});
}

}  // namespace temperature_loads_test
