#include "solvers/scheme_ranking.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace beamfea {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// 1/C_dd for the first nd directions d, C = K^-1.
Eigen::VectorXd series_diagonal(const Eigen::MatrixXd& K, int nd) {
  const Eigen::MatrixXd C = K.inverse();
  Eigen::VectorXd c(nd);
  for (int d = 0; d < nd; ++d) c[d] = 1.0 / C(d, d);
  return c;
}
}  // namespace

std::array<Eigen::VectorXd, kUnloadedSchemeComponents> scheme_components(const SchemeResult& r, int nd) {
  std::array<Eigen::VectorXd, kUnloadedSchemeComponents> c;
  for (auto& v : c) v = Eigen::VectorXd::Constant(nd, kNaN);
  const auto& A = r.actuated_stiffness;
  if (A.ok() || A.condensed_ok)
    for (int d = 0; d < nd; ++d) c[0][d] = A.K()(d, d);
  if (r.structural.ok)
    for (int d = 0; d < nd; ++d) c[1][d] = 1.0 / r.structural.C(d, d);
  if (r.total.eq19.size() == nd) c[2] = r.total.eq19;
  if (r.total.ok) c[3] = series_diagonal(r.total.K_series, nd);
  if (r.total.fea_ok) c[4] = series_diagonal(r.total.K_fea, nd);
  return c;
}

std::array<Eigen::VectorXd, kLoadedSchemeComponents> loaded_scheme_components(const SchemeLoadResponse& r, int nd) {
  const LoadedSchemeModel* models[kLoadedSchemeComponents] = {&r.actuated, &r.structural, &r.total};
  std::array<Eigen::VectorXd, kLoadedSchemeComponents> c;
  for (int w = 0; w < kLoadedSchemeComponents; ++w) {
    c[w] = Eigen::VectorXd::Constant(nd, kNaN);
    const LoadedSchemeModel& m = *models[w];
    if (!m.stiffness_ok) continue;
    if (w == 0) {
      c[w] = m.K_loaded.diagonal();  // as the unloaded "actuated" component, K_A,dd
      continue;
    }
    Eigen::FullPivLU<Eigen::MatrixXd> lu(m.K_loaded);
    if (!lu.isInvertible()) continue;
    const Eigen::MatrixXd C = lu.inverse();
    for (int d = 0; d < nd; ++d) c[w][d] = 1.0 / C(d, d);
  }
  return c;
}

Eigen::MatrixXd stiffness_of_compliance(const Eigen::MatrixXd& C) { return C.inverse(); }

void SchemeRank::add_pose(const SchemeResult& r, double value, const std::string& pose) {
  if (!r.valid) {
    if (ranked()) {
      status = SchemeRankStatus::InvalidAtPose;
      reason = r.status;
      failed_pose = pose;
    }
  } else if (!std::isfinite(value)) {
    if (ranked()) {
      status = SchemeRankStatus::NoValueAtPose;
      failed_pose = pose;
    }
  } else if (value < worst_value) {
    worst_value = value;
    worst_pose = pose;
  }
}

void rank_schemes(std::vector<SchemeRank>& ranks) {
  std::stable_sort(ranks.begin(), ranks.end(), [](const SchemeRank& a, const SchemeRank& b) {
    if (a.ranked() != b.ranked()) return a.ranked();
    return a.ranked() && a.worst_value > b.worst_value;
  });
}

}  // namespace beamfea
