#include "solvers/mass_matrix.hpp"

#include "solvers/structure.hpp"

namespace beamfea {

namespace {

// Calls f(raw dofs, global matrix) for each beam with mass and each point mass.
template <class F>
void for_each_mass(const LinearStructure& structure, const DofMap& map, MassKind kind, F&& f) {
  const Model& model = structure.model();
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const FrameElement* beam = structure.beam(static_cast<int>(e));
    if (!beam) continue;
    const double rho = model.materials[model.elements[e].material].density;
    if (!(rho > 0.0)) continue;
    const Mat12 M = beam->mass(kind, rho);
    const auto dofs = structure.element_dofs(map, static_cast<int>(e));
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

void assemble_mass(const LinearStructure& structure, const DofMap& map, MassKind kind, SystemAssembler& assembler) {
  for_each_mass(structure, map, kind, [&](std::span<const int> dofs, const Eigen::Ref<const Eigen::MatrixXd>& M) {
    assembler.add(dofs, M);
  });
}

Eigen::VectorXd raw_mass_product(const LinearStructure& structure, const DofMap& map, MassKind kind,
                                 const Eigen::VectorXd& u) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(map.raw_size());
  for_each_mass(structure, map, kind, [&](std::span<const int> dofs, const Eigen::Ref<const Eigen::MatrixXd>& M) {
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

Eigen::MatrixXd free_rigid_body_motions(const Model& model, const DofMap& map) {
  const Eigen::MatrixXd R = rigid_body_motions(model, map);
  Eigen::MatrixXd Z = Eigen::MatrixXd::Zero(map.free_size(), 6);
  for (int raw = 0; raw < map.raw_size(); ++raw)
    if (const int f = map.free_index(raw); f >= 0) Z.row(f) = R.row(raw);
  return Z;
}

}  // namespace beamfea
