// The dynamic analyses through the model file and the program: damping input, "frf" and
// "transient" results and files, bad input exiting 2 with the field's JSON pointer.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/cli_case.hpp"
#include "support/models.hpp"
#include "support/sweep_util.hpp"

namespace dynamics_cli_test {

using namespace beamfea;
using nlohmann::json;
using std::numbers::pi;

namespace {

constexpr double k = 1.0e4, m = 1.0, c = 2.0;  // f_n = 100 / (2 pi) Hz, zeta = 0.01

// A mass on a virtual spring (six single-DOF oscillators); joint damping c on every coordinate.
json oscillator() {
  json d;
  d["nodes"] = {{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {0, 0, 0}}}};
  d["joints"] = {{{"id", "v"}, {"type", "virtual_spring"}, {"nodes", {"A", "B"}}, {"axes", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
                  {"stiffness", {k, k, k, k, k, k}}, {"damping", {c, c, c, c, c, c}}}};
  d["supports"] = {{{"node", "A"}, {"fix", "all"}}};
  d["masses"] = {{{"node", "B"}, {"mass", m}, {"inertia", {{m, 0, 0}, {0, m, 0}, {0, 0, m}}}}};
  d["load_cases"] = {{{"id", "push"}, {"loads", {{{"node", "B"}, {"force", {0, 0, 10.0}}}}}}};
  return d;
}

const double fn = std::sqrt(k / m) / (2 * pi);

json frf(const json& extra = json::object()) {
  json a = {{"id", "h"}, {"type", "frf"}, {"input", {{"node", "B"}, {"dof", "uz"}}}, {"outputs", {{{"node", "B"}, {"dof", "uz"}}}},
            {"frequencies", {{"from", 0.5 * fn}, {"to", 1.5 * fn}, {"count", 11}, {"spacing", "linear"}}}};
  a.update(extra);
  return a;
}

json transient(const json& extra = json::object()) {
  json a = {{"id", "t"}, {"type", "transient"}, {"dt", 2.5e-4}, {"duration", 0.1},
            {"loads", {{{"load_case", "push"}, {"time_function", {{"type", "step"}}}}}}, {"track", {"B"}}, {"output_every", 40}};
  a.update(extra);
  return a;
}

}  // namespace

// The receptance at the resonance of the lightly damped oscillator: H = 1 / (i c w_n), -90 degrees.
TEST(DynamicsCli, FrfResultsAndCsv) {
  json d = oscillator();
  d["analyses"] = {frf()};
  const auto o = test::run_model("dyn_frf", d);
  ASSERT_EQ(o.code, 0) << o.message;
  const json h = o.results()["analyses"]["h"];
  ASSERT_EQ(h["frequencies"].size(), 11u);
  EXPECT_DOUBLE_EQ(h["frequencies"][0].get<double>(), 0.5 * fn);
  EXPECT_DOUBLE_EQ(h["frequencies"][10].get<double>(), 1.5 * fn);
  const json& out = h["outputs"][0];
  const double w = 2 * pi * fn;
  EXPECT_NEAR(out["magnitude"][5].get<double>(), 1.0 / (c * w), 1e-9 / (c * w));
  EXPECT_NEAR(out["phase_deg"][5].get<double>(), -90.0, 1e-6);
  EXPECT_NEAR(out["imag"][5].get<double>(), -1.0 / (c * w), 1e-9 / (c * w));
  EXPECT_NEAR(out["peak_frequency"].get<double>(), fn, 1e-12 * fn);
  const std::string csv = test::read_text(o.out() / "h.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "frequency_hz,B.uz_real,B.uz_imag,B.uz_magnitude,B.uz_phase_deg");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 12);
}

// "outputs": "all": the 6 x 6 matrix; the oscillator's is diagonal. Log spacing is geometric.
TEST(DynamicsCli, FrfAllIsTheSixBySixMatrix) {
  json d = oscillator();
  d["analyses"] = {frf({{"input", {{"node", "B"}}}, {"outputs", "all"}, {"method", "modal"}, {"modes", 6},
                        {"frequencies", {{"from", 1.0}, {"to", 100.0}, {"count", 3}, {"spacing", "log"}}}})};
  const auto o = test::run_model("dyn_frf_all", d);
  ASSERT_EQ(o.code, 0) << o.message;
  const json h = o.results()["analyses"]["h"];
  EXPECT_NEAR(h["frequencies"][1].get<double>(), 10.0, 1e-12);
  ASSERT_EQ(h["outputs"].size(), 36u);
  for (std::size_t i = 0; i < 36; ++i) {
    const json& e = h["outputs"][i];
    const double w = 2 * pi * 10.0;
    const double expected = (i / 6 == i % 6) ? 1.0 / std::hypot(k - m * w * w, c * w) : 0.0;
    EXPECT_NEAR(e["magnitude"][1].get<double>(), expected, 1e-9 / k) << e.dump();
  }
}

// A transient's steps, energy, CSV and ParaView series.
TEST(DynamicsCli, TransientResultsAndFiles) {
  json d = oscillator();
  d["analyses"] = {transient()};
  const auto o = test::run_model("dyn_transient", d);
  ASSERT_EQ(o.code, 0) << o.message;
  const json t = o.results()["analyses"]["t"];
  ASSERT_EQ(t["steps"].size(), 11u);
  const json& last = t["steps"][10];
  EXPECT_NEAR(last["time"].get<double>(), 0.1, 1e-12);
  const double w = std::sqrt(k / m), zeta = c / (2 * std::sqrt(k * m)), wd = w * std::sqrt(1 - zeta * zeta), xst = 10.0 / k;
  const double x = xst * (1 - std::exp(-zeta * w * 0.1) * (std::cos(wd * 0.1) + zeta / std::sqrt(1 - zeta * zeta) * std::sin(wd * 0.1)));
  EXPECT_NEAR(last["nodes"]["B"]["displacement"][2].get<double>(), x, 0.01 * xst);
  const json& e = last["energy"];
  EXPECT_NEAR(e["kinetic"].get<double>() + e["strain"].get<double>() + e["dissipated"].get<double>(), e["work"].get<double>(),
              1e-10 * e["work"].get<double>());
  EXPECT_TRUE(std::filesystem::exists(o.out() / "t.csv"));
  EXPECT_TRUE(std::filesystem::exists(o.out() / "t.pvd"));
  EXPECT_TRUE(std::filesystem::exists(o.out() / "t_step10.vtu"));
  EXPECT_FALSE(std::filesystem::exists(o.out() / "t_step11.vtu"));
}

// A static start under a step load stays at rest: x = x_st throughout.
TEST(DynamicsCli, StaticStartStaysAtRest) {
  json d = oscillator();
  d["analyses"] = {transient({{"initial", {{"displacement", "static"}}}})};
  const auto o = test::run_model("dyn_static_start", d);
  ASSERT_EQ(o.code, 0) << o.message;
  const json results = o.results();
  for (const json& s : results["analyses"]["t"]["steps"]) EXPECT_NEAR(s["nodes"]["B"]["displacement"][2].get<double>(), 10.0 / k, 1e-12);
}

// dt = 0.01 against the oscillator's 15.9 Hz: a warning with the numbers.
TEST(DynamicsCli, CoarseStepWarnsWithTheNumber) {
  json d = oscillator();
  d["analyses"] = {transient({{"dt", 0.01}, {"output_every", 1}, {"modes", 1}})};
  const auto o = test::run_model("dyn_coarse", d);
  ASSERT_EQ(o.code, 0) << o.message;
  const json w = o.results()["analyses"]["t"]["warnings"];
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].get<std::string>().find("cannot resolve mode 1 (15.9155 Hz"), std::string::npos) << w[0];
}

// Sweep columns: the FRF's peak (frequency and magnitude) and the transient's peak displacement
// and settling time, per case. A mass of 4 halves f_n: the peaks sit on grid points 0.5 f_n(1) and
// f_n(1), where |H| = 1 / (c w_n).
TEST(DynamicsCli, SweepCollectsPeaks) {
  json base = oscillator();
  base["analyses"] = {frf(), transient()};
  const json sweep = {{"grid", {{{"name", "m"}, {"pointer", "/masses/0/mass"}, {"values", {1.0, 4.0}}}}},
                      {"outputs", {{{"name", "f_peak"}, {"path", "analyses.h.outputs[0].peak_frequency"}},
                                   {{"name", "h_peak"}, {"path", "analyses.h.outputs[0].peak_magnitude"}},
                                   {{"name", "x_peak"}, {"path", "analyses.t.peaks.B.peak_displacement"}},
                                   {{"name", "t_settle"}, {"path", "analyses.t.peaks.B.settling_time"}}}}};
  const auto dir = sweep_test::temp_dir("dyn_sweep");
  const auto file = sweep_test::write_sweep(dir, sweep, base);
  const auto r = test::run_cli("sweep " + file.string() + " --out " + (dir / "out").string() + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto csv = sweep_test::read_csv(dir / "out" / "cases.csv");
  ASSERT_EQ(csv.rows.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const double mass = i == 0 ? 1.0 : 4.0, wn = std::sqrt(k / mass);
    EXPECT_NEAR(std::stod(csv.rows[i][static_cast<std::size_t>(csv.col("f_peak"))]), wn / (2 * pi), 1e-9 * wn);
    EXPECT_NEAR(std::stod(csv.rows[i][static_cast<std::size_t>(csv.col("h_peak"))]), 1.0 / (c * wn), 1e-9 / (c * wn));
    EXPECT_GT(std::stod(csv.rows[i][static_cast<std::size_t>(csv.col("x_peak"))]), 10.0 / k);
    EXPECT_GT(std::stod(csv.rows[i][static_cast<std::size_t>(csv.col("t_settle"))]), 0.0);
  }
}

TEST(DynamicsCli, BadInputNamesTheField) {
  {
    json d = oscillator();
    d.erase("masses");
    d["analyses"] = {frf()};
    test::expect_bad_input(test::run_model("dyn_bad_mass", d), {"/analyses/0", "no mass"});
  }
  {
    json d = oscillator();
    d["analyses"] = {frf({{"frequencies", {10.0, 30.0, 20.0}}})};
    test::expect_bad_input(test::run_model("dyn_bad_increasing", d), {"/analyses/0/frequencies/2", "increase"});
  }
  {
    json d = oscillator();
    d["analyses"] = {frf({{"frequencies", {{"from", 10.0}, {"to", 5.0}, {"count", 3}}}})};
    test::expect_bad_input(test::run_model("dyn_bad_to", d), {"/analyses/0/frequencies/to", "increase"});
  }
  {
    json d = oscillator();
    d["analyses"] = {transient({{"loads", {{{"load_case", "push"}, {"time_function", {{"type", "square"}}}}}}})};
    test::expect_bad_input(test::run_model("dyn_bad_function", d), {"/analyses/0/loads/0/time_function/type", "square"});
  }
  {
    json d = oscillator();
    d["damping"] = {{"rayleigh", {{"alpha", 1.0}, {"betta", 2.0}}}};
    d["analyses"] = {frf()};
    test::expect_bad_input(test::run_model("dyn_bad_key", d), {"/damping/rayleigh/betta", "beta"});
  }
  {
    json d = oscillator();
    d["joints"][0]["damping"] = {1.0, 2.0};
    d["analyses"] = {frf()};
    test::expect_bad_input(test::run_model("dyn_bad_joint", d), {"/joints/0/damping", "joint 'v'"});
  }
  {
    json d = oscillator();
    d["damping"] = {{"modal", 0.02}};
    d["analyses"] = {transient()};
    test::expect_bad_input(test::run_model("dyn_bad_modal", d), {"/damping/modal", "/analyses/0"});
  }
  {
    json d = oscillator();
    d["analyses"] = {frf({{"input", {{"node", "A"}, {"dof", "ux"}}}})};
    test::expect_bad_input(test::run_model("dyn_bad_held", d), {"/analyses/0/input", "node 'A' dof ux", "held"});
  }
}

}  // namespace dynamics_cli_test
