#pragma once
// The predictor of a path step: the step's specification (StepSpec) and the initial guess of its
// unknowns, from the tangent at the start state (solvers/path/factor_cache.hpp's tangent()).
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
#include "solvers/path/factor_cache.hpp"
#include "solvers/path/path_types.hpp"

namespace beamfea {

// A step's specification and the initial guess of its unknowns.
struct StepPrediction {
  StepSpec spec;
  Eigen::VectorXd u;
};

class Predictor {
 public:
  Predictor(const PathSystem& sys, FactorCache& factors) : sys_(sys), factors_(factors) {}
  // The step of kind `control` and size h from c, along the tangent (factorised at c here).
  StepPrediction predict(const Converged& c, PathControl control, double h);
  // An arc-length step of size h from c along an imposed direction [Delta_f (nf), dlambda] (a
  // bisection along the last step, a branch switch).
  StepPrediction predict_along(const Converged& c, double h, const Eigen::VectorXd& direction);

  // [Delta_f, dlambda] of the last accepted step (empty at first): the orientation of the next
  // arc-length predictor, and the secant where the tangent is singular.
  const Eigen::VectorXd& previous_direction() const { return previous_; }
  void accept(const Eigen::VectorXd& direction) { previous_ = direction; }

 private:
  // An arc-length step along `direction`, or (none) along the tangent t oriented by the previous step.
  StepPrediction arc_step(const Converged& c, double h, const Eigen::VectorXd& t,
                          const Eigen::VectorXd* direction) const;
  const PathSystem& sys_;
  FactorCache& factors_;
  Eigen::VectorXd previous_;
};

}  // namespace beamfea
