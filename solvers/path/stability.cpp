#include "solvers/path/stability.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <Eigen/UmfPackSupport>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "solvers/eigen_lowest.hpp"

namespace beamfea {

namespace {
// Pivots below this fraction of the largest constraint coefficient are zero (a dependent row).
constexpr double kNullSpacePivotTolerance = 1e-12;
// Shift of the shift-invert eigen-solver just below a positive definite (Jacobi-scaled, so O(1))
// spectrum: fast convergence to the lowest eigenvalue.
constexpr double kEigenShiftMargin = 1e-6;
// Below zero, the shift is this factor times the last lowest eigenvalue (a little below it: the
// eigenvalue nearest the shift is the lowest one while it moves by less than half its value).
constexpr double kNegativeShiftFactor = 1.5;
// The shift when the first negative eigenvalue appears (just past a critical point the lowest
// eigenvalue of the Jacobi-scaled matrix is small).
constexpr double kFirstNegativeShift = 1e-3;
}  // namespace

SparseMatrix null_space(const Eigen::MatrixXd& C0, int n) {
  std::vector<Eigen::Triplet<double>> t;
  if (C0.rows() == 0) {
    SparseMatrix Z(n, n);
    Z.setIdentity();
    return Z;
  }
  Eigen::MatrixXd C = C0;
  std::vector<int> pivot_col;
  std::vector<char> is_pivot(n, 0);
  const double scale = C.cwiseAbs().maxCoeff();
  int r = 0;
  for (; r < C.rows(); ++r) {
    Eigen::Index pr, pc;
    const double best = C.bottomRows(C.rows() - r).cwiseAbs().maxCoeff(&pr, &pc);
    if (!(best > kNullSpacePivotTolerance * scale)) break;
    pr += r;
    C.row(r).swap(C.row(pr));
    C.row(r) /= C(r, pc);
    for (Eigen::Index i = 0; i < C.rows(); ++i)
      if (i != r && C(i, pc) != 0.0) C.row(i) -= C(i, pc) * C.row(r);
    pivot_col.push_back(static_cast<int>(pc));
    is_pivot[pc] = 1;
  }
  int col = 0;
  for (int j = 0; j < n; ++j) {
    if (is_pivot[j]) continue;
    t.emplace_back(j, col, 1.0);
    for (int i = 0; i < r; ++i)
      if (C(i, j) != 0.0) t.emplace_back(pivot_col[i], col, -C(i, j));
    ++col;
  }
  SparseMatrix Z(n, col);
  Z.setFromTriplets(t.begin(), t.end());
  return Z;
}

StabilityAnalysis constrained_tangent(const PathSystem& P, FactorCache& factors, const Converged& c,
                                      ControlDof control) {
  StabilityAnalysis out;
  // The tangent at the state, as the predictor sees it (evaluated once per state).
  const NonlinearStructure::Evaluation& ev = factors.evaluation_at(P, c);
  // Restriction to the free coordinates, column by column: the free index is increasing on the free
  // gens, so the rows and columns stay in order (no triplets, no sort).
  const int nf = P.nf();
  SparseMatrix Kff(nf, nf);
  Kff.reserve(ev.tangent.nonZeros());
  for (int j = 0; j < ev.tangent.outerSize(); ++j) {
    if (P.free_index(j) < 0) continue;
    Kff.startVec(P.free_index(j));
    for (SparseMatrix::InnerIterator it(ev.tangent, j); it; ++it)
      if (P.free_index(it.row()) >= 0) Kff.insertBack(P.free_index(it.row()), P.free_index(j)) = it.value();
  }
  Kff.finalize();
  const Eigen::MatrixXd C = P.constraint_matrix(c.state, control);
  out.Z = null_space(C, nf);
  if (C.rows() == 0) {  // Z = I
    out.K = std::move(Kff);
    out.p = P.load_pattern(c.state);
  } else {
    out.K = SparseMatrix(out.Z.transpose() * Kff * out.Z);
    out.p = out.Z.transpose() * P.load_pattern(c.state);
  }
  return out;
}

StabilityAnalyzer::StabilityAnalyzer(const PathSystem& sys, FactorCache& factors, int dense_limit)
    : sys_(sys), factors_(factors), dense_limit_(dense_limit) {}

StabilityAnalysis StabilityAnalyzer::analyse(const Converged& c, const StabilityRequest& request) {
  const bool want_mode = request.mode == CriticalMode::Wanted;
  StabilityAnalysis out = constrained_tangent(sys_, factors_, c, request.control);
  const int n = static_cast<int>(out.K.rows());
  if (n == 0) return out;
  const bool large = n > dense_limit_;
  // No constraint row (Z = I): the matrix is the symmetric part of the tangent system itself, which
  // the factor cache factorises by LL^T where it can (is_cholesky): that factor, shared with
  // the next predictor and the chord iterations, decides the inertia and gives the lowest
  // eigenvalue; no factorisation here.
  const bool unconstrained = out.Z.rows() == out.Z.cols() && n == sys_.nf();
  if (large && unconstrained && !last_indefinite_ && n > kSymmetricTangentMinDofs) factors_.tangent(sys_, c);
  const bool shared = large && unconstrained && factors_.is_cholesky(c);
  // The symmetrised matrix, made only where something here factorises or reads it.
  SparseMatrix S;
  const auto symmetrised = [&]() -> const SparseMatrix& {
    if (S.rows() != n) S = SparseMatrix(0.5 * (out.K + SparseMatrix(out.K.transpose())));
    return S;
  };
  // Inertia (Sylvester's law): positive definite when the LL^T succeeds, otherwise the number of
  // negative pivots of the LDL^T.
  const bool cholesky = shared || (large && !last_indefinite_ && llt_.factorize(symmetrised()));
  if (cholesky) {
    out.info.negative = 0;
  } else if (inertia_ldlt_.factorize(symmetrised())) {
    out.info.negative = static_cast<int>((inertia_ldlt_.solver().vectorD().array() < 0.0).count());
  } else {
    out.info.negative = -1;
  }
  last_indefinite_ = out.info.negative != 0;
  // Lowest eigenvalue of the Jacobi-scaled matrix.
  const Eigen::VectorXd d = out.K.diagonal().cwiseAbs();  // S's diagonal
  const Eigen::VectorXd sc = (d.array() > 0.0).select(d.cwiseSqrt().cwiseInverse(), Eigen::VectorXd::Ones(n));
  // The lowest eigenvalue from the factorisation just made, no shifted one (see lowest_from_factor).
  // Up to dense_limit_, for the critical mode, and where that fails to settle: the general route below.
  if (large && out.info.negative >= 0 && !want_mode) {
    const InertiaFactor factor =
        shared ? InertiaFactor::SharedLlt : (cholesky ? InertiaFactor::OwnLlt : InertiaFactor::Ldlt);
    if (const std::optional<double> lowest = lowest_from_factor(sc, factor, out.info.negative)) {
      out.info.min_eigenvalue = *lowest;
      return out;
    }
  }
  const SparseMatrix A = SparseMatrix(sc.asDiagonal() * symmetrised() * sc.asDiagonal());
  const auto gershgorin_shift = [&] {  // below the Gershgorin lower bound of the spectrum
    double g = 0.0;
    for (int j = 0; j < A.outerSize(); ++j) {
      double diag = 0.0, off = 0.0;
      for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
        if (it.row() == j) diag += it.value();
        else off += std::abs(it.value());
      }
      g = std::min(g, diag - off);
    }
    return g - kEigenShiftMargin;
  };
  // Shift-invert converges fast only with the shift near the wanted eigenvalue. Along a path the
  // lowest eigenvalue moves continuously: below zero, the shift is a little below the last one found
  // (kNegativeShiftFactor), which the Gershgorin bound (far below, slow) only backs up.
  double shift = -kEigenShiftMargin;
  if (out.info.negative != 0)
    shift = last_min_ < 0.0 ? kNegativeShiftFactor * last_min_ - kEigenShiftMargin : -kFirstNegativeShift;
  const int want = out.info.negative != 0 || want_mode ? std::max(1, out.info.negative) + 1 : 1;
  for (int attempt = 0; attempt < 2; ++attempt) {
    try {
      EigenPairs ep;
      if (n <= dense_limit_) {
        // Dense: a few milliseconds at this size, and no Lanczos restarts on the clustered lowest
        // eigenvalues of slender structures (bending next to axial stiffness).
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es{Eigen::MatrixXd(A)};
        ep.values = es.eigenvalues().head(std::min(want, n));
        ep.vectors = es.eigenvectors().leftCols(std::min(want, n));
      } else {
        ep = lowest_eigenpairs(A, std::min(want, n), shift);
      }
      const int found_negative = static_cast<int>((ep.values.array() < 0.0).count());
      if (attempt == 0 && out.info.negative > 0 && found_negative == 0) {
        shift = gershgorin_shift();  // the continuation shift missed the negative eigenvalue
        continue;
      }
      if (ep.values.size() > 0) {
        out.info.min_eigenvalue = ep.values[0];
        last_min_ = ep.values[0];
        if (want_mode) {
          Eigen::Index best = 0;
          ep.values.cwiseAbs().minCoeff(&best);
          out.info.mode = out.Z * Eigen::VectorXd(sc.cwiseProduct(ep.vectors.col(best)));
        }
      }
      break;
    } catch (const Error&) {
      out.info.min_eigenvalue = NAN;
      if (attempt == 0) shift = gershgorin_shift();
    }
  }
  return out;
}

// The eigenvalues of A nearest zero are the largest of A^-1: Lanczos on the inverse that the
// inertia's factorisation gives, for the negative count plus one of them. When the negative ones
// found are as many as the inertia counts (Sylvester), they are all of A's negative eigenvalues and
// the least found is the lowest; a stable state needs only the one nearest zero, its lowest.
std::optional<double> StabilityAnalyzer::lowest_from_factor(const Eigen::VectorXd& sc, InertiaFactor factor,
                                                            int negative) {
  const auto& ldlt = inertia_ldlt_.solver();
  if (factor == InertiaFactor::Ldlt && !(ldlt.vectorD().array() != 0.0).all()) return std::nullopt;  // singular
  const Eigen::Index n = sc.size();
  // A = Sc S Sc (Jacobi-scaled), so A^-1 x = Sc^-1 S^-1 Sc^-1 x with S's factorisation.
  const Eigen::VectorXd inv_sc = sc.cwiseInverse();
  work_.resize(n);
  const InverseOp inverse = [&](const double* x, double* y) {
    work_ = inv_sc.cwiseProduct(Eigen::Map<const Eigen::VectorXd>(x, n));
    switch (factor) {
      case InertiaFactor::SharedLlt: z_ = factors_.solve_symmetric(work_); break;
      case InertiaFactor::OwnLlt: z_ = llt_.solver().solve(work_); break;
      case InertiaFactor::Ldlt: z_ = ldlt.solve(work_); break;
    }
    Eigen::Map<Eigen::VectorXd>(y, n) = inv_sc.cwiseProduct(z_);
  };
  const int want = negative == 0 ? 1 : negative + 1;
  try {
    const EigenPairs ep =
        lowest_eigenpairs_of_inverse(n, inverse, want, last_vector_.size() == n ? &last_vector_ : nullptr);
    if (!ep.converged || ep.values.size() == 0) return std::nullopt;
    if ((ep.values.array() < 0.0).count() != negative) return std::nullopt;
    if (negative == 0 && !(ep.values[0] > 0.0)) return std::nullopt;
    last_min_ = ep.values[0];
    last_vector_ = ep.vectors.col(0);
    return last_min_;
  } catch (const Error&) {
    return std::nullopt;
  }
}

CondensedStiffness StabilityAnalyzer::node_stiffness(const Converged& c, const StabilityAnalysis& st, int node) const {
  const PathSystem& P = sys_;
  const auto tw = P.structure().twists(c.state);
  const int n = static_cast<int>(st.K.rows());
  // The node's six rows over the constrained coordinates: T_n Z.
  Eigen::MatrixXd Tn = Eigen::MatrixXd::Zero(6, n);
  for (int k = 0; k < 6 && n > 0; ++k) {
    Eigen::VectorXd r = Eigen::VectorXd::Zero(P.nf());
    for (const auto& [g, v] : P.structure().raw_row(c.state, tw, node, k))
      if (P.free_index(g) >= 0) r[P.free_index(g)] += v;
    Tn.row(k) = (st.Z.transpose() * r).transpose();
  }
  // The coordinates of Z mix translations and rotations: no per-column scale (the range of T_n Z,
  // what the node can move, does not depend on it).
  return node_compliance(st.K, Tn, Eigen::VectorXd::Ones(n), P.length_scale());
}

}  // namespace beamfea
