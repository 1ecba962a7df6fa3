#pragma once
// What a load case does to one actuation scheme of a parallel manipulator (`load_case` on the
// `actuator_allocation` analysis; docs/analyses/actuator-allocation.md, "With a load case"). For
// the scheme's actuated candidates (solvers/actuator_allocation.hpp) and the case's loads (a
// payload on the platform, the links' and motors' own weight, member loads):
//
//   actuator efforts tau_i: the generalized force (the torque of a revolute joint, the force of a
//       translational coordinate) that actuator i applies to its joint coordinate to hold the
//       loaded manipulator: the reaction of the frozen coordinate (DofMap::constraint_forces of
//       the residual f_int - f_ext) in the frozen structure (links as modelled, passive candidates
//       free; the model of K_S). With rigid links and a wrench W applied to the platform, virtual
//       work (W^T J dq + tau^T dq = 0, J of Bu's eq. 7) gives tau = -J^T W, i.e. the robotics
//       textbook's tau = J^T F with F = -W the wrench the platform exerts on what loads it; a load
//       elsewhere (a link's weight) enters with the Jacobian of its own point. Flexible links
//       change tau only where the frozen structure is statically indeterminate.
//   platform displacement: the six components of the platform node under the case in three
//       models: total (actuator springs k_i, links as modelled), structural (actuators frozen,
//       links as modelled) and actuated (actuator springs, rigid links). With rigid links the
//       springs turn by q = -K_I^-1 tau (a spring's torque -k q balances the effort), so the
//       actuated displacement is J q = -J K_I^-1 tau; where the frozen structure is statically
//       determinate, total = structural + actuated to first order (compliances in series).
//   loaded stiffness: the directional stiffness (condense_to_directions) of K + sym(K_g) of each
//       of the three models, K_g the geometric stiffness of the case's linear solution
//       (solvers/initial_stress.hpp), as the `stiffness` analysis's loaded mode does. With rigid
//       links K_g is the curvature of the constraints that transmit the load: an inverted pendulum
//       of length L, spring k at its base and weight P at its tip, has the tip stiffness
//       (k - P L) / L^2 across its axis (k + P L hanging).
//
// Rigid links carry no member loads or self-weight in beamfea (solvers/member_loading.cpp loads
// beams only), so the actuated model gets the flexible model's consistent nodal loads instead
// (`nodal_equivalent`): statically equivalent on a rigid link, hence exact for the efforts and
// the displacements; for the loaded stiffness exact for a load whose consistent end forces carry
// its first moment (uniform loads such as self-weight), a close approximation otherwise.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/model.hpp"
#include "solvers/actuator_allocation.hpp"

namespace beamfea {

// One of the scheme's models under the case.
struct LoadedSchemeModel {
  bool ok = false;                 // the linear solution exists (no mechanism)
  std::string message;
  Vec6 platform = Vec6::Zero();    // displacement of the platform node, ux uy uz rx ry rz
  bool stiffness_ok = false;
  std::string stiffness_message;
  Eigen::MatrixXd K_loaded;        // directions x directions, condensation of K + sym(K_g)
};

struct SchemeLoadResponse {
  bool efforts_ok = false;
  std::string efforts_message;
  Eigen::VectorXd efforts;         // per actuated candidate, in the order of `actuated`
  LoadedSchemeModel total;         // springs, links as modelled
  LoadedSchemeModel structural;    // actuators frozen, links as modelled
  LoadedSchemeModel actuated;      // springs, rigid links (nodal-equivalent loads)
};

SchemeLoadResponse scheme_load_response(const Model& model, const AllocationOptions& options,
                                        const std::vector<int>& actuated, const LoadSet& loads);

// The loads as nodal forces and moments (consistent nodal loads of member loads and self-weight,
// the point masses' weight, nodal loads) plus the joint loads unchanged; no gravity, no member loads.
LoadSet nodal_equivalent(const Model& model, const LoadSet& loads);

}  // namespace beamfea
