#pragma once
// The corrector of a path step: Newton's method on the bordered system (KINSOL,
// solvers/kinsol_solver.hpp), preceded by the chord corrector, modified Newton iterations on the
// factor of the start state's tangent (Crisfield 1991, vol. 1, sec. 9.3 and ch. 9's modified Newton-Raphson: the
// tangent is not updated within the step).
//
// The predictor of every step comes from the converged start state's tangent system, assembled and
// factorised once (FactorCache::tangent, solvers/path/factor_cache.hpp; shared with the stability
// analysis and the record of the step). The chord iterations solve with that same factor, so a step that converges here costs
// no factorisation: per iteration one residual evaluation and one or two triangular solves.
//
//   load control, imposed motion   J0 du = -F                 (the factor is of the step's system)
//   arc length, displacement       the bordered system [J0, -q0; a^T, b] [du; dlambda] = -[F; g]
//   control with loads             by block elimination with J0 (Crisfield 1991, vol. 1, eq. 9.12:
//                                  du = dū + dlambda du_t, dū = -J0^-1 F, du_t = J0^-1 q0 the
//                                  tangent per unit load factor that the predictor already has), and
//                                  dlambda from the linearised extra row,
//                                  dlambda = -(g + a^T dū) / (a^T du_t + b)
//                                  (arc length: a = W Delta / ds, b = psi^2 (lambda - lambda_0) / ds,
//                                  the row of the full Newton Jacobian, i.e. the constraint of eq.
//                                  9.13 linearised at the iterate; displacement: a the controlled
//                                  DOF's row at the start, b = 0).
//
// J0 = [K_t, -C^T; C, 0] at the start state (lambda_0, its multipliers), q0 = [T^T f_ext; 0] there.
// Convergence is tested exactly as KINSOL tests it (solvers/kinsol_solver.hpp): the scaled residual
// max |fscale_i F_i| at most the function tolerance, so a converged point meets the same tolerance
// whichever corrector found it. The chord gives up (and the caller falls back to full Newton from
// the same predictor, Corrector::solve) when the start factor is missing or
// failed (a singular tangent), when an iterate cannot be evaluated, when the residual grows, or when
// its observed contraction cannot reach the tolerance within kMaxChordIterations.
#include <Eigen/Core>
#include <string>

#include "solvers/kinsol_solver.hpp"
#include "solvers/path/equilibrium.hpp"
#include "solvers/path/factor_cache.hpp"

namespace beamfea {

// At most this many chord iterations per step (each a residual evaluation and a solve, some 10-20 %
// of an assembly + LU on the frames of bench_path_step); beyond, full Newton is cheaper.
inline constexpr int kMaxChordIterations = 8;
// The initial guess is accepted as KINSOL accepts it (KIN_INITIAL_GUESS_OK): scaled residual below
// this fraction of the tolerance.
inline constexpr double kInitialGuessFraction = 0.01;

struct ChordOutcome {
  bool converged = false;
  int iterations = 0;            // chord iterations made (residual evaluations after the predictor's)
  double residual_norm = 0.0;    // scaled max norm at the last iterate
  std::string why;               // why the chord gave up (empty when converged)
  Eigen::VectorXd u;             // the last iterate (the solution when converged)
};

// Chord iterations from the predictor u0 of step s from start, on the factor that `factors` keeps of
// start's tangent. tolerance: KINSOL's function tolerance (on the scaled max norm).
ChordOutcome chord_correct(const PathSystem& sys, FactorCache& factors, const Converged& start, const StepSpec& s,
                           Eigen::VectorXd u0, double tolerance);

// Whether a step tries the chord iterations before full Newton (PathOptions::chord_corrector).
enum class ChordIterations { Off, On };

// The outcome of a step's solve: the converged state, or why none.
struct StepSolution {
  bool converged = false;
  Converged state;            // when converged
  std::string report;         // the solver's one-line report (why not, when not converged)
};

// The corrector of a path's steps: the system (read), its factor cache (the chord solves with the
// start state's factor) and the Newton solver (its factorisations), and the chord's statistics.
class Corrector {
 public:
  Corrector(const PathSystem& sys, FactorCache& factors, KinsolSolver& kin, ChordIterations chord)
      : sys_(sys), factors_(factors), kin_(kin), chord_(chord) {}
  // Solves step s from `start` with the initial guess u (the predictor). With the chord iterations on
  // and the start state's tangent factorised (FactorCache::tangent(start), as the predictor leaves
  // it), chord iterations on that factor first; when they give up, full Newton (KINSOL) from the
  // same u.
  StepSolution solve(const Converged& start, const StepSpec& s, Eigen::VectorXd u);
  // Steps solved by the chord iterations, and those where they gave up (full Newton then), so far.
  long chord_steps() const { return chord_steps_; }
  long chord_fallbacks() const { return chord_fallbacks_; }

 private:
  const PathSystem& sys_;
  FactorCache& factors_;
  KinsolSolver& kin_;
  const ChordIterations chord_;
  long chord_steps_ = 0, chord_fallbacks_ = 0;
};

// The state at the start of the path: the reference with the prescribed independent values imposed,
// and the slave constraints solved for when any is non-zero (a load step at load factor 0).
StepSolution initial_state(const PathSystem& sys, FactorCache& factors, KinsolSolver& kin);

}  // namespace beamfea
