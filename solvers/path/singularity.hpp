#pragma once
// Singular poses of closed loops along a path: where a loop's passive sub-chain loses rank (a passive
// dyad straightens or folds), or the whole constraint Jacobian does.
//
// A loop's passive coordinates are the free coordinates (neither prescribed nor controlled) of its
// joints that have no stiffness; its passive Jacobian A = dc/dq_p is the closure's Jacobian over them,
// restricted to the loop's independent closure rows. A is singular at a serial singularity of the
// passive sub-chain (Gosselin & Angeles 1990, "Singularity analysis of closed-loop kinematic chains",
// IEEE Trans. Robot. Autom. 6(3), the type-II singularity of the loop with the actuated joints held),
// which neither the inertia of the constrained tangent nor the rank of the whole closure need show.
// The whole constraint Jacobian C (supports on slave nodes and closures over every free coordinate)
// loses rank where the loop as a whole does (a change point): its measure is the nc-th singular value
// of all its rows, kept or dropped (PathSystem::rank_measure).
//
// The measure of each is its smallest singular value after scaling the rows and columns to be free of
// units: translation rows by 1/L, translational coordinates by L (L: the model length), so that the
// measure is the same in any consistent unit system. Where A is square the measure carries the sign of
// det A, which changes through a crossing of the singular pose: the crossing is located by bisection on
// that sign, like a critical point. A's rows are not the closure's rows themselves but an orthonormal
// basis Q of the loop's row space (the span of its closure rows' Jacobian over all coordinates, of
// the dimension of the rows kept for it), A = Q^T J_p: then A is singular exactly where J_p loses
// rank, whichever rows are kept (the rows a model keeps can lose rank on the passive coordinates
// where the loop does not: a Bennett linkage's rotation rows, where its passive axes fall into a
// plane). Q is carried along the path, projected from one converged state onto the next one's row
// space and orthonormalised by its polar factor (transport), so that its orientation, and the sign
// of det A, change continuously: through states interpolated along the way, each turning the row
// space by less than 25 degrees (a loop's row space can turn by 90 degrees and back within one step
// of a path: a Bennett linkage's near 180 degrees of its first joint). Where the path ends at the singular pose (a fold: the measure goes
// to zero like the square root of the distance, so its square linearly), the point is where the square
// of the measure, extrapolated from the last two converged states, vanishes.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "solvers/path/critical_points.hpp"
#include "solvers/path/equilibrium.hpp"

namespace beamfea {

// Where the extrapolated zero of the squared measure may lie beyond the last converged state: at most
// this many times the step that failed there (the step before its cuts).
inline constexpr double kSingularReach = 1.0;
// The measure at the last converged state must have dropped to this fraction of its value at the
// path's start before the end of a path is ascribed to a singular pose.
inline constexpr double kSingularDrop = 0.1;
// A located crossing is a singular pose where the passive Jacobian's smallest singular value at the
// final bracket is below this fraction of its value at the step's ends.
inline constexpr double kSingularConfirm = 0.1;

// One measured Jacobian: a loop's passive Jacobian, or the whole constraint Jacobian.
struct SingularityCandidate {
  int closure = -1;             // the loop's closure (NonlinearStructure::closures()); -1: the whole Jacobian
  std::vector<int> rows;        // the loop's independent closure rows (structure numbering)
  std::vector<int> gens;        // the passive coordinates (gens)
  bool square = false;          // A square: the measure is signed
  std::vector<int> joints, nodes;  // what it involves (model indices, ascending)
};

class SingularityMonitor {
 public:
  // The candidates of the system's rows, their bases taken at `st` (the path's first state).
  SingularityMonitor(const PathSystem& sys, const NonlinearState& st) : sys_(sys) { refresh(st); }
  // The candidates afresh from the system's rows (after PathSystem::reselect), at the state st.
  void refresh(const NonlinearState& st);
  // Carries the loops' bases to the converged state st (the next state of the path). Where they do
  // not carry (kMaxCarrySteps interpolated states do not suffice) they are taken afresh there, and
  // false returned: a change of sign of a measure over that step means nothing.
  bool transport(const NonlinearState& st);
  // Whether the loops' bases carry to st (transport would keep them): the signs of the measures at
  // st compare with those at the state the bases are at.
  bool transportable(const NonlinearState& st) const;
  bool empty() const { return candidates_.empty(); }
  const std::vector<SingularityCandidate>& candidates() const { return candidates_; }
  // The measure of every candidate at a state (signed where square; NaN for a loop whose basis does
  // not carry there).
  Eigen::VectorXd measures(const NonlinearState& st) const;
  // The smallest singular value of a loop's passive Jacobian over all its six closure rows (scaled,
  // unsigned: no basis), or the whole Jacobian's measure.
  double passive_rank_measure(const NonlinearState& st, int candidate) const;
  // "passive joints 'J4', 'J5', 'J6' of the loop closed by element 'PJ4'" / "the constraints of the
  // loops through joints ...": what a candidate is, in words.
  std::string describe(int candidate) const;

 private:
  // A loop candidate's scaled closure rows over every free coordinate (6 x nf) at a state, and the
  // projector's basis: the leading left singular vectors of as many rows as are kept for the loop.
  Eigen::MatrixXd loop_rows(const NonlinearState& st, const SingularityCandidate& c) const;
  Eigen::MatrixXd row_space(const NonlinearState& st, const SingularityCandidate& c) const;
  // The loop's six scaled rows over its passive coordinates (6 x gens).
  Eigen::MatrixXd passive_jacobian(const NonlinearState& st, const SingularityCandidate& c) const;
  // The bases carried from at_ to st through interpolated states (`out`); false where they do not
  // carry.
  bool carry(const NonlinearState& st, std::vector<Eigen::MatrixXd>& out) const;
  // A loop's basis taken afresh at st: the unit vectors of its kept rows projected on its row space.
  Eigen::MatrixXd fresh_basis(const NonlinearState& st, const SingularityCandidate& c) const;

  const PathSystem& sys_;
  std::vector<SingularityCandidate> candidates_;
  std::vector<Eigen::MatrixXd> basis_;  // per candidate: Q (6 x rows) of a loop; empty for the whole Jacobian
  NonlinearState at_;                   // the state the bases are at
};

// A basis is carried from one interpolated state to the next when its projection onto the next
// one's row space keeps its smallest singular value above this (cos 25 degrees), through at most
// kMaxCarrySteps states.
inline constexpr double kCarryQuality = 0.9;
inline constexpr int kMaxCarrySteps = 256;

// A crossing of a signed candidate's singular pose between cur and next (measures m_cur, m_next of
// opposite signs), located by bisection of the step on the sign of the measure; the point carries
// the load factor and control value interpolated to the zero of the measure. `confirmed` (when
// given): whether the passive Jacobian over all the loop's rows (unsigned, free of any basis) at the
// final bracket is below kSingularConfirm of its value at the step's ends, as it is at a singular
// pose bisected to critical_tolerance; not where the bisection could not close in (its trial steps
// failing, off the loop) or the sign changed without the rank dropping.
CriticalPoint locate_singularity(const CriticalPointParts& parts, const SingularityMonitor& monitor, int candidate,
                                 const Converged& cur, const Converged& next, double m_cur, double m_next, double h,
                                 const Eigen::VectorXd& dir, PathControl mode,
                                 const std::function<double(const Converged&, double)>& control_at,
                                 bool* confirmed = nullptr);

// The end of a path at a singular pose: of the candidates whose measure fell from m_prev to m_cur
// (below kSingularDrop of m_start), the one whose squared measure, extrapolated linearly in the
// control value from (c_prev, c_cur), vanishes nearest, within `reach` of c_cur. The point carries the
// load factor and control value extrapolated there.
std::optional<CriticalPoint> singular_end(const SingularityMonitor& monitor, const Eigen::VectorXd& m_start,
                                          const Eigen::VectorXd& m_prev, const Eigen::VectorXd& m_cur,
                                          double lambda_prev, double lambda_cur, double c_prev, double c_cur,
                                          double reach);

}  // namespace beamfea
