#include "solvers/mass_matrix.hpp"

#include "solvers/structure.hpp"

namespace beamfea {

namespace {

// Calls f(raw dofs, global matrix) for each beam with mass and each point mass.
template <class F>
void for_each_mass(const Model& model, const DofMap& map, MassKind kind, F&& f) {
  for (const auto& el : model.elements) {
    if (el.type != MemberType::Beam) continue;
    const double rho = model.materials[el.material].density;
    if (!(rho > 0.0)) continue;
    const Vec3& x1 = model.nodes[el.nodes[0]].x;
    const Vec3& x2 = model.nodes[el.nodes[1]].x;
    const Mat12 T = beam_transformation(beam_local_axes(x1, x2, el.orientation));
    const Mat12 M = T.transpose() * beam_local_mass(beam_section(model, el), rho, (x2 - x1).norm(), kind) * T;
    std::array<int, 12> dofs{};
    for (int k = 0; k < 6; ++k) {
      dofs[k] = map.raw_node(el.nodes[0], k);
      dofs[6 + k] = map.raw_node(el.nodes[1], k);
    }
    f(std::span<const int>(dofs), Eigen::Ref<const Eigen::MatrixXd>(M));
  }
  for (const auto& pm : model.masses) {
    std::array<int, 6> dofs{};
    for (int k = 0; k < 6; ++k) dofs[k] = map.raw_node(pm.node, k);
    const Mat6 M = point_mass_matrix(pm.mass, pm.inertia);
    f(std::span<const int>(dofs), Eigen::Ref<const Eigen::MatrixXd>(M));
  }
}

}  // namespace

void assemble_mass(const Model& model, const DofMap& map, MassKind kind, SystemAssembler& assembler) {
  for_each_mass(model, map, kind, [&](std::span<const int> dofs, const Eigen::Ref<const Eigen::MatrixXd>& M) {
    assembler.add(dofs, M);
  });
}

Eigen::VectorXd raw_mass_product(const Model& model, const DofMap& map, MassKind kind, const Eigen::VectorXd& u) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(map.raw_size());
  for_each_mass(model, map, kind, [&](std::span<const int> dofs, const Eigen::Ref<const Eigen::MatrixXd>& M) {
    const auto n = static_cast<Eigen::Index>(dofs.size());
    Eigen::VectorXd ue(n);
    for (Eigen::Index k = 0; k < n; ++k) ue[k] = u[dofs[static_cast<std::size_t>(k)]];
    const Eigen::VectorXd fe = M * ue;
    for (Eigen::Index k = 0; k < n; ++k) f[dofs[static_cast<std::size_t>(k)]] += fe[k];
  });
  return f;
}

Eigen::MatrixXd rigid_body_motions(const Model& model, const DofMap& map) {
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(map.raw_size(), 6);
  for (std::size_t n = 0; n < model.nodes.size(); ++n) {
    const int r = map.raw_node(static_cast<int>(n), 0);
    const Vec3& X = model.nodes[n].x;
    for (int d = 0; d < 3; ++d) {
      R(r + d, d) = 1.0;
      const Vec3 axis = Vec3::Unit(d);
      R.block<3, 1>(r, 3 + d) = axis.cross(X);
      R(r + 3 + d, 3 + d) = 1.0;
    }
  }
  return R;
}

}  // namespace beamfea
