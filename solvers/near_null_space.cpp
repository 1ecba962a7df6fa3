#include "solvers/near_null_space.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>

namespace beamfea {

namespace {
// A column of the QR's R below this fraction of the largest is dependent on the others (rounding
// of an exactly dependent one leaves about n eps relative).
constexpr double kDependentModeRelative = 1e-10;
}  // namespace

Eigen::MatrixXd rigid_body_modes(const Model& model, const DofMap& map) {
  const int n = map.free_size();
  Vec3 xc = Vec3::Zero();
  for (const Node& node : model.nodes) xc += node.x;
  if (!model.nodes.empty()) xc /= static_cast<double>(model.nodes.size());
  Eigen::MatrixXd Z = Eigen::MatrixXd::Zero(n, 6);
  for (int i = 0; i < n; ++i) {
    const DofRef& d = map.free_dofs()[i];
    if (d.owner != DofRef::Owner::Node) continue;  // joint coordinates stay at zero
    const Vec3 dx = model.nodes[d.index].x - xc;
    if (d.comp < 3) {
      Z(i, d.comp) = 1.0;
      // theta = e_k: u = e_k x dx, component d.comp.
      for (int k = 0; k < 3; ++k) Z(i, 3 + k) = Vec3::Unit(k).cross(dx)[d.comp];
    } else {
      Z(i, d.comp) = 1.0;  // r = theta = e_(comp - 3)
    }
  }
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(Z);
  const Eigen::MatrixXd R = qr.matrixQR().topRows(std::min(n, 6)).triangularView<Eigen::Upper>();
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(n, std::min(n, 6));
  double largest = 0.0;
  for (Eigen::Index k = 0; k < R.rows(); ++k) largest = std::max(largest, std::abs(R(k, k)));
  Eigen::MatrixXd out(n, 0);
  for (Eigen::Index k = 0; k < R.rows(); ++k) {
    if (!(std::abs(R(k, k)) > kDependentModeRelative * largest)) continue;
    out.conservativeResize(Eigen::NoChange, out.cols() + 1);
    out.col(out.cols() - 1) = Q.col(k);
  }
  return out;
}

int node_block_size(const DofMap& map) {
  const int n = map.free_size();
  if (n == 0 || n % 6 != 0) return 1;
  for (int i = 0; i < n; ++i) {
    const DofRef& d = map.free_dofs()[i];
    const DofRef& first = map.free_dofs()[i - i % 6];
    if (d.owner != DofRef::Owner::Node || first.owner != DofRef::Owner::Node || d.index != first.index ||
        d.comp != i % 6)
      return 1;
  }
  return 6;
}

}  // namespace beamfea
