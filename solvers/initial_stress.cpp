#include "solvers/initial_stress.hpp"

#include "core/assembly.hpp"
#include "solvers/member_loading.hpp"
#include "solvers/nonlinear_structure.hpp"

namespace beamfea {

namespace {
// Z: independent coordinates <- free DOFs (the DofMap's T_f rows at the independent raw DOFs).
SparseMatrix independent_from_free(const NonlinearStructure& ns, const DofMap& map) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < ns.size(); ++i)
    for (SparseRowMatrix::InnerIterator it(map.T_free(), ns.gens()[i].raw); it; ++it)
      t.emplace_back(i, static_cast<int>(it.col()), it.value());
  SparseMatrix Z(ns.size(), map.free_size());
  Z.setFromTriplets(t.begin(), t.end());
  return Z;
}
}  // namespace

SparseMatrix constraint_geometric_stiffness(const NonlinearStructure& ns, const DofMap& map, Eigen::VectorXd f) {
  const auto cf = map.constraint_forces(f);
  for (int p = 0; p < map.prescribed_size(); ++p) {
    if (map.prescribed()[p].constraint >= 0) continue;  // a linear constraint's value: in user_raw
    const int raw = map.raw_index(map.prescribed()[p].dof);
    const DofRef d = map.prescribed()[p].dof;
    if (d.owner == DofRef::Owner::Node && map.is_slave(d.index)) f[raw] -= cf.prescribed[p];
  }
  // Skewed supports, ties and linear constraints: the forces they apply, as the supports' above.
  f -= cf.user_raw;
  const NonlinearState s0 = ns.reference_state();
  const auto tw0 = ns.twists(s0);
  SparseMatrix G = ns.constraint_curvature(s0, tw0, f);
  // Closed loops: the curvature of each closure contracted with its multipliers, the forces it
  // transmits (mu = -lambda: DofMap's lambda balance f_int - f_ext, ours join the residual).
  if (!ns.closures().empty()) {
    Eigen::VectorXd mu(ns.closure_rows());
    for (int k = 0; k < static_cast<int>(ns.closures().size()); ++k) mu.segment<6>(6 * k) = -cf.loop[k];
    G += ns.closure_curvature(s0, tw0, mu);
  }
  if (G.nonZeros() == 0) return SparseMatrix(map.free_size(), map.free_size());
  const SparseMatrix Z = independent_from_free(ns, map);
  return SparseMatrix(Z.transpose() * G * Z);
}

SparseMatrix geometric_stiffness(const Model& model, const DofMap& map, const LinearStructure& structure,
                                 const LinearStaticResult& lin, const LoadSet& loads, GeometricStiffness kind) {
  const NonlinearStructure ns(model);
  SystemAssembler ga(map);
  ga.begin();
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const auto& beam = structure.beam(static_cast<int>(e));
    if (!beam) continue;
    // End forces include the member loads' fixed-end forces: kg takes the element's mean axial
    // force, so a load along the member (a column's own weight) converges with the mesh.
    const auto dofs = structure.element_dofs(map, static_cast<int>(e));
    ga.add(dofs, beam->geometric_stiffness(lin.end_forces[e], kind));
  }
  ga.end();
  SparseMatrix Kg = ga.K_ff();

  // Rigid links and joints: constraint curvature for the forces they transmit.
  const Eigen::VectorXd f_ext = external_force(model, map, loads);
  Kg += constraint_geometric_stiffness(ns, map, structure.internal_force(map, lin.u) - f_ext);
  return Kg;
}

}  // namespace beamfea
