#include "solvers/initial_stress.hpp"

#include "core/assembly.hpp"
#include "elements/geometric_stiffness.hpp"
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

SparseMatrix initial_stress_stiffness(const Model& model, const DofMap& map, const LinearStructure& structure,
                                      const LinearStaticResult& lin, const Eigen::VectorXd& f_ext_raw) {
  SystemAssembler ga(map);
  ga.begin();
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const auto& beam = structure.beam(static_cast<int>(e));
    if (!beam) continue;
    const auto& s = model.sections[model.elements[e].section];
    const Mat12 kg = beam_local_geometric_stiffness(beam->length(), s.A, s.Iy, s.Iz, lin.end_forces[e]);
    const Mat12 Kg = beam->transformation().transpose() * kg * beam->transformation();
    const auto dofs = structure.element_dofs(map, static_cast<int>(e));
    ga.add(dofs, Kg);
  }
  ga.end();
  SparseMatrix Kg = ga.K_ff();

  // Rigid links and joints: constraint curvature for the forces they transmit.
  if (!map.tree_edges().empty()) {
    const NonlinearStructure ns(model);  // refuses closed loops
    Eigen::VectorXd f = structure.internal_force(map, lin.u) - f_ext_raw;
    const auto cf = map.constraint_forces(f);
    for (int p = 0; p < map.prescribed_size(); ++p) {
      const int raw = map.raw_index(map.prescribed()[p].dof);
      const DofRef d = map.prescribed()[p].dof;
      if (d.owner == DofRef::Owner::Node && map.is_slave(d.index)) f[raw] -= cf.prescribed[p];
    }
    const NonlinearState s0 = ns.reference_state();
    const SparseMatrix G = ns.constraint_curvature(s0, ns.twists(s0), f);
    if (G.nonZeros() > 0) {
      const SparseMatrix Z = independent_from_free(ns, map);
      Kg += SparseMatrix(Z.transpose() * G * Z);
    }
  }
  return SparseMatrix(0.5 * (SparseMatrix(Kg.transpose()) + Kg));
}

}  // namespace beamfea
