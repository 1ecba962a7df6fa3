#pragma once
// The predictor of a path step: the step's specification (StepSpec) and the initial guess of its
// unknowns, from the tangent at the start state (solvers/path/equilibrium.hpp's tangent()).
//
//   load factor    u = start + h t (t: tangent per unit load factor);
//   displacement   dlambda = h / (dU_c/dlambda), u = start + dlambda [t; 1] (with loads), or
//                  u = start + h t with t per unit control (imposed motion);
//   arc length     along d = [t; 1] (or a given direction: the secant, a critical mode) scaled to
//                  |d|_W = ds; the sign of d follows the previous step (d . d_prev > 0 in the
//                  arc-length metric, Crisfield 1991, vol. 1, sec. 9.4.2), the secant where the
//                  tangent is singular.
#include <Eigen/Core>

#include "solvers/path/equilibrium.hpp"
#include "solvers/path/path_types.hpp"

namespace beamfea {

class Predictor {
 public:
  Predictor(PathControl c, const PathEquilibrium& eq) : control(c), eq_(eq) {}
  // The spec and predictor of a step of size hh from c. dir: an imposed arc-length direction
  // [Delta_f (nf), dlambda] (a bisection along the last step, a branch switch); none: the tangent.
  void make_step(const Converged& c, double hh, StepSpec& s, Eigen::VectorXd& u, const Eigen::VectorXd* dir = nullptr) const;
  // The direction [Delta_f, dlambda] of a converged step from a to b.
  Eigen::VectorXd direction(const Converged& a, const Converged& b) const;
  // Dot product of two directions in the arc-length metric (W on Delta, psi^2 on dlambda).
  double arc_dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;

  Eigen::VectorXd previous_direction;  // [Delta_f, dlambda] of the last accepted step (empty at first)
  PathControl control;                 // the kind of step made (the step control's current mode)

 private:
  const PathEquilibrium& eq_;
};

}  // namespace beamfea
