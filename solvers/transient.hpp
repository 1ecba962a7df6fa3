#pragma once
// Transient response: linear structural dynamics
//     M a + C v + K d = f(t) = sum_i g_i(t) f_i
// over the free DOFs (solvers/dynamic_system.hpp: supports and prescribed DOFs held, the motion
// relative to their values; K elastic), loads f_i of load cases times time functions g_i, by an
// implicit one-step integrator with constant dt and ONE factorisation of its effective matrix.
//
// Integrators: the generalized-alpha family of Chung & Hulbert (1993), which holds the others,
//   M a_{n+1-am} + C v_{n+1-af} + K d_{n+1-af} = f_{n+1-af},  x_{n+1-a} = (1 - a) x_{n+1} + a x_n
//   (the balance of Chung & Hulbert 1993, section 2; f interpolated as d is), with Newmark's updates
//   d_{n+1} = d_n + dt v_n + dt^2 ((1/2 - beta) a_n + beta a_{n+1}),
//   v_{n+1} = v_n + dt ((1 - gamma) a_n + gamma a_{n+1})   (Newmark 1959; Hughes, The Finite
//   Element Method, 1987, section 9.1.1):
//     Newmark            am = af = 0; gamma, beta as given; default average acceleration
//                        (gamma = 1/2, beta = 1/4: unconditionally stable, no numerical damping,
//                        period elongation tan(w' dt / 2) = w dt / 2);
//     HHT                am = 0, af = -alpha, alpha in [-1/3, 0], gamma = (1 - 2 alpha)/2,
//                        beta = (1 - alpha)^2 / 4 (Hilber, Hughes & Taylor 1977, the alpha-method);
//                        spectral radius at w dt -> infinity rho = (1 + alpha)/(1 - alpha);
//     generalized alpha  am = (2 rho_inf - 1)/(rho_inf + 1), af = rho_inf/(rho_inf + 1) (eq. 25),
//                        gamma = 1/2 - am + af (eq. 17), beta = (1 - am + af)^2 / 4 (eq. 20):
//                        second order, spectral radius rho_inf at w dt -> infinity.
// The unknown of a step is a_{n+1}:
//   S a_{n+1} = f_{n+1-af} - am M a_n - C ((1-af) v~ + af v_n) - K ((1-af) d~ + af d_n),
//   S = (1 - am) M + (1 - af) gamma dt C + (1 - af) beta dt^2 K   (factorised once),
//   d~ = d_n + dt v_n + dt^2 (1/2 - beta) a_n, v~ = v_n + dt (1 - gamma) a_n (the predictors).
// Start: d_0 static (K d_0 = f(0)) or zero; v_0 given; a_0 from M a_0 = f(0) - C v_0 - K d_0 (where
// M is singular, massless DOFs, from S a_0 = the same right-hand side instead, with a warning).
//
// Energy (per output step), over the free DOFs: kinetic 1/2 v^T M v, strain 1/2 d^T K d,
// dissipated sum (d_{n+1} - d_n)^T C (v_n + v_{n+1})/2, work W_0 + sum (d_{n+1} - d_n)^T
// (f_n + f_{n+1})/2, with W_0 = the kinetic and strain energy at the start (the work that brought
// the structure to its initial state). kinetic + strain + dissipated = work holds exactly for the
// average acceleration method (the trapezoidal rule conserves the discrete energy of a linear
// system); HHT and generalized alpha dissipate the high modes numerically, the difference.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "core/model.hpp"
#include "elements/beam_mass.hpp"

namespace beamfea {

// A time function g(t) of a transient load (0 before t = 0 for step and ramp).
struct TimeFunction {
  enum class Kind { Step, Ramp, Sine, Table };
  Kind kind = Kind::Step;
  double duration = 0.0;   // ramp: from 0 at t = 0 to 1 at t = duration, then 1
  double frequency = 0.0;  // sine: sin(2 pi frequency t + phase), frequency in Hz
  double phase_deg = 0.0;
  std::vector<std::array<double, 2>> points;  // table: (t, g) with t increasing; linear between,
                                              // the end values held beyond the ends
  double operator()(double t) const;
};
const char* to_string(TimeFunction::Kind k);

struct TransientLoad {
  const LoadSet* loads = nullptr;  // a load set of the model
  TimeFunction function;
};

enum class Integrator { Newmark, Hht, GeneralizedAlpha };
const char* to_string(Integrator m);

// The most steps of one transient analysis (docs/analyses/transient.md).
inline constexpr long long kMaxTransientSteps = 10'000'000;

struct TransientOptions {
  double dt = 0.0;
  double duration = 0.0;
  Integrator method = Integrator::Newmark;
  double gamma = 0.5, beta = 0.25;  // Newmark
  double alpha = -0.05;             // HHT, in [-1/3, 0]
  double rho_inf = 0.8;             // generalized alpha, in [0, 1]
  bool static_initial = false;      // d_0 from K d_0 = f(0); otherwise zero
  std::vector<std::pair<DofRef, double>> initial_velocity;  // raw DOFs (free ones) and values
  MassKind mass = MassKind::Consistent;
  int output_every = 1;             // record every n-th step (and the first and last)
  std::vector<int> track;           // node indices whose motion is recorded
  void validate() const;
  long long step_count() const;     // duration / dt, rounded up (a last time within 1e-9 dt of it)
};

enum class TransientStatus {
  Succeeded,
  NoMass,
  Singular,  // the effective matrix (or K for a static start) could not be factorised
  Diverged,  // a non-finite state (a conditionally stable scheme beyond its limit)
};
const char* to_string(TransientStatus s);

struct TransientResult {
  TransientStatus status = TransientStatus::Singular;
  std::string message;
  std::vector<std::string> warnings;
  long long steps = 0;               // integration steps made
  std::vector<double> times;         // the output times
  // Per output time (rows) the tracked nodes' 6 components each (columns 6 t + c).
  Eigen::MatrixXd displacement, velocity, acceleration;
  Eigen::MatrixXd energy;            // per output time: kinetic, strain, dissipated, work
  double max_energy_error = 0.0;     // max |kinetic + strain + dissipated - work| / max work
  double am = 0.0, af = 0.0, gamma = 0.5, beta = 0.25;  // the parameters used
  std::string brief_report() const { return message; }
};

// Called at every output time with the raw displacement (a .pvd series of deformed shapes).
using ShapeSink = std::function<void(double time, const Eigen::VectorXd& u_raw)>;

TransientResult solve_transient(const Model& model, const std::vector<TransientLoad>& loads, const TransientOptions& options,
                                const ShapeSink& shapes = {});

}  // namespace beamfea
