#include "solvers/modal.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>

#include <Eigen/QR>

#include "core/assembly.hpp"
#include "core/errors.hpp"
#include "solvers/generalized_eigen.hpp"
#include "solvers/initial_stress.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/mass_matrix.hpp"
#include "solvers/slepc_eigen.hpp"
#include "solvers/structure.hpp"

namespace beamfea {

namespace {
// sigma = -kShiftRelative * min_i(K_ii/M_ii). min_i(K_ii/M_ii) bounds lambda_1 from above (the
// Rayleigh quotient of a unit vector), and exceeds it by about 30 n^4 for a member of n cubic
// elements; 1e-9 keeps |sigma| below lambda_1 up to ~100 elements per member (fast Lanczos
// convergence) while K - sigma M stays safely factorisable where K is singular (rigid modes).
constexpr double kShiftRelative = 1e-9;
// A zero mode is a rigid-body motion when its distance to the span of the 6 rigid motions is
// below this fraction of its size.
constexpr double kRigidRelative = 1e-6;
}  // namespace

void ModalOptions::validate() const {
  if (modes < 1) throw Error("ModalOptions: modes must be at least 1");
  if (!(zero_tolerance > 0.0)) throw Error("ModalOptions: zero_tolerance must be positive");
}

const char* to_string(ModalStatus s) {
  switch (s) {
    case ModalStatus::Succeeded: return "ok";
    case ModalStatus::NoMass: return "no mass";
    case ModalStatus::MasslessMechanism: return "massless mechanism";
    case ModalStatus::PreloadFailed: return "preload failed";
    case ModalStatus::Failed: return "failed";
  }
  return "?";
}

const char* to_string(ModeKind k) {
  switch (k) {
    case ModeKind::Elastic: return "elastic";
    case ModeKind::RigidBody: return "rigid_body";
    case ModeKind::Mechanism: return "mechanism";
    case ModeKind::Unstable: return "unstable";
  }
  return "?";
}

int modal_dof_count(const Model& model) { return DofMap(model).free_size(); }

namespace {

// The shift: just below zero, relative to the smallest diagonal ratio; nullopt when M has no mass
// on the free DOFs.
std::optional<double> modal_shift(const Eigen::VectorXd& dK, const Eigen::VectorXd& dM) {
  double ratio = std::numeric_limits<double>::infinity();
  double m_max = 0.0;
  for (Eigen::Index i = 0; i < dK.size(); ++i) {
    m_max = std::max(m_max, dM[i]);
    if (dM[i] > 0.0 && dK[i] > 0.0) ratio = std::min(ratio, dK[i] / dM[i]);
  }
  if (!(m_max > 0.0)) return std::nullopt;
  if (!std::isfinite(ratio)) ratio = 1.0;  // no DOF both stiff and massive: any scale
  return -kShiftRelative * ratio;
}

// The rigid-body motions' node DOFs, rotations scaled by the model's length (commensurable), and
// the test whether a raw mode lies in their span.
class RigidMotions {
 public:
  RigidMotions(const Model& model, const Eigen::MatrixXd& R) : model_(model), Ls_(model.length_scale()) {
    Rn_.resize(6 * static_cast<Eigen::Index>(model.nodes.size()), 6);
    for (int d = 0; d < 6; ++d) Rn_.col(d) = node_part(R.col(d));
    qr_ = Rn_.colPivHouseholderQr();
  }
  bool contains(const Eigen::VectorXd& raw) const {
    const Eigen::VectorXd v = node_part(raw);
    const Eigen::VectorXd fit = Rn_ * qr_.solve(v);
    return (v - fit).norm() <= kRigidRelative * v.norm();
  }

 private:
  Eigen::VectorXd node_part(const Eigen::VectorXd& u) const {
    Eigen::VectorXd v(6 * static_cast<Eigen::Index>(model_.nodes.size()));
    for (Eigen::Index i = 0; i < v.size(); ++i) v[i] = (i % 6 < 3) ? u[i] : Ls_ * u[i];
    return v;
  }
  const Model& model_;
  double Ls_;
  Eigen::MatrixXd Rn_;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr_;
};

// Mode kinds, frequencies, raw shapes and participation of the eigen-pairs, into res; the counts
// of zero-frequency and unstable modes.
std::pair<int, int> classify_modes(const Model& model, const DofMap& map, const LinearStructure& structure,
                                   const ModalOptions& options, const SparseMatrix& K, const GeneralizedEigenPairs& eig,
                                   ModalResult& res) {
  const Eigen::MatrixXd R = rigid_body_motions(model, map);
  Eigen::MatrixXd MR(map.raw_size(), 6);
  for (int d = 0; d < 6; ++d) MR.col(d) = raw_mass_product(structure, map, options.mass, R.col(d));
  for (int d = 0; d < 6; ++d) res.total_mass[d] = R.col(d).dot(MR.col(d));
  const RigidMotions rigid(model, R);
  const Eigen::VectorXd dK = K.diagonal();
  const Eigen::Index count = eig.values.size();
  res.eigenvalues = eig.values;
  res.frequencies.resize(count);
  res.participation.resize(count, 6);
  res.effective_mass.resize(count, 6);
  int zero = 0, unstable = 0;
  for (Eigen::Index k = 0; k < count; ++k) {
    const Eigen::VectorXd phi = eig.vectors.col(k);
    const double quad = phi.dot(K * phi);
    double scaled = 0.0;
    for (Eigen::Index i = 0; i < phi.size(); ++i) scaled += std::abs(dK[i]) * phi[i] * phi[i];
    const double rayleigh = scaled > 0.0 ? quad / scaled : 0.0;
    const Eigen::VectorXd raw = map.T_free() * phi;
    ModeKind kind = ModeKind::Elastic;
    double lambda = eig.values[k];
    if (std::abs(rayleigh) < options.zero_tolerance) {
      ++zero;
      lambda = 0.0;
      kind = rigid.contains(raw) ? ModeKind::RigidBody : ModeKind::Mechanism;
    } else if (lambda < 0.0) {
      ++unstable;
      kind = ModeKind::Unstable;
    }
    res.eigenvalues[k] = lambda;
    res.frequencies[k] = std::copysign(std::sqrt(std::abs(lambda)), lambda) / (2.0 * std::numbers::pi);
    res.kinds.push_back(kind);
    res.modes.push_back(raw);
    for (int d = 0; d < 6; ++d) {
      res.participation(k, d) = raw.dot(MR.col(d));
      res.effective_mass(k, d) = res.participation(k, d) * res.participation(k, d);
    }
  }
  return {zero, unstable};
}

}  // namespace

ModalResult solve_modal(const Model& model, const ModalOptions& options) {
  return solve_modal(model, model.default_loads(), options);
}

ModalResult solve_modal(const Model& model, const LoadSet& loads, const ModalOptions& options) {
  options.validate();
  ModalResult res;
  const DofMap map(model);
  const LinearStructure structure(model);
  res.free_dofs = map.free_size();
  const int n = map.free_size();
  if (n == 0) {
    res.status = ModalStatus::NoMass;
    res.message = "modal: no free DOFs";
    return res;
  }

  SystemAssembler ka(map), ma(map);
  structure.assemble_stiffness(map, ka);
  ma.begin();
  assemble_mass(structure, map, options.mass, ma);
  ma.end();
  SparseMatrix K = ka.K_ff();
  const SparseMatrix& M = ma.K_ff();
  if (options.preload) {
    std::string why;
    std::optional<SparseMatrix> Kt = loaded_tangent(model, map, structure, K, loads, options.about_state, why);
    if (!Kt) {
      res.status = ModalStatus::PreloadFailed;
      res.message = "modal: " + why;
      return res;
    }
    K = std::move(*Kt);
  }

  const std::optional<double> sigma = modal_shift(K.diagonal(), M.diagonal());
  if (!sigma) {
    res.status = ModalStatus::NoMass;
    res.message = "modal: the model has no mass (give the materials a density or add point masses)";
    return res;
  }
  GeneralizedEigenPairs eig;
  if (eigen_solver_iterative(model.solver, n)) {
    // SLEPc: Krylov-Schur, shift-and-invert about the same sigma (solvers/slepc_eigen.hpp).
    SlepcEigenOptions so = slepc_options(model.solver, options.modes);
    so.target = *sigma;
    so.indefinite = options.preload;  // K + K_g - sigma M is indefinite beyond buckling
    const Eigen::MatrixXd rigid = free_rigid_body_motions(model, map);
    SlepcEigenPairs sp = slepc_vibration_pairs(K, M, so, &rigid);
    res.solver = EigenSolverReport{true, sp.iterations, sp.linear_iterations, 0.0};
    if (!sp.converged) {
      res.status = ModalStatus::Failed;
      res.message = sp.message;
      return res;
    }
    eig.values = std::move(sp.values);
    eig.vectors = std::move(sp.vectors);
    eig.converged = true;
  } else {
    try {
      eig = nearest_generalized_eigenpairs(K, M, options.modes, *sigma);
    } catch (const Error& e) {
      res.status = ModalStatus::MasslessMechanism;
      res.message = std::string("modal: ") + e.what();
      return res;
    }
    if (!eig.converged) {
      res.status = ModalStatus::Failed;
      res.message = "modal: " + eig.message;
      return res;
    }
  }
  res.solver.residual = relative_eigen_residual(K, M, eig.values, eig.vectors);

  const auto [zero, unstable] = classify_modes(model, map, structure, options, K, eig, res);
  const Eigen::Index count = eig.values.size();
  res.status = ModalStatus::Succeeded;
  res.message = fmt::format("modal: {} free DOFs, {} modes{}, lowest {:.6g} Hz{}{}", n, count,
                            !options.preload ? "" : options.about_state.about == Equilibrium::SecondOrder ? " about the second-order equilibrium" : " about the loaded state",
                            count > 0 ? res.frequencies[0] : 0.0,
                            zero > 0 ? fmt::format(", {} zero-frequency", zero) : "",
                            unstable > 0 ? fmt::format(", {} unstable (beyond buckling)", unstable) : "");
  return res;
}

}  // namespace beamfea
