#pragma once
// Diagnosis of singular structures: the zero-energy modes of a reduced stiffness matrix, and
// the nodes, elements, joints and DOFs that take part in each.
#include <string>
#include <vector>

#include "core/dof_map.hpp"
#include "core/model.hpp"

namespace beamfea {

struct ZeroEnergyMode {
  Eigen::VectorXd free;       // the mode over the free DOFs
  std::vector<int> nodes;     // nodes that move in it
  std::vector<int> elements;  // elements attached to a moving node whose ends move differently
  std::vector<int> joints;    // joints whose coordinates move
  std::vector<DofRef> dofs;   // the raw DOFs that move most
  std::string description;    // one line naming all of the above
};

// Zero-energy modes of K (free x free): eigenvectors of the Jacobi-scaled matrix whose
// eigenvalue is below `tolerance` (dimensionless). At most `max_modes`.
std::vector<ZeroEnergyMode> zero_energy_modes(const Model& model, const DofMap& map, const SparseMatrix& K,
                                              int max_modes = 12, double tolerance = 1e-10);

// "mechanism: 2 zero-energy modes; mode 1: ...; mode 2: ..."
std::string describe_mechanism(const std::vector<ZeroEnergyMode>& modes);

}  // namespace beamfea
