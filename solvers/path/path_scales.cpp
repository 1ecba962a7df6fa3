#include "solvers/path/path_scales.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "solvers/buckling.hpp"

namespace beamfea {

PathScales path_scales(const Model& model, const PathEquilibrium& eq, const Converged& start, bool with_buckling) {
  PathScales s;
  if (!eq.has_loads) return s;
  const Eigen::VectorXd t = eq.tangent(start);
  double t_max = 0.0;  // largest translation of the linear response per unit load factor
  if (t.size()) {
    s.t_norm = std::sqrt(eq.weighted_dot(t, t));
    for (int k = 0; k < eq.nf; ++k)
      if (!eq.ns.is_rotation(eq.free[k])) t_max = std::max(t_max, std::abs(t[k]));
  }
  if (with_buckling) {
    try {
      BucklingOptions bo;
      bo.modes = 1;
      const BucklingResult b = solve_buckling(model, bo);
      if (b.status == BucklingStatus::Succeeded && b.load_factors.size() > 0 && b.load_factors[0] > 0.0) {
        s.buckling_factor = b.load_factors[0];
      }
    } catch (const Error&) {
      // Linearised buckling is not available for this model (e.g. a closed loop): the linear
      // response alone sets the scales.
    }
  }
  if (s.buckling_factor > 0.0) {
    s.lambda_ref = s.buckling_factor;
  } else if (t_max > 0.0) {
    s.lambda_ref = eq.L / t_max;
  }
  s.psi = std::max(s.t_norm, s.buckling_factor > 0.0 ? eq.L / s.buckling_factor : 0.0);
  if (!(s.psi > 0.0) && s.lambda_ref > 0.0) s.psi = eq.L / s.lambda_ref;
  if (s.lambda_ref > 0.0) s.ds_auto = s.lambda_ref / kAutoIncrementsToReference * std::hypot(s.t_norm, s.psi);
  return s;
}

}  // namespace beamfea
