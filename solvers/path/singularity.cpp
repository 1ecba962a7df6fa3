#include "solvers/path/singularity.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <Eigen/SVD>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>

namespace beamfea {

namespace {

// Whether coordinate `comp` of joint j has no stiffness (a passive coordinate).
bool passive(const Joint& j, int comp) {
  if (!j.has_stiffness()) return true;
  const Eigen::MatrixXd K = j.stiffness_as_matrix();
  if (comp >= K.rows()) return true;
  return K.row(comp).cwiseAbs().maxCoeff() == 0.0 && K.col(comp).cwiseAbs().maxCoeff() == 0.0;
}

// The nodes of joints, ascending and unique.
std::vector<int> nodes_of(const Model& m, const std::vector<int>& joints) {
  std::set<int> s;
  for (int j : joints) s.insert(m.joints[j].nodes.begin(), m.joints[j].nodes.end());
  return {s.begin(), s.end()};
}

std::string quoted_joints(const Model& m, const std::vector<int>& joints) {
  std::string s;
  for (std::size_t i = 0; i < joints.size(); ++i)
    s += (i ? ", '" : "'") + m.joints[joints[i]].id + "'";
  return s;
}

// The polar factor U V^T of M = U S V^T (6 x r): the orthonormal basis nearest M, turning with it.
Eigen::MatrixXd polar_factor(const Eigen::MatrixXd& M) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(M, Eigen::ComputeThinU | Eigen::ComputeThinV);
  return svd.matrixU() * svd.matrixV().transpose();
}

// The smallest singular value of M (rows <= cols: the rows-th), signed by det M when square.
double measure_of(const Eigen::MatrixXd& M, bool square) {
  if (M.rows() == 0) return 0.0;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(M);
  const double s = svd.singularValues()[std::min(M.rows(), M.cols()) - 1];
  if (!square) return s;
  return M.determinant() < 0.0 ? -s : s;
}

}  // namespace

void SingularityMonitor::refresh(const NonlinearState& st) {
  candidates_.clear();
  const PathSystem& sys = sys_;
  const NonlinearStructure& ns = sys.structure();
  const Model& m = ns.model();
  const auto& cl = ns.closures();
  std::set<int> all_joints;
  for (int k = 0; k < static_cast<int>(cl.size()); ++k) {
    SingularityCandidate c;
    c.closure = k;
    for (int r : sys.closure_rows())
      if (r / 6 == k) c.rows.push_back(r);
    // The loop's coordinates: those upstream of exactly one side of the closure.
    std::vector<int> a = ns.chain(cl[k].edge.child), b = cl[k].chain, loop;
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    std::set_symmetric_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(loop));
    std::set<int> joints;
    for (int g : loop) {
      const auto& gen = ns.gens()[g];
      if (gen.kind != NonlinearStructure::GenKind::JointScalar && gen.kind != NonlinearStructure::GenKind::JointSpherical)
        continue;
      all_joints.insert(gen.owner);
      if (sys.free_index(g) < 0 || !passive(m.joints[gen.owner], gen.comp)) continue;
      c.gens.push_back(g);
      joints.insert(gen.owner);
    }
    if (cl[k].edge.kind == ConstraintEdge::Kind::Joint) all_joints.insert(cl[k].edge.index);
    // A passive sub-chain that alone cannot close the loop has no serial singularity of its own.
    if (c.rows.empty() || c.gens.size() < c.rows.size()) continue;
    c.square = c.gens.size() == c.rows.size();
    c.joints.assign(joints.begin(), joints.end());
    c.nodes = nodes_of(m, c.joints);
    candidates_.push_back(std::move(c));
  }
  if (!cl.empty() && sys.nc() > 0) {
    SingularityCandidate c;
    c.joints.assign(all_joints.begin(), all_joints.end());
    c.nodes = nodes_of(m, c.joints);
    candidates_.push_back(std::move(c));
  }
  // A loop's basis: its kept rows' unit vectors projected onto its row space at st.
  at_ = st;
  basis_.assign(candidates_.size(), Eigen::MatrixXd());
  for (std::size_t i = 0; i < candidates_.size(); ++i)
    if (candidates_[i].closure >= 0) basis_[i] = fresh_basis(st, candidates_[i]);
}

Eigen::MatrixXd SingularityMonitor::fresh_basis(const NonlinearState& st, const SingularityCandidate& c) const {
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(6, static_cast<Eigen::Index>(c.rows.size()));
  for (std::size_t r = 0; r < c.rows.size(); ++r) S(c.rows[r] % 6, static_cast<Eigen::Index>(r)) = 1.0;
  const Eigen::MatrixXd U = row_space(st, c);
  return polar_factor(U * (U.transpose() * S));
}

Eigen::MatrixXd SingularityMonitor::loop_rows(const NonlinearState& st, const SingularityCandidate& c) const {
  return sys_.scaled_rows(st).middleRows(sys_.closure_row_offset() + 6 * c.closure, 6);
}

Eigen::MatrixXd SingularityMonitor::passive_jacobian(const NonlinearState& st, const SingularityCandidate& c) const {
  const Eigen::MatrixXd A = loop_rows(st, c);
  Eigen::MatrixXd Jp(6, static_cast<Eigen::Index>(c.gens.size()));
  for (std::size_t g = 0; g < c.gens.size(); ++g) Jp.col(static_cast<Eigen::Index>(g)) = A.col(sys_.free_index(c.gens[g]));
  return Jp;
}

Eigen::MatrixXd SingularityMonitor::row_space(const NonlinearState& st, const SingularityCandidate& c) const {
  const Eigen::MatrixXd A = loop_rows(st, c);
  // The leading left singular vectors (6 x rows) of A, through A A^T (6 x 6).
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(A * A.transpose());
  const auto r = static_cast<Eigen::Index>(c.rows.size());
  return es.eigenvectors().rightCols(r);
}

bool SingularityMonitor::carry(const NonlinearState& st, std::vector<Eigen::MatrixXd>& out) const {
  out = basis_;
  if (std::all_of(basis_.begin(), basis_.end(), [](const Eigen::MatrixXd& b) { return b.size() == 0; })) return true;
  for (int n = 1; n <= kMaxCarrySteps; n *= 2) {
    out = basis_;
    bool ok = true;
    for (int k = 1; k <= n && ok; ++k) {
      const NonlinearState s = k == n ? st : sys_.between(at_, st, static_cast<double>(k) / n);
      for (std::size_t i = 0; i < candidates_.size() && ok; ++i) {
        if (out[i].size() == 0) continue;
        const Eigen::MatrixXd U = row_space(s, candidates_[i]);
        const Eigen::MatrixXd projected = U * (U.transpose() * out[i]);
        ok = Eigen::JacobiSVD<Eigen::MatrixXd>(projected).singularValues().minCoeff() >= kCarryQuality;
        out[i] = polar_factor(projected);
      }
    }
    if (ok) return true;
  }
  return false;
}

bool SingularityMonitor::transportable(const NonlinearState& st) const {
  std::vector<Eigen::MatrixXd> carried;
  return carry(st, carried);
}

bool SingularityMonitor::transport(const NonlinearState& st) {
  std::vector<Eigen::MatrixXd> carried;
  const bool ok = carry(st, carried);
  at_ = st;
  if (ok) {
    basis_ = std::move(carried);
    return true;
  }
  for (std::size_t i = 0; i < candidates_.size(); ++i)
    if (basis_[i].size()) basis_[i] = fresh_basis(st, candidates_[i]);
  return false;
}

Eigen::VectorXd SingularityMonitor::measures(const NonlinearState& st) const {
  Eigen::VectorXd out(static_cast<Eigen::Index>(candidates_.size()));
  std::vector<Eigen::MatrixXd> carried;
  const bool carries = carry(st, carried);
  for (std::size_t i = 0; i < candidates_.size(); ++i) {
    const SingularityCandidate& c = candidates_[i];
    if (c.closure >= 0) {
      // Q^T J_p with Q the basis carried to this state's row space (see the header).
      const Eigen::MatrixXd A = carried[i].transpose() * passive_jacobian(st, c);
      out[static_cast<Eigen::Index>(i)] = carries ? measure_of(A, c.square) : NAN;
    } else {
      // The whole constraint Jacobian: its nc()-th singular value over all the rows (kept or
      // dropped), whichever rows are kept.
      out[static_cast<Eigen::Index>(i)] = sys_.rank_measure(st);
    }
  }
  return out;
}

std::string SingularityMonitor::describe(int candidate) const {
  const NonlinearStructure& ns = sys_.structure();
  const Model& m = ns.model();
  const SingularityCandidate& c = candidates_[candidate];
  if (c.closure < 0) return "the constraints of the loops through joints " + quoted_joints(m, c.joints);
  const auto& e = ns.closures()[c.closure].edge;
  const std::string closer = e.kind == ConstraintEdge::Kind::Rigid ? "element '" + m.elements[e.index].id + "'"
                                                                   : "joint '" + m.joints[e.index].id + "'";
  return fmt::format("passive joints {} of the loop closed by {}", quoted_joints(m, c.joints), closer);
}

namespace {

CriticalPoint singular_point(const SingularityMonitor& monitor, int candidate) {
  CriticalPoint p;
  p.type = CriticalPointType::Singularity;
  p.joints = monitor.candidates()[candidate].joints;
  p.nodes = monitor.candidates()[candidate].nodes;
  p.what = monitor.describe(candidate);
  return p;
}

}  // namespace

CriticalPoint locate_singularity(const CriticalPointParts& parts, const SingularityMonitor& monitor, int candidate,
                                 const Converged& cur, const Converged& next, double m_cur, double m_next, double h,
                                 const Eigen::VectorXd& dir, PathControl mode,
                                 const std::function<double(const Converged&, double)>& control_at,
                                 bool* confirmed) {
  Converged before = cur, after = next;
  double lo = 0.0, hi = 1.0, m_lo = m_cur, m_hi = m_next;
  for (int it = 0; it < kMaxBisections && hi - lo > parts.options.critical_tolerance; ++it) {
    const double mid = 0.5 * (lo + hi);
    const StepPrediction trial = trial_step(parts, cur, mid, h, dir, mode);
    const StepSolution sol = parts.corrector.solve(cur, trial.spec, trial.u);
    if (!sol.converged) break;
    const double m = monitor.measures(sol.state.state)[candidate];
    if (!std::isfinite(m)) break;  // a state the basis does not carry to
    if ((m > 0.0) == (m_cur > 0.0)) {
      lo = mid, m_lo = m, before = sol.state;
    } else {
      hi = mid, m_hi = m, after = sol.state;
    }
  }
  // The zero of the measure, linear between the bracket's ends.
  const double t = m_lo == m_hi ? 0.5 : m_lo / (m_lo - m_hi);
  CriticalPoint p = singular_point(monitor, candidate);
  p.load_factor = before.lambda + t * (after.lambda - before.lambda);
  p.control = control_at(before, lo) + t * (control_at(after, hi) - control_at(before, lo));
  p.reaction = before.extra_mu + t * (after.extra_mu - before.extra_mu);
  p.passed = true;
  // Confirmed where the passive Jacobian itself (all the loop's rows) nearly loses rank at the
  // bracket, against the step's ends.
  const double at_bracket = std::min(monitor.passive_rank_measure(before.state, candidate),
                                     monitor.passive_rank_measure(after.state, candidate));
  const double at_ends = std::max(monitor.passive_rank_measure(cur.state, candidate),
                                  monitor.passive_rank_measure(next.state, candidate));
  if (confirmed) *confirmed = at_bracket <= kSingularConfirm * at_ends;
  return p;
}

double SingularityMonitor::passive_rank_measure(const NonlinearState& st, int candidate) const {
  const SingularityCandidate& c = candidates_[candidate];
  if (c.closure < 0) return sys_.rank_measure(st);
  const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(passive_jacobian(st, c)).singularValues();
  return s.size() ? s[s.size() - 1] : 0.0;
}

std::optional<CriticalPoint> singular_end(const SingularityMonitor& monitor, const Eigen::VectorXd& m_start,
                                          const Eigen::VectorXd& m_prev, const Eigen::VectorXd& m_cur,
                                          double lambda_prev, double lambda_cur, double c_prev, double c_cur,
                                          double reach) {
  std::optional<CriticalPoint> best;
  double nearest = INFINITY;
  for (int i = 0; i < m_cur.size(); ++i) {
    const double a2 = m_prev[i] * m_prev[i], b2 = m_cur[i] * m_cur[i];
    if (!(b2 < a2) || !(std::abs(m_cur[i]) <= kSingularDrop * std::abs(m_start[i]))) continue;
    // m^2 linear in the control value: zero at c_cur + t (c_cur - c_prev).
    const double t = b2 / (a2 - b2);
    const double dist = t * std::abs(c_cur - c_prev);
    if (!(dist <= reach) || dist >= nearest) continue;
    nearest = dist;
    CriticalPoint p = singular_point(monitor, i);
    p.load_factor = lambda_cur + t * (lambda_cur - lambda_prev);
    p.control = c_cur + t * (c_cur - c_prev);
    best = std::move(p);
  }
  return best;
}

}  // namespace beamfea
