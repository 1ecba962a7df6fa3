#include "solvers/path/path_scales.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "solvers/buckling.hpp"

namespace beamfea {

PathScales path_scales(const Model& model, const PathSystem& sys, FactorCache& factors, const Converged& start) {
  PathScales s;
  if (!sys.has_loads()) return s;
  const Eigen::VectorXd t = factors.tangent(sys, start);
  double t_max = 0.0;  // largest translation of the linear response per unit load factor
  double r_max = 0.0;  // and largest rotation
  if (t.size()) {
    s.t_norm = std::sqrt(sys.weighted_dot(t, t));
    for (int k = 0; k < sys.nf(); ++k) {
      double& m = sys.structure().is_rotation(sys.free_gens()[k]) ? r_max : t_max;
      m = std::max(m, std::abs(t[k]));
    }
  }
  try {
    BucklingOptions bo;
    bo.modes = 1;
    const BucklingResult b = solve_buckling(model, sys.loads(), bo);
    if (b.status == BucklingStatus::Succeeded && b.load_factors.size() > 0 && b.load_factors[0] > 0.0) {
      s.buckling_factor = b.load_factors[0];
    }
  } catch (const Error&) {
    // Linearised buckling is not available for this model (e.g. a closed loop): the linear
    // response alone sets the scales.
  }
  // The linear response's scale: the load factor that moves some node by L, or, with no free
  // translation (rigid links and joints, a lumped model), turns some coordinate by a radian.
  const double lambda_linear = t_max > 0.0 ? sys.length_scale() / t_max : (r_max > 0.0 ? 1.0 / r_max : 0.0);
  // A buckling factor this far beyond it is the round-off of a geometric stiffness the load hardly
  // has (a moment turning a mechanism: 1.6e16 against 1), not a scale of the path.
  if (lambda_linear > 0.0 && s.buckling_factor > kRoundOffBucklingRatio * lambda_linear) s.buckling_factor = 0.0;
  s.lambda_ref = s.buckling_factor > 0.0 ? s.buckling_factor : lambda_linear;
  s.psi = std::max(s.t_norm, s.buckling_factor > 0.0 ? sys.length_scale() / s.buckling_factor : 0.0);
  if (!(s.psi > 0.0) && s.lambda_ref > 0.0) s.psi = sys.length_scale() / s.lambda_ref;
  if (s.lambda_ref > 0.0) s.ds_auto = s.lambda_ref / kAutoIncrementsToReference * std::hypot(s.t_norm, s.psi);
  return s;
}

}  // namespace beamfea
