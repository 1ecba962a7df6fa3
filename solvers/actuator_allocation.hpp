#pragma once
// Actuated, structural and total stiffness of a parallel manipulator for a choice of actuated
// joints, after W. Bu, "On the Stiffness Affected by the Allocation of Actuators of a Parallel
// Manipulator", The Open Mechanical Engineering Journal 6 (2012). Equation numbers are the paper's.
//
// The manipulator is an ordinary model: links are beams (or rigid links), joints are joints.
// A *candidate* is one joint coordinate that may carry an actuator; a *scheme* is a choice of
// candidates that do (eq. 20 counts them). For a scheme:
//
//   actuated stiffness K_A (eqs. 1-10)   links rigid, actuated coordinates springs k_i, the other
//       candidates passive (free). (a) from the Jacobian: J column i = platform twist per unit motion
//       of actuator i with the other actuators locked (a DofMap expansion of the rigid model with
//       the actuated coordinates prescribed); K_A = J^-T K_I J^-1 (eq. 10). (b) the condensed
//       stiffness of the rigid model with the actuator springs. They agree when J is square and
//       regular. A non-square J (lower mobility in the requested directions) gets eq. 9 in its
//       pseudo-inverse form K_A = J^+T K_I J^+ (stiffness within the range of J), a singular J
//       and redundant actuation a message; nothing throws for them.
//   structural stiffness K_S (eqs. 11-14) actuated coordinates frozen (prescribed 0), passive
//       ones free, links flexible. (a) principle of virtual force: for a unit load at the platform
//       in each direction the internal forces N, Qy, Qz, T, My, Mz of every element are the FEA
//       end forces of the frozen structure; C_S,ij = sum over elements of the integrals of eq. 12
//       (axial N_i N_j / EA, shear k Q_i Q_j / GA, torsion T_i T_j / GJ, bending M_i M_j / EI).
//       For an indeterminate frozen structure these internal forces already satisfy compatibility
//       (the stiffness method finds the redundants), so the unit-load integrals stay exact; the
//       same internal forces serve as real and virtual ones. (b) the FEA compliance of the same
//       structure (unit-load solves) and its condensed stiffness. (a) with the axial, bending and
//       torsion terms equals (b) to rounding (beams are Euler-Bernoulli: the shear term of (a) has
//       no FEA counterpart and is reported on its own). Eq. 14 is (a) with the bending term only.
//       Directions the frozen structure holds rigidly (a lumped model of rigid links) have C_S = 0:
//       an infinitely stiff structure there, not a mechanism.
//   total stiffness (eq. 19)  per direction d, as the paper: K_d = K_A,dd K_S,d / (K_A,dd + K_S,d)
//       (K_A,dd where C_S,dd = 0)
//       with K_A,dd the diagonal of K_A and K_S,d = 1 / C_S,dd; and consistently, compliances in
//       series C = K_A^-1 + C_S (matrix), equal to the condensed stiffness of the model with the
//       actuator springs and the flexible links (computed as a check).
//
// Directions: the platform node has six DOFs (ux uy uz rx ry rz); results are for the requested
// ones (e.g. rz ux uy for a planar manipulator, the paper's [phi, x, y]). A stiffness "in the
// directions" leaves the node's other DOFs free: it is the inverse of the node's compliance
// restricted to the directions, computed directly as the saddle point of condense_to_node with
// only the requested rows (so it exists when the other DOFs are held rigidly by the constraints,
// as the out-of-plane DOFs of a planar linkage of rigid links are).
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "core/dof_map.hpp"
#include "core/model.hpp"
#include "solvers/mechanism.hpp"

namespace beamfea {

// One joint coordinate that may carry an actuator.
struct ActuatorCandidate {
  int joint = -1;
  int coordinate = 0;
};

// Stiffness of `node` in directions `dirs` (0..5, ux..rz) with the node's other DOFs free:
// K_d = ((K_c^-1)_dd)^-1 for the condensed stiffness K_c of condense_to_node, computed from
// [K T_d^T; T_d 0][X; M] = [0; I], K_d = -M. ok = false (message) when a direction is held
// rigidly or holding the node in the directions leaves a mechanism.
struct DirectionalStiffness {
  bool ok = false;
  std::string message;
  Eigen::MatrixXd K;
};
DirectionalStiffness condense_to_directions(const Model& model, const DofMap& map, const SparseMatrix& K, int node,
                                            const std::vector<int>& dirs);

// Moves nodes to new positions: each override also moves the nodes joined to it by joints
// (unless they are overridden themselves), and internal nodes of divided members are re-spaced.
// Throws ModelError naming a joint whose nodes no longer coincide or a member of zero length.
void apply_node_positions(Model& model, const std::vector<std::pair<int, Vec3>>& positions);

enum class StructuralTerm { Axial = 0, Shear = 1, Torsion = 2, Bending = 3 };
inline constexpr int kStructuralTermCount = 4;
const char* to_string(StructuralTerm t);

struct AllocationOptions {
  int platform_node = -1;
  std::vector<int> directions;                 // 0..5
  std::vector<ActuatorCandidate> candidates;
  std::vector<double> actuator_stiffness;      // one per candidate, > 0
  // Terms of eq. 12 in the structural compliance used for K_S and the totals; {Bending} is eq. 14.
  std::vector<StructuralTerm> terms{StructuralTerm::Axial, StructuralTerm::Shear, StructuralTerm::Torsion,
                                    StructuralTerm::Bending};
  double singular_tolerance = 1e-9;            // |det J| relative to the product of column norms
  void validate(const Model& model) const;
};

// Actuated stiffness (eqs. 1-10); matrices in the order of the requested directions.
struct ActuatedStiffness {
  bool jacobian_ok = false;          // J could be formed
  std::string jacobian_message;
  Eigen::MatrixXd J;                 // directions x actuators
  double det_J = 0.0;                // square J only
  std::string form;                  // "eq10", "eq9_pseudo_inverse", "" (none)
  Eigen::MatrixXd K_jacobian;        // K_A from J
  bool condensed_ok = false;
  std::string condensed_message;
  Eigen::MatrixXd K_condensed;       // K_A from the rigid model with actuator springs
  bool ok() const { return jacobian_ok && !form.empty(); }
  const Eigen::MatrixXd& K() const { return condensed_ok ? K_condensed : K_jacobian; }
};

// Per member, per direction d (unit load in d): the integrals of eq. 12 over the member.
struct LinkIntegrals {
  int member = -1;
  // raw[d][k]: integral of the squared unit-load internal force k over the member, k = N, Qy, Qz,
  // T, My, Mz (m for forces, m^3 for moments: Tables 3/4 give the Mz one).
  std::vector<std::array<double, 6>> raw;
  // compliance[d][t]: contribution of term t (StructuralTerm) to C_S,dd.
  std::vector<std::array<double, kStructuralTermCount>> compliance;
};

struct StructuralStiffness {
  bool ok = false;
  std::string message;
  std::vector<ZeroEnergyMode> modes;                   // frozen structure is a mechanism
  Eigen::MatrixXd C_fea;                               // FEA compliance, directions^2
  Eigen::MatrixXd K_fea;                               // condensed stiffness of the frozen structure
  std::array<Eigen::MatrixXd, kStructuralTermCount> C_terms;  // virtual force, term by term
  Eigen::MatrixXd C;                                   // virtual force, options.terms summed
  double fea_mismatch = 0.0;  // |C_vf(axial+torsion+bending) - C_fea| / |C_fea| (max norms)
  std::vector<LinkIntegrals> links;
  // Directions (indices into options.directions) that the frozen structure holds rigidly: no
  // elastic DOF moves the platform there (rigid links, as in a lumped model), so C_S has zero rows
  // and columns there (an infinitely stiff structure) and the total stiffness is the actuated one.
  std::vector<int> held;
};

struct TotalStiffness {
  bool ok = false;
  std::string message;
  Eigen::VectorXd eq19;              // per direction, eq. 19 with K_A,dd and 1/C_S,dd
  Eigen::MatrixXd K_series;          // (K_A^-1 + C_S)^-1
  bool fea_ok = false;
  Eigen::MatrixXd K_fea;             // condensed stiffness with springs and flexible links
};

struct SchemeResult {
  std::vector<int> actuated;         // indices into options.candidates, ascending
  bool valid = false;                // frozen structure stable and J regular
  std::string status;                // "ok", "mechanism", "singular", "redundant"
  std::string message;
  ActuatedStiffness actuated_stiffness;
  StructuralStiffness structural;
  TotalStiffness total;
};

ActuatedStiffness actuated_stiffness(const Model& model, const AllocationOptions& options,
                                     const std::vector<int>& actuated);
StructuralStiffness structural_stiffness(const Model& model, const AllocationOptions& options,
                                         const std::vector<int>& actuated);
SchemeResult evaluate_scheme(const Model& model, const AllocationOptions& options, const std::vector<int>& actuated);

// The model of one scheme: every candidate passive (stiffness 0) except the actuated ones, which
// are springs k_i or frozen (prescribed 0); links rigid (every beam an exact rigid link) or as
// modelled; every prescribed value zero; `loads` as its default load case (none by default).
// Rigid links carry no member loads or self-weight (member_loading skips non-beams): give such a
// model statically equivalent nodal loads (solvers/actuator_load_case.hpp does).
enum class SchemeLinks { Rigid, Flexible };
enum class SchemeActuators { Springs, Frozen };
Model scheme_model(const Model& model, const AllocationOptions& options, const std::vector<int>& actuated,
                   SchemeLinks links, SchemeActuators actuators, const LoadSet& loads = {});

// All C(n, k) ascending index combinations, lexicographic.
std::vector<std::vector<int>> combinations(int n, int k);

}  // namespace beamfea
