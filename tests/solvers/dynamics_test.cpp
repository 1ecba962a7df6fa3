// Frequency response and transient response against closed forms: a mass on a joint spring (six
// uncoupled single-DOF oscillators), a cantilever beam; the integrators' published properties.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>

#include "solvers/frequency_response.hpp"
#include "solvers/transient.hpp"
#include "support/models.hpp"

namespace dynamics_test {

using namespace beamfea;
using nlohmann::json;
using std::numbers::pi;

namespace {

constexpr double k = 4.0e4, m = 2.5, c = 8.0;  // omega_n = 126.49 rad/s, zeta = c / (2 sqrt(k m)) = 0.0126

// A point mass m (rotary inertia m on each axis) on a virtual spring of stiffness k and viscous
// damping c on every coordinate, to a fixed node: six single-DOF oscillators m x'' + c x' + k x = f.
json sdof(double stiffness = k, double mass = m, double damping = c) {
  json d;
  d["nodes"] = {{{"id", "A"}, {"xyz", {0, 0, 0}}}, {{"id", "B"}, {"xyz", {0, 0, 0}}}};
  d["joints"] = {{{"id", "v"}, {"type", "virtual_spring"}, {"nodes", {"A", "B"}}, {"axes", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
                  {"stiffness", json::array({stiffness, stiffness, stiffness, stiffness, stiffness, stiffness})},
                  {"damping", json::array({damping, damping, damping, damping, damping, damping})}}};
  d["supports"] = {{{"node", "A"}, {"fix", "all"}}};
  d["masses"] = {{{"node", "B"}, {"mass", mass}, {"inertia", {{mass, 0, 0}, {0, mass, 0}, {0, 0, mass}}}}};
  d["loads"] = {{{"node", "B"}, {"force", {1.0, 0, 0}}}};
  return d;
}

// A steel cantilever along x, 1 m, 10 elements, 20 x 20 mm square, a tip mass; Rayleigh damping.
json cantilever_beam() {
  json d = test::cantilever(1.0, 2.1e11, 8.1e10, 4e-4, 1.3333e-8, 1.3333e-8, 2.25e-8, 10);
  d["materials"][0]["density"] = 7850.0;
  d["masses"] = {{{"node", "B"}, {"mass", 0.5}}};
  d["damping"] = {{"rayleigh", {{"alpha", 2.0}, {"beta", 1e-5}}}};
  d["loads"] = {{{"node", "B"}, {"force", {0, 0, -100.0}}}};
  return d;
}

const DofRef kBux{DofRef::Owner::Node, 1, 0};
const DofRef kBuz{DofRef::Owner::Node, 1, 2};

Eigen::VectorXd linear_hz(double from, double to, int n) { return Eigen::VectorXd::LinSpaced(n, from, to); }

}  // namespace

// |H| = 1 / sqrt((k - m w^2)^2 + (c w)^2), phase = -atan2(c w, k - m w^2) (a displacement per force
// lags), the peak at the damped resonance w_n sqrt(1 - 2 zeta^2).
TEST(FrequencyResponse, SingleDofReceptanceIsTheClosedForm) {
  const Model model = test::model_from(sdof());
  const double fn = std::sqrt(k / m) / (2 * pi);
  const Eigen::VectorXd hz = linear_hz(0.2 * fn, 3.0 * fn, 2801);
  for (FrfMethod method : {FrfMethod::Direct, FrfMethod::Modal}) {
    FrfOptions o;
    o.method = method;
    o.modes = 6;
    const FrfResult r = frequency_response(model, {kBux}, {kBux}, hz, model.default_loads(), o);
    ASSERT_EQ(r.status, FrfStatus::Succeeded) << r.message;
    Eigen::Index peak = 0;
    r.receptance[0].col(0).cwiseAbs().maxCoeff(&peak);
    for (Eigen::Index i = 0; i < hz.size(); ++i) {
      const double w = 2 * pi * hz[i];
      const std::complex<double> h = r.receptance[0](i, 0);
      const double mag = 1.0 / std::hypot(k - m * w * w, c * w);
      EXPECT_NEAR(std::abs(h), mag, 1e-9 * mag) << hz[i];
      EXPECT_NEAR(std::arg(h), -std::atan2(c * w, k - m * w * w), 1e-9) << hz[i];
    }
    const double zeta = c / (2 * std::sqrt(k * m));
    EXPECT_NEAR(hz[peak], fn * std::sqrt(1 - 2 * zeta * zeta), hz[1] - hz[0]);
  }
}

// Direct and modal with every mode agree; with few modes the modal receptance converges, from
// below at low frequency for a driving point (each mode adds phi^2 / omega^2 > 0 to the static
// flexibility), and the residual flexibility of the modes left out closes most of the gap.
TEST(FrequencyResponse, CantileverDirectAndModalAgreeAndTruncationConverges) {
  const Model model = test::model_from(cantilever_beam());
  const Eigen::VectorXd hz = linear_hz(1.0, 400.0, 400);
  FrfOptions direct;
  const FrfResult rd = frequency_response(model, {kBuz}, {kBuz, kBux}, hz, model.default_loads(), direct);
  ASSERT_EQ(rd.status, FrfStatus::Succeeded) << rd.message;
  EXPECT_EQ(rd.factorizations, hz.size());
  const auto modal = [&](int modes, bool residual) {
    FrfOptions o;
    o.method = FrfMethod::Modal;
    o.modes = modes;
    o.residual_flexibility = residual;
    const FrfResult r = frequency_response(model, {kBuz}, {kBuz, kBux}, hz, model.default_loads(), o);
    EXPECT_EQ(r.status, FrfStatus::Succeeded) << r.message;
    return r;
  };
  const double scale = rd.receptance[0].col(0).cwiseAbs().maxCoeff();
  const FrfResult all = modal(60, false);
  EXPECT_LT((all.receptance[0].col(0) - rd.receptance[0].col(0)).cwiseAbs().maxCoeff(), 1e-7 * scale);
  double last_error = std::numeric_limits<double>::infinity();
  for (int modes : {2, 4, 8, 16}) {
    const FrfResult r = modal(modes, false);
    const double error = std::abs(r.receptance[0](0, 0) - rd.receptance[0](0, 0));
    EXPECT_LT(r.receptance[0](0, 0).real(), rd.receptance[0](0, 0).real()) << modes << " modes";
    EXPECT_LT(error, last_error) << modes << " modes";
    last_error = error;
    const FrfResult rr = modal(modes, true);
    EXPECT_LT(std::abs(rr.receptance[0](0, 0) - rd.receptance[0](0, 0)), 0.01 * error) << modes << " modes";
  }
}

// About a loaded state (K + K_g of a load case): a cantilever under an axial compression P has the
// static tip compliance (tan(kL) - kL) / (P k), k = sqrt(P / EI) (Timoshenko & Gere, Theory of
// Elastic Stability, 1961, chapter 1: beam-columns), which the receptance approaches at 0.01 Hz; direct and
// modal (all modes) agree there too.
TEST(FrequencyResponse, AboutALoadedStateTheCompressedCantileverIsSofter) {
  json d = cantilever_beam();
  const double EI = 2.1e11 * 1.3333e-8, L = 1.0, P = 3000.0;  // P = 0.43 P_cr, P_cr = pi^2 EI / (4 L^2)
  d["load_cases"] = {{{"id", "axial"}, {"loads", {{{"node", "B"}, {"force", {-P, 0, 0}}}}}}};
  const Model model = test::model_from(d);
  const Eigen::VectorXd hz = Eigen::VectorXd::Constant(1, 0.01);
  FrfOptions o;
  o.system.preload = true;
  const FrfResult loaded = frequency_response(model, {kBuz}, {kBuz}, hz, model.loads_for("axial"), o);
  ASSERT_EQ(loaded.status, FrfStatus::Succeeded) << loaded.message;
  const double k = std::sqrt(P / EI);
  const double compliance = (std::tan(k * L) - k * L) / (P * k);
  EXPECT_NEAR(std::abs(loaded.receptance[0](0, 0)), compliance, 1e-4 * compliance);
  const FrfResult plain = frequency_response(model, {kBuz}, {kBuz}, hz, model.default_loads(), FrfOptions{});
  EXPECT_NEAR(std::abs(plain.receptance[0](0, 0)), L * L * L / (3 * EI), 1e-4 * L * L * L / (3 * EI));
  o.method = FrfMethod::Modal;
  o.modes = 60;
  const FrfResult modal = frequency_response(model, {kBuz}, {kBuz}, hz, model.loads_for("axial"), o);
  ASSERT_EQ(modal.status, FrfStatus::Succeeded) << modal.message;
  EXPECT_NEAR(std::abs(modal.receptance[0](0, 0) - loaded.receptance[0](0, 0)), 0.0, 1e-8 * compliance);
}

// Modal damping is no matrix: the direct method refuses it.
TEST(FrequencyResponse, DirectMethodRefusesModalDamping) {
  json d = sdof();
  d["damping"] = {{"modal", 0.02}};
  const Model model = test::model_from(d);
  const FrfResult r = frequency_response(model, {kBux}, {kBux}, linear_hz(1, 10, 3), model.default_loads(), FrfOptions{});
  EXPECT_EQ(r.status, FrfStatus::ModalDampingNeedsModal);
  // The modal method takes the ratio: |H(w_n)| = 1 / (2 zeta k), joint damping added to it.
  FrfOptions o;
  o.method = FrfMethod::Modal;
  o.modes = 6;
  const double fn = std::sqrt(k / m) / (2 * pi);
  const FrfResult rm = frequency_response(model, {kBux}, {kBux}, Eigen::VectorXd::Constant(1, fn), model.default_loads(), o);
  ASSERT_EQ(rm.status, FrfStatus::Succeeded) << rm.message;
  const double cw = c * 2 * pi * fn + 2 * 0.02 * k;
  EXPECT_NEAR(std::abs(rm.receptance[0](0, 0)), 1.0 / cw, 1e-9 / cw);
}

namespace {

TransientOptions sdof_options(double dt, double duration) {
  TransientOptions o;
  o.dt = dt;
  o.duration = duration;
  o.track = {1};
  return o;
}

}  // namespace

// A step force F on m x'' + c x' + k x = F from rest: x(t) = x_st (1 - e^{-zeta w t} (cos w_d t +
// zeta / sqrt(1 - zeta^2) sin w_d t)) (Chopra, Dynamics of Structures, section 4.3, with damping);
// undamped, the peak is 2 x_st.
TEST(Transient, StepOnADampedOscillatorIsTheClosedForm) {
  for (double damping : {c, 0.0}) {
    const Model model = test::model_from(sdof(k, m, damping));
    const double w = std::sqrt(k / m), T = 2 * pi / w, xst = 1.0 / k;
    const double zeta = damping / (2 * std::sqrt(k * m)), wd = w * std::sqrt(1 - zeta * zeta);
    const TimeFunction step;
    const TransientResult r = solve_transient(model, {{&model.default_loads(), step}}, sdof_options(T / 400, 3 * T));
    ASSERT_EQ(r.status, TransientStatus::Succeeded) << r.message;
    ASSERT_EQ(r.times.size(), 1201u);
    double peak = 0.0;
    for (std::size_t i = 0; i < r.times.size(); ++i) {
      const double t = r.times[i];
      const double x = xst * (1 - std::exp(-zeta * w * t) * (std::cos(wd * t) + zeta / std::sqrt(1 - zeta * zeta) * std::sin(wd * t)));
      EXPECT_NEAR(r.displacement(static_cast<Eigen::Index>(i), 0), x, 2e-3 * xst) << t;
      peak = std::max(peak, r.displacement(static_cast<Eigen::Index>(i), 0));
    }
    if (damping == 0.0) {
      EXPECT_NEAR(peak, 2 * xst, 1e-4 * xst);
    }
    EXPECT_LT(r.max_energy_error, 1e-10);  // average acceleration: the discrete energy balance is exact
  }
}

// Period elongation of the average acceleration method: its free vibration x_n satisfies
// x_{n+1} + x_{n-1} = 2 cos(w' dt) x_n, with tan(w' dt / 2) = w dt / 2 (the eigenvalues of its
// amplification matrix, Hughes 1987, section 9.1), so T'/T = w dt / (2 atan(w dt / 2)):
// 1.000833 at w dt = 0.1, 1.020497 at w dt = 0.5 (1 + (w dt)^2 / 12 to leading order).
TEST(Transient, AverageAccelerationPeriodElongationIsThePublishedOne) {
  const Model model = test::model_from(sdof(k, m, 0.0));
  const double w = std::sqrt(k / m);
  for (double wdt : {0.1, 0.5}) {
    TransientOptions o = sdof_options(wdt / w, 40 * wdt / w);
    o.initial_velocity = {{DofRef{DofRef::Owner::Joint, 0, 0}, 1.0}};
    const TransientResult r = solve_transient(model, {}, o);
    ASSERT_EQ(r.status, TransientStatus::Succeeded) << r.message;
    double sum = 0.0;
    int count = 0;
    for (Eigen::Index i = 1; i + 1 < r.displacement.rows(); ++i) {
      const double x = r.displacement(i, 0);
      if (std::abs(x) < 0.3 / w) continue;  // far from a zero crossing
      sum += (r.displacement(i + 1, 0) + r.displacement(i - 1, 0)) / (2 * x);
      ++count;
    }
    ASSERT_GT(count, 5);
    const double ratio = wdt / std::acos(sum / count);  // T'/T = w / w'
    EXPECT_NEAR(ratio, wdt / (2 * std::atan(wdt / 2)), 1e-9) << "w dt = " << wdt;
  }
  // The leading-order elongation (w dt)^2 / 12 of the average acceleration method.
  EXPECT_NEAR(0.1 / (2 * std::atan(0.05)), 1.0 + 0.01 / 12, 1e-6);
}

// Numerical dissipation at w dt -> infinity: the amplitude falls by the spectral radius per step,
// (1 + alpha)/(1 - alpha) for HHT (Hilber, Hughes & Taylor 1977), rho_inf for generalized alpha
// (Chung & Hulbert 1993); average acceleration keeps it (radius 1).
TEST(Transient, HighFrequencySpectralRadiusIsThePublishedOne) {
  const double stiff = 1e8, mass = 1.0;  // w = 1e4 rad/s, dt = 1: w dt = 1e4
  const Model model = test::model_from(sdof(stiff, mass, 0.0));
  struct Case {
    Integrator method;
    double parameter, rho;
  };
  for (const Case& cs : {Case{Integrator::Hht, -0.1, 0.9 / 1.1}, Case{Integrator::Hht, -0.3, 0.7 / 1.3},
                         Case{Integrator::GeneralizedAlpha, 0.8, 0.8}, Case{Integrator::GeneralizedAlpha, 0.5, 0.5},
                         Case{Integrator::Newmark, 0.0, 1.0}}) {
    TransientOptions o = sdof_options(1.0, 600.0);
    o.method = cs.method;
    (cs.method == Integrator::Hht ? o.alpha : o.rho_inf) = cs.parameter;
    o.initial_velocity = {{DofRef{DofRef::Owner::Joint, 0, 0}, 1.0}};
    const TransientResult r = solve_transient(model, {}, o);
    ASSERT_EQ(r.status, TransientStatus::Succeeded) << r.message;
    // |state| over 300 steps; the repeated root at infinity adds a factor ~ (n2/n1)^2 = 4, i.e.
    // (4)^(1/300) = 1.0046 per step at most.
    const auto amplitude = [&](Eigen::Index i) { return std::hypot(r.displacement(i, 0) * std::sqrt(stiff / mass), r.velocity(i, 0)); };
    const double measured = std::pow(amplitude(600) / amplitude(300), 1.0 / 300.0);
    EXPECT_NEAR(measured, cs.rho, 0.006 * cs.rho) << to_string(cs.method) << " " << cs.parameter;
  }
}

// An undamped cantilever under a step tip load: the average acceleration method conserves
// kinetic + strain = work at every step (to round-off), its peak tip deflection is about twice
// the static one; with Rayleigh damping dissipated energy closes the balance.
TEST(Transient, UndampedBeamUnderAStepLoadConservesEnergy) {
  json d = cantilever_beam();
  d.erase("damping");
  const Model model = test::model_from(d);
  TransientOptions o;
  o.dt = 1e-4;
  o.duration = 0.2;
  o.track = {1};
  const TimeFunction step;
  const TransientResult r = solve_transient(model, {{&model.default_loads(), step}}, o);
  ASSERT_EQ(r.status, TransientStatus::Succeeded) << r.message;
  EXPECT_LT(r.max_energy_error, 1e-10);
  for (Eigen::Index i = 0; i < r.energy.rows(); ++i)
    EXPECT_NEAR(r.energy(i, 0) + r.energy(i, 1), r.energy(i, 3), 1e-10 * r.energy.col(3).maxCoeff());
  // Static tip deflection P L^3 / (3 E I); a step's dynamic peak approaches 2x (higher modes
  // add a little).
  const double uz_static = -100.0 / (3 * 2.1e11 * 1.3333e-8);
  EXPECT_NEAR(r.displacement.col(2).minCoeff() / uz_static, 2.0, 0.1);

  json dd = cantilever_beam();
  const Model damped = test::model_from(dd);
  const TransientResult rd = solve_transient(damped, {{&damped.default_loads(), step}}, o);
  ASSERT_EQ(rd.status, TransientStatus::Succeeded) << rd.message;
  EXPECT_LT(rd.max_energy_error, 1e-10);
  EXPECT_GT(rd.energy(rd.energy.rows() - 1, 2), 0.05 * rd.energy(rd.energy.rows() - 1, 3));
}

// El Centro 1940 N-S (OpenSees' EXAMPLES/verification/elCentro.dat, 0.02 s, in g) on single-DOF
// systems of T_n = 0.5, 1, 2 s and 2 % damping, as a table time function times the inertia load
// -m g a_g(t) (a load case of gravity): the peak deformations D = 2.67, 5.97, 7.47 in. of Chopra,
// Dynamics of Structures, section 6.4 (Fig. 6.4.1; the case OpenSees' sdofTransient.tcl checks),
// g = 386.4 in/s^2, dt = 0.002 s. Chopra integrates the piecewise-linear record exactly; average
// acceleration at w dt <= 0.025 is within 1 %.
TEST(Transient, ElCentroPeaksAreChoprasFigure641) {
  const std::filesystem::path record = std::filesystem::path(BEAMFEA_SOURCE_DIR) / "tests" / "data" / "elCentro.dat";
  ASSERT_TRUE(std::filesystem::exists(record)) << record;
  std::ifstream in(record);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  TimeFunction ground;
  ground.kind = TimeFunction::Kind::Table;
  const std::regex number(R"(-?\d+\.\d+)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), number); it != std::sregex_iterator(); ++it)
    ground.points.push_back({0.02 * static_cast<double>(ground.points.size()), std::stod(it->str())});
  ASSERT_EQ(ground.points.size(), 1559u);
  const double g = 386.4, zeta = 0.02;
  for (const auto& [Tn, D] : {std::pair{0.5, 2.67}, std::pair{1.0, 5.97}, std::pair{2.0, 7.47}}) {
    const double w = 2 * pi / Tn;
    json d = sdof(w * w, 1.0, 2 * zeta * w);
    d.erase("loads");
    d["load_cases"] = {{{"id", "ground"}, {"gravity", {-g, 0, 0}}}};
    const Model model = test::model_from(d);
    const TransientResult r = solve_transient(model, {{&model.loads_for("ground"), ground}}, sdof_options(0.002, 30.0));
    ASSERT_EQ(r.status, TransientStatus::Succeeded) << r.message;
    EXPECT_NEAR(r.displacement.col(0).cwiseAbs().maxCoeff(), D, 0.01 * D) << "T_n = " << Tn;
  }
}

// Time functions: step, ramp, sine, table as documented.
TEST(Transient, TimeFunctionsAreTheDocumentedOnes) {
  TimeFunction g;
  EXPECT_EQ(g(-1e-9), 0.0);
  EXPECT_EQ(g(0.0), 1.0);
  g.kind = TimeFunction::Kind::Ramp;
  g.duration = 2.0;
  EXPECT_DOUBLE_EQ(g(0.5), 0.25);
  EXPECT_DOUBLE_EQ(g(3.0), 1.0);
  g.kind = TimeFunction::Kind::Sine;
  g.frequency = 2.0;
  g.phase_deg = 90.0;
  EXPECT_NEAR(g(0.125), std::cos(2 * pi * 2.0 * 0.125), 1e-15);
  g.kind = TimeFunction::Kind::Table;
  g.points = {{0.0, 0.0}, {1.0, 2.0}, {3.0, -2.0}};
  EXPECT_DOUBLE_EQ(g(0.5), 1.0);
  EXPECT_DOUBLE_EQ(g(2.0), 0.0);
  EXPECT_DOUBLE_EQ(g(5.0), -2.0);
}

}  // namespace dynamics_test
