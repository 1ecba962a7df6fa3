#pragma once
// Second-order (P-Delta) statics, and members that carry one sign of axial force only.
//
// Second order: equilibrium in the reference geometry with the geometric stiffness of the current
// axial forces (the linearised method of Frame3DD's geometric stiffness, Pynite's analyze_PDelta
// and design codes' second-order elastic analysis; docs/analyses/second-order.md):
//     (K + K_g(N(u))) u = F,
// by fixed-point iteration on the axial forces N:
//     u_0 = K^-1 F                                   the linear step (linear statics' answer)
//     u_k = (K + K_g(N(u_{k-1})))^-1 F,  k = 1, 2 ...
// converged when max_e |N_e(u_k) - N_e(u_{k-1})| <= tolerance * max_e |N_e(u_k)| (and, where rigid
// links or joints carry K_g, when the raw residual f_int - f_ext they transmit changes by no more
// than tolerance of its largest).
//   N_e    element e's mean axial force, from its end forces f_e = k_e T u_e + kg_e T u_e + the
//          fixed-end forces of its member loads (so a column's own weight enters);
//   K_g    the beams' FrameElement::geometric_stiffness of the options' kind, plus the rigid
//          links' and joints' constraint curvature (solvers/initial_stress.hpp).
// End forces, stations and reactions include K_g u. Every solve factorises K + K_g of one pattern
// (K's: the beams' K_g blocks are K's blocks), so one symbolic analysis serves them all
// (symbolic_analyses counts them: 1, or 2 where rigid links or joints first carry force after the
// linear step). A K + K_g that is not positive definite means a load at or above the elastic
// critical load: the analysis stops (Diverged) and reports the lowest load factor of the buckling
// analysis of the same loads (solvers/buckling.hpp), the linear step kept.
//
// Tension-only and compression-only members (Member::behaviour), iterated in the same loop (and
// alone in linear statics, `geometric` false; the linear step is then the last solve of a linear
// phase that ends when they settle, and K_g joins after it): after each solve an active member whose mean axial
// force (over its elements) has the wrong sign, by more than kSlackRelative of the largest |N|,
// is removed: its elements' stiffness, geometric stiffness and member loads leave the system, the
// interior nodes of a meshed member are held and reported along its chord. An inactive member
// whose ends move apart (tension-only) or together (compression-only) along its chord is restored.
// The iteration ends when the set stays the same (and, in second order, N has converged); at most
// max_iterations solves after the linear step (NotConverged otherwise: a set that keeps changing).
// A structure that becomes a mechanism is reported with the members that went slack.
#include <optional>
#include <string>
#include <vector>

#include "core/dof_map.hpp"
#include "core/model.hpp"
#include "elements/frame_element.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

// A member's mean axial force of this fraction of the largest |N| or less has no sign: it keeps
// its state (rounding of an unloaded member's force must not switch it off).
inline constexpr double kSlackRelative = 1e-9;

struct SecondOrderOptions {
  bool geometric = true;  // false: linear statics, iterating the members' behaviour alone
  GeometricStiffness kind = GeometricStiffness::Full;
  double tolerance = 1e-10;  // relative change of the axial forces
  int max_iterations = 100;  // solves after the first
  double singular_rcond = 1e-13;         // as LinearStaticOptions
  double zero_energy_tolerance = 1e-10;  // as LinearStaticOptions
  void validate() const;
};

enum class SecondOrderStatus {
  Converged,
  Diverged,      // K + K_g not positive definite: a load above the critical load
  NotConverged,  // max_iterations reached
  Mechanism,     // the structure (without its slack members) is a mechanism
  Failed,        // the stiffness could not be factorised
};
const char* to_string(SecondOrderStatus s);

struct SecondOrderResult {
  SecondOrderStatus status = SecondOrderStatus::Failed;
  std::string message;
  LinearStaticResult linear;    // the linear step (K_g = 0, slack members settled)
  LinearStaticResult solution;  // the last iterate (its status and message: this result's)
  int iterations = 0;           // solves after the first
  double amplification = 1.0;   // max |u| of the solution over that of the linear step
  double critical_load_factor = 0.0;  // Diverged: the lowest buckling load factor (NaN: none found)
  std::vector<int> inactive_members;  // member indices, ascending
  int factorizations = 0;
  int symbolic_analyses = 0;
  // Converged: K + K_g (free x free, symmetric) at the solution, inactive members left out: the
  // tangent a modal or stiffness analysis about this equilibrium uses.
  SparseMatrix tangent;
};

// The equilibrium of `loads` (a load set of the model).
SecondOrderResult solve_second_order(const Model& model, const LoadSet& loads, const SecondOrderOptions& options = {});

// About which equilibrium of a load case a loaded analysis (modal, node stiffness) linearises the
// structure, and with which beam K_g (elements/frame_element.hpp).
enum class Equilibrium { LinearStatic, SecondOrder };
struct PreloadOptions {
  Equilibrium about = Equilibrium::LinearStatic;
  GeometricStiffness geometric_stiffness = GeometricStiffness::Full;
};

// The tangent K + K_g (free x free over `map`, symmetric) about the equilibrium of `loads`:
//   LinearStatic  K_g of the linear static solution (solvers/initial_stress.hpp), every member active;
//   SecondOrder   solve_second_order's tangent (its slack members left out).
// K is the elastic stiffness over `map`. Null, with `message` saying why, when the equilibrium
// could not be found.
std::optional<SparseMatrix> loaded_tangent(const Model& model, const DofMap& map, const LinearStructure& structure,
                                           const SparseMatrix& K, const LoadSet& loads, const PreloadOptions& options,
                                           std::string& message);

// Whether any member is tension-only or compression-only.
bool has_behaviour_members(const Model& model);

// The largest node translation |u_i| of raw displacements (the largest rotation where nothing
// translates): the measure of `amplification`.
double max_translation(const Model& model, const Eigen::VectorXd& u);

}  // namespace beamfea
