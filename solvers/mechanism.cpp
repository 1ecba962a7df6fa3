#include "solvers/mechanism.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "elements/released_element.hpp"
#include "solvers/eigen_lowest.hpp"
#include "solvers/sparse_factor.hpp"

namespace beamfea {

std::vector<ZeroEnergyMode> zero_energy_modes(const Model& model, const DofMap& map, const SparseMatrix& K,
                                              int max_modes, double tolerance) {
  std::vector<ZeroEnergyMode> modes;
  const int n = static_cast<int>(K.rows());
  if (n == 0) return modes;
  Eigen::VectorXd s(n);
  for (int i = 0; i < n; ++i) s[i] = K.coeff(i, i) > 0.0 ? 1.0 / std::sqrt(K.coeff(i, i)) : 1.0;
  const SparseMatrix A = scaled(K, s);
  const EigenPairs ep = lowest_eigenpairs(A, std::min(max_modes, n), -1e-3);
  const double Lc = model.length_scale();
  for (int k = 0; k < ep.values.size(); ++k) {
    if (ep.values[k] > tolerance) break;
    ZeroEnergyMode m;
    m.free = s.cwiseProduct(ep.vectors.col(k));
    // Raw motion, rotations scaled by the model's length so that both count alike.
    Eigen::VectorXd raw = map.T_free() * m.free;
    for (int r = 0; r < raw.size(); ++r) {
      const DofRef d = map.raw_ref(r);
      if (d.owner == DofRef::Owner::Node && d.comp >= 3) raw[r] *= Lc;
      if (d.owner == DofRef::Owner::Joint) raw[r] *= Lc;
    }
    const double big = raw.cwiseAbs().maxCoeff();
    if (!(big > 0.0)) continue;
    std::set<int> nodes, joints;
    for (int r = 0; r < raw.size(); ++r) {
      if (std::abs(raw[r]) < 0.2 * big) continue;
      const DofRef d = map.raw_ref(r);
      m.dofs.push_back(d);
      (d.owner == DofRef::Owner::Node ? nodes : joints).insert(d.index);
    }
    m.nodes.assign(nodes.begin(), nodes.end());
    m.joints.assign(joints.begin(), joints.end());
    for (int e = 0; e < static_cast<int>(model.elements.size()); ++e) {
      const auto& el = model.elements[e];
      if (nodes.count(el.nodes[0]) || nodes.count(el.nodes[1])) m.elements.push_back(e);
    }
    std::string d = "mode " + std::to_string(k + 1) + " moves";
    std::string dofs;
    for (const auto& r : m.dofs) dofs += (dofs.empty() ? " " : ", ") + model.describe(r);
    d += dofs;
    if (!m.elements.empty()) {
      d += "; elements";
      std::set<int> members;
      for (int e : m.elements) {
        const auto& el = model.elements[e];
        const std::string id = el.member >= 0 ? model.members[el.member].id : el.id;
        if (el.member >= 0 && !members.insert(el.member).second) continue;
        d += " '" + id + "'";
        if (el.member >= 0) {  // end releases free the member's ends: say which
          const auto& ends = model.members[el.member].releases;
          Releases r{};
          std::copy(ends[0].begin(), ends[0].end(), r.begin());
          std::copy(ends[1].begin(), ends[1].end(), r.begin() + 6);
          if (std::any_of(r.begin(), r.end(), [](bool b) { return b; })) d += " (released " + describe_releases(r) + ")";
        }
      }
    }
    m.description = d;
    modes.push_back(std::move(m));
  }
  return modes;
}

std::string describe_mechanism(const std::vector<ZeroEnergyMode>& modes) {
  std::string s = "the structure is a mechanism: " + std::to_string(modes.size()) + " zero-energy mode" +
                  (modes.size() == 1 ? "" : "s");
  for (const auto& m : modes) s += "; " + m.description;
  return s;
}

}  // namespace beamfea
