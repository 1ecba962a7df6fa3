#pragma once
// The linear structural dynamics of a model, M x'' + C x' + K x = f(t), over the free DOFs of its
// DofMap (supports and prescribed DOFs held: the motion is relative to their values; rigid links
// and joints eliminated exactly, as for the modal analysis, solvers/modal.hpp):
//   K  the elastic stiffness, or the tangent K + K_g about the equilibrium of a load case
//      (solvers/second_order.hpp, loaded_tangent), as the modal analysis uses it;
//   M  the consistent or lumped mass (solvers/mass_matrix.hpp);
//   C  the viscous damping of the model (core/model.hpp, Damping): alpha M + beta K (Rayleigh,
//      with the K above) plus the joints' coefficients on their coordinates, C_ff = T_f^T C_raw T_f.
//      Modal damping (a ratio per mode) is no matrix of this kind: the modal superposition uses it
//      (solvers/frequency_response.hpp), the direct solvers reject it.
#include <optional>
#include <string>

#include "core/dof_map.hpp"
#include "core/model.hpp"
#include "elements/beam_mass.hpp"
#include "solvers/second_order.hpp"

namespace beamfea {

struct DynamicSystemOptions {
  MassKind mass = MassKind::Consistent;
  bool preload = false;        // K + K_g about the equilibrium of the preload's loads
  PreloadOptions about_state;  // which equilibrium, which K_g
};

enum class DynamicSystemStatus {
  Succeeded,
  NoFreeDofs,
  NoMass,         // M has no entry on the free DOFs
  PreloadFailed,  // the equilibrium of the preload was not found
};

struct DynamicSystem {
  DynamicSystemStatus status = DynamicSystemStatus::NoFreeDofs;
  std::string message;  // why not, when not Succeeded
  SparseMatrix K, M;    // free x free, symmetric
  SparseMatrix C;       // free x free, symmetric: Rayleigh and joint damping (zero without damping)
  bool has_damping_matrix = false;  // C has a non-zero entry
};

// The matrices of `model` over `map` (a DofMap of the model in its reference configuration);
// `preload`: the loads of the equilibrium about which K is taken (read when options.preload).
DynamicSystem dynamic_system(const Model& model, const DofMap& map, const LoadSet& preload,
                             const DynamicSystemOptions& options);

// The joints' viscous damping, T_f^T C_raw T_f over the free DOFs (C_raw diagonal on the joint
// coordinates).
SparseMatrix joint_damping(const Model& model, const DofMap& map);

// A unit generalised force at raw DOF `raw`, over the free DOFs: T_f^T e_raw (a force on a slave
// node reaches the DOFs that carry it).
Eigen::VectorXd unit_free_force(const DofMap& map, int raw);

// Whether raw DOF `raw` moves with the free DOFs (false: held by a support or a prescription).
bool raw_dof_moves(const DofMap& map, int raw);

}  // namespace beamfea
