#pragma once
// Ranking the actuation schemes of an actuator allocation (solvers/actuator_allocation.hpp,
// docs/analyses/actuator-allocation.md): a scheme's stiffness components at one pose, per reported
// direction, and the ranking of the schemes by one component in one direction, worst case over
// the poses (W. Bu 2012, eq. 20: the best scheme maximises its least stiffness).
//
// A component in a direction d is a diagonal stiffness K_dd (the actuated stiffness) or the
// reciprocal 1/C_dd of a compliance's diagonal (C = K^-1 where a stiffness K is what the scheme
// gives): the stiffness met along d when the other directions are free.
#include <Eigen/Core>
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "solvers/actuator_allocation.hpp"
#include "solvers/actuator_load_case.hpp"

namespace beamfea {

// Per direction: actuated K_A,dd, structural 1/C_S,dd, total_eq19 (eq. 19), total 1/C_dd
// (C = K_series^-1), total_fea 1/C_dd (C = K_fea^-1); NaN where the scheme gives none.
inline constexpr int kUnloadedSchemeComponents = 5;
std::array<Eigen::VectorXd, kUnloadedSchemeComponents> scheme_components(const SchemeResult& r, int directions);

// Under a load case, per direction: loaded actuated K_dd, loaded structural and loaded total
// 1/C_dd (C = K_loaded^-1); NaN where absent or where K_loaded is singular.
inline constexpr int kLoadedSchemeComponents = 3;
std::array<Eigen::VectorXd, kLoadedSchemeComponents> loaded_scheme_components(const SchemeLoadResponse& r, int directions);

// The stiffness C^-1 of a structural compliance C (reported beside it).
Eigen::MatrixXd stiffness_of_compliance(const Eigen::MatrixXd& C);

// Whether a scheme takes part in the ranking, decided by its first pose that has no value.
enum class SchemeRankStatus {
  Ranked,         // a value at every pose
  InvalidAtPose,  // the frozen structure is unstable or J singular at `failed_pose`
  NoValueAtPose,  // no value of the ranking component at `failed_pose` (the loaded structure a mechanism)
};

// One scheme's worst case over the poses, built pose by pose with add_pose.
struct SchemeRank {
  std::size_t scheme = 0;  // index into the analysis's schemes
  SchemeRankStatus status = SchemeRankStatus::Ranked;
  std::string failed_pose;  // the first pose without a value (when not Ranked)
  std::string reason;       // InvalidAtPose: the scheme's status there (SchemeResult::status)
  // The least finite value over the poses and its pose (kept over every pose, ranked or not).
  double worst_value = std::numeric_limits<double>::infinity();
  std::string worst_pose;

  bool ranked() const { return status == SchemeRankStatus::Ranked; }
  // The scheme `r` at `pose`, whose ranking component there is `value` (read only when r.valid).
  void add_pose(const SchemeResult& r, double value, const std::string& pose);
};

// Ranked schemes first, by decreasing worst value; the others after them, each group in its
// order (a stable sort).
void rank_schemes(std::vector<SchemeRank>& ranks);

}  // namespace beamfea
