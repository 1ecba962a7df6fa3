#include "solvers/path/vibration.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>

#include "core/errors.hpp"
#include "elements/corotational_beam.hpp"
#include "solvers/generalized_eigen.hpp"
#include "solvers/modal.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

namespace {
// The shift sigma = -kPathShiftRelative * min_i(K_ii / M_ii): the modal analysis's choice
// (solvers/modal.cpp, kShiftRelative: below the lowest eigenvalue of a stable state, and K - sigma M
// factorisable where K is singular).
constexpr double kPathShiftRelative = 1e-9;
}  // namespace

SparseMatrix deformed_raw_mass(const NonlinearStructure& ns, const NonlinearState& s, MassKind kind) {
  const Model& model = ns.model();
  const auto nn = static_cast<int>(model.nodes.size());
  std::vector<Eigen::Triplet<double>> t;
  auto add = [&](std::span<const int> nodes, const Eigen::Ref<const Eigen::MatrixXd>& M) {
    const auto n = static_cast<int>(M.rows());
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        if (M(a, b) != 0.0) t.emplace_back(6 * nodes[a / 6] + a % 6, 6 * nodes[b / 6] + b % 6, M(a, b));
  };
  for (int e = 0; e < static_cast<int>(model.elements.size()); ++e) {
    const auto& el = model.elements[e];
    const FrameElement* beam = ns.beam(e);
    if (!beam) continue;
    const double rho = model.materials[el.material].density;
    if (!(rho > 0.0)) continue;
    const int n1 = el.nodes[0], n2 = el.nodes[1];
    const Mat12 M = beam->mass_at({s.x[n1], s.x[n2], s.R[n1], s.R[n2]}, kind, rho);
    const std::array<int, 2> nodes{n1, n2};
    add(nodes, M);
  }
  for (const auto& pm : model.masses) {
    const Mat3& R = s.R[pm.node];
    const Mat6 M = point_mass_matrix(pm.mass, R * pm.inertia * R.transpose());
    const std::array<int, 1> nodes{pm.node};
    add(nodes, M);
  }
  SparseMatrix M(6 * nn, 6 * nn);
  M.setFromTriplets(t.begin(), t.end());
  return M;
}

PathFrequencies path_frequencies(const PathSystem& P, const Converged& c, const StabilityAnalysis& tangent,
                                 const PathFrequencyOptions& options) {
  PathFrequencies out;
  const NonlinearStructure& ns = P.structure();
  const auto nn = static_cast<int>(ns.model().nodes.size());
  const int n = static_cast<int>(tangent.K.rows());
  if (n == 0) {
    out.message = "no free coordinates";
    return out;
  }
  // T: the nodes' raw DOFs over the free independent coordinates at the state.
  const auto tw = ns.twists(c.state);
  std::vector<Eigen::Triplet<double>> t;
  for (int node = 0; node < nn; ++node)
    for (int k = 0; k < 6; ++k)
      for (const auto& [g, v] : ns.raw_row(c.state, tw, node, k))
        if (P.free_index(g) >= 0) t.emplace_back(6 * node + k, P.free_index(g), v);
  SparseMatrix T(6 * nn, P.nf());
  T.setFromTriplets(t.begin(), t.end());
  const SparseMatrix TZ = T * tangent.Z;
  const SparseMatrix Mraw = deformed_raw_mass(ns, c.state, options.mass);
  SparseMatrix M = SparseMatrix(TZ.transpose() * Mraw * TZ);
  M = SparseMatrix(0.5 * (M + SparseMatrix(M.transpose())));
  const SparseMatrix K = SparseMatrix(0.5 * (tangent.K + SparseMatrix(tangent.K.transpose())));

  const Eigen::VectorXd dK = K.diagonal(), dM = M.diagonal();
  double ratio = std::numeric_limits<double>::infinity(), m_max = 0.0;
  for (int i = 0; i < n; ++i) {
    m_max = std::max(m_max, dM[i]);
    if (dM[i] > 0.0 && dK[i] > 0.0) ratio = std::min(ratio, dK[i] / dM[i]);
  }
  if (!(m_max > 0.0)) {
    out.message = "the model has no mass (give the materials a density or add point masses)";
    return out;
  }
  if (!std::isfinite(ratio)) ratio = 1.0;
  GeneralizedEigenPairs eig;
  try {
    eig = nearest_generalized_eigenpairs(K, M, options.modes, -kPathShiftRelative * ratio);
  } catch (const Error& e) {
    out.message = e.what();
    return out;
  }
  if (!eig.converged) {
    out.message = eig.message;
    return out;
  }
  const double zero_tolerance = ModalOptions{}.zero_tolerance;
  out.eigenvalues = eig.values;
  out.frequencies.resize(eig.values.size());
  for (Eigen::Index k = 0; k < eig.values.size(); ++k) {
    const Eigen::VectorXd phi = eig.vectors.col(k);
    double scaled = 0.0;
    for (int i = 0; i < n; ++i) scaled += std::abs(dK[i]) * phi[i] * phi[i];
    const double rayleigh = scaled > 0.0 ? phi.dot(K * phi) / scaled : 0.0;
    if (std::abs(rayleigh) < zero_tolerance) out.eigenvalues[k] = 0.0;
    const double w2 = out.eigenvalues[k];
    out.frequencies[k] = std::copysign(std::sqrt(std::abs(w2)), w2) / (2.0 * std::numbers::pi);
  }
  out.ok = true;
  return out;
}

}  // namespace beamfea
