// DofMap, part 4: the user's constraint rows (core/dof_map.hpp, "user rows"): the fixed axes of
// skewed supports, ties (OpenSees' equalDOF) and linear multi-point constraints. Each is one extra
// row over raw DOFs, eliminated exactly with the loop rows (no penalty numbers):
//   skewed support, fixed component k of frame A (rows = axes):  A.row(k) . u_node = 0
//                                                                 (k >= 3: A.row(k - 3) . theta)
//   tie a -> b, DOF k:                                            u_b[k] - u_a[k] = 0
//   linear constraint:                                            sum_i c_i u(dof_i) = value
// A constraint's value is a prescribed value of its own (PrescribedValue::constraint), so that
// every analysis that moves prescribed values (K_fp u_p) moves it too.
#include <cmath>
#include <string>

#include "core/dof_map.hpp"
#include "core/errors.hpp"

namespace beamfea {

namespace {
// A row whose reduced prescribed part is below this fraction of its terms' magnitude holds for the
// given values: redundant rather than contradictory. The same relative test as check_consistency.
constexpr double kConsistencyTolerance = 1e-9;
}  // namespace

void DofMap::build_user_rows(const Model& m, std::size_t& next) {
  for (std::size_t si = 0; si < m.supports.size(); ++si) {
    const Support& s = m.supports[si];
    if (!s.skewed) continue;
    for (int k = 0; k < 6; ++k) {
      if (!s.fixed[k]) continue;
      ExtraRow& x = next_extra_row(next);
      const int offset = k < 3 ? 0 : 3;
      for (int i = 0; i < 3; ++i)
        if (s.axes(k - offset, i) != 0.0) x.raw.push_back({raw_node(s.node, offset + i), s.axes(k - offset, i)});
      x.support = static_cast<int>(si);
      x.comp = k;
    }
  }
  for (std::size_t ti = 0; ti < m.ties.size(); ++ti) {
    const Tie& t = m.ties[ti];
    for (int k = 0; k < 6; ++k) {
      if (!t.dofs[k]) continue;
      ExtraRow& x = next_extra_row(next);
      x.raw.push_back({raw_node(t.nodes[1], k), 1.0});
      x.raw.push_back({raw_node(t.nodes[0], k), -1.0});
      x.tie = static_cast<int>(ti);
      x.comp = k;
    }
  }
  for (std::size_t ci = 0; ci < m.constraints.size(); ++ci) {
    ExtraRow& x = next_extra_row(next);
    for (const auto& t : m.constraints[ci].terms) x.raw.push_back({raw_index(t.dof), t.coefficient});
    // The constraint's value: the prescribed values after the supports' and "prescribed"'s, in order.
    const int p = prescribed_size() - static_cast<int>(m.constraints.size()) + static_cast<int>(ci);
    x.rhs.push_back({p, 1.0});
    x.constraint = static_cast<int>(ci);
  }
}

void DofMap::reject_user_row(const Model& m, const ExtraRow& x, const SparseRow& e, double scale) const {
  // The row reduced to prescribed values alone: sum_p e_p u_p = 0 must hold.
  double residual = 0.0, magnitude = 0.0;
  for (const auto& [k, v] : e) {
    if (k >= 0 || std::abs(v) <= 1e-10 * scale) continue;
    residual += v * prescribed_[-1 - k].value;
    magnitude += std::abs(v * prescribed_[-1 - k].value);
  }
  const bool contradictory = std::abs(residual) > kConsistencyTolerance * magnitude && residual != 0.0;
  std::string what;
  describe_extra(m, x, what);
  const std::string why = contradictory
                              ? " contradicts the supports, prescribed values, rigid links, joints and constraints "
                                "before it: they cannot all hold"
                              : " is redundant: the supports, rigid links, joints and constraints before it imply it "
                                "already; remove it";
  std::string pointer;
  if (x.support >= 0) pointer = "/supports/" + std::to_string(x.support);
  else if (x.tie >= 0) pointer = "/ties/" + std::to_string(x.tie);
  else pointer = "/constraints/" + std::to_string(x.constraint);
  throw InputError(pointer, what + why);
}

}  // namespace beamfea
