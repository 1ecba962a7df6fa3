#include "solvers/frequency_response.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <Eigen/UmfPackSupport>
#include <cmath>
#include <memory>
#include <numbers>

#include "core/errors.hpp"
#include "solvers/linear_solver.hpp"
#include "solvers/modal.hpp"

namespace beamfea {

namespace {

using Complex = std::complex<double>;
using ComplexSparse = Eigen::SparseMatrix<Complex, Eigen::ColMajor, int>;

// Off-diagonal terms of the modal damping matrix below this fraction of its largest entry are
// round-off (Phi^T C Phi of a proportional C): the modes stay uncoupled.
constexpr double kUncoupledRelative = 1e-12;

FrfResult frf_failed(FrfStatus status, std::string message) {
  FrfResult r;
  r.status = status;
  r.message = "frf: " + std::move(message);
  return r;
}

FrfStatus from_system(DynamicSystemStatus s) {
  return s == DynamicSystemStatus::PreloadFailed ? FrfStatus::PreloadFailed
         : s == DynamicSystemStatus::NoMass      ? FrfStatus::NoMass
                                                 : FrfStatus::Failed;
}

// The free-DOF forces of unit inputs, as columns.
Eigen::MatrixXd input_forces(const DofMap& map, const std::vector<int>& raw_inputs) {
  Eigen::MatrixXd F(map.free_size(), static_cast<Eigen::Index>(raw_inputs.size()));
  for (std::size_t i = 0; i < raw_inputs.size(); ++i) F.col(static_cast<Eigen::Index>(i)) = unit_free_force(map, raw_inputs[i]);
  return F;
}

// The rows of T_f of the outputs: raw u_o = O u_free.
Eigen::SparseMatrix<double, Eigen::RowMajor> output_rows(const DofMap& map, const std::vector<int>& raw_outputs) {
  Eigen::SparseMatrix<double, Eigen::RowMajor> O(static_cast<Eigen::Index>(raw_outputs.size()), map.free_size());
  for (std::size_t o = 0; o < raw_outputs.size(); ++o) O.row(static_cast<Eigen::Index>(o)) = map.T_free().row(raw_outputs[o]);
  return O;
}

void solve_direct(const DynamicSystem& sys, const Eigen::MatrixXd& F, const Eigen::SparseMatrix<double, Eigen::RowMajor>& O,
            const Eigen::VectorXd& hz, FrfResult& r) {
  const ComplexSparse K = sys.K.cast<Complex>(), M = sys.M.cast<Complex>(), C = sys.C.cast<Complex>();
  const Eigen::MatrixXcd Fc = F.cast<Complex>();
  const Eigen::SparseMatrix<Complex, Eigen::RowMajor> Oc = O.cast<Complex>();
  // The pattern of K - w^2 M + i w C is the union of the three (Eigen keeps explicit zeros of a
  // sum), the same at every frequency: one symbolic analysis.
  ComplexSparse A = K - M + Complex(0.0, 1.0) * C;
  Eigen::UmfPackLU<ComplexSparse> lu;
  lu.analyzePattern(A);
  Eigen::MatrixXcd X;
  for (Eigen::Index k = 0; k < hz.size(); ++k) {
    const double w = 2.0 * std::numbers::pi * hz[k];
    A = K - (w * w) * M + Complex(0.0, w) * C;
    lu.factorize(A);
    ++r.factorizations;
    if (lu.info() != Eigen::Success) {
      r.status = FrfStatus::Singular;
      r.message = fmt::format("frf: the dynamic stiffness K - w^2 M + i w C is singular at {:.9g} Hz (an undamped resonance: add damping or move the frequency)", hz[k]);
      return;
    }
    X = lu.solve(Fc);
    const Eigen::MatrixXcd Y = Oc * X;  // outputs x inputs
    for (std::size_t i = 0; i < r.receptance.size(); ++i) r.receptance[i].row(k) = Y.col(static_cast<Eigen::Index>(i)).transpose();
  }
  r.status = FrfStatus::Succeeded;
}

void solve_by_modes(const Model& model, const DofMap& map, const DynamicSystem& sys, const Eigen::MatrixXd& F,
           const Eigen::SparseMatrix<double, Eigen::RowMajor>& O, const Eigen::VectorXd& hz, const LoadSet& preload,
           const FrfOptions& options, FrfResult& r) {
  ModalOptions mo;
  mo.modes = options.modes;
  mo.mass = options.system.mass;
  mo.preload = options.system.preload;
  mo.about_state = options.system.about_state;
  const ModalResult m = solve_modal(model, preload, mo);
  if (m.status != ModalStatus::Succeeded) {
    r.status = m.status == ModalStatus::PreloadFailed ? FrfStatus::PreloadFailed : FrfStatus::Failed;
    r.message = "frf: " + m.message;
    return;
  }
  const Eigen::Index nm = m.eigenvalues.size();
  r.mode_frequencies = m.frequencies;
  // Mass-normalised modes over the free DOFs: a free DOF is an independent raw DOF, whose T_f row
  // is the unit row, so its value is the raw mode's there.
  Eigen::MatrixXd Phi(map.free_size(), nm);
  for (Eigen::Index q = 0; q < map.free_size(); ++q) {
    const int raw = map.raw_index(map.free_dofs()[static_cast<std::size_t>(q)]);
    for (Eigen::Index k = 0; k < nm; ++k) Phi(q, k) = m.modes[static_cast<std::size_t>(k)][raw];
  }
  const Eigen::VectorXd& lambda = m.eigenvalues;
  // The modal damping matrix: the proportional part on the diagonal, exactly; the joints' part
  // projected.
  Eigen::MatrixXd Cq = Phi.transpose() * (joint_damping(model, map) * Phi);
  const Damping& d = model.damping;
  for (Eigen::Index k = 0; k < nm; ++k) {
    if (d.kind == Damping::Kind::Rayleigh) Cq(k, k) += d.alpha + d.beta * lambda[k];
    if (d.kind == Damping::Kind::Modal)
      Cq(k, k) += 2.0 * d.modal_ratio(static_cast<std::size_t>(k)) * std::sqrt(std::max(lambda[k], 0.0));
  }
  const double c_max = Cq.cwiseAbs().maxCoeff();
  const bool coupled = (Cq - Eigen::MatrixXd(Cq.diagonal().asDiagonal())).cwiseAbs().maxCoeff() > kUncoupledRelative * c_max;
  const Eigen::MatrixXcd Pf = (Phi.transpose() * F).cast<Complex>();  // modes x inputs
  const Eigen::MatrixXcd Po = (O * Phi).cast<Complex>();              // outputs x modes
  Eigen::MatrixXd residual = Eigen::MatrixXd::Zero(O.rows(), F.cols());
  if (options.residual_flexibility) {
    std::unique_ptr<LinearSolver> solver = make_linear_solver();
    if (solver->compute(sys.K) != FactorStatus::Succeeded) {
      r.status = FrfStatus::Failed;
      r.message = "frf: residual_flexibility needs a non-singular stiffness (the structure has rigid-body or mechanism modes)";
      return;
    }
    Eigen::MatrixXd static_part = O * solver->solve(F);
    for (Eigen::Index k = 0; k < nm; ++k)
      if (lambda[k] > 0.0) static_part -= (O * Phi.col(k)) * (Phi.col(k).transpose() * F) / lambda[k];
    residual = static_part;
  }
  Eigen::MatrixXcd Q(nm, F.cols());
  for (Eigen::Index k = 0; k < hz.size(); ++k) {
    const double w = 2.0 * std::numbers::pi * hz[k];
    if (coupled) {
      Eigen::MatrixXcd D = Complex(0.0, w) * Cq.cast<Complex>();
      for (Eigen::Index j = 0; j < nm; ++j) D(j, j) += lambda[j] - w * w;
      Q = D.partialPivLu().solve(Pf);
    } else {
      for (Eigen::Index j = 0; j < nm; ++j) Q.row(j) = Pf.row(j) / Complex(lambda[j] - w * w, w * Cq(j, j));
    }
    const Eigen::MatrixXcd Y = Po * Q + residual.cast<Complex>();
    if (!Y.allFinite()) {
      r.status = FrfStatus::Singular;
      r.message = fmt::format("frf: an undamped mode resonates at {:.9g} Hz (add damping or move the frequency)", hz[k]);
      return;
    }
    for (std::size_t i = 0; i < r.receptance.size(); ++i) r.receptance[i].row(k) = Y.col(static_cast<Eigen::Index>(i)).transpose();
  }
  r.status = FrfStatus::Succeeded;
}

}  // namespace

void FrfOptions::validate() const {
  if (modes < 1) throw Error("FrfOptions: modes must be at least 1");
}

const char* to_string(FrfStatus s) {
  switch (s) {
    case FrfStatus::Succeeded: return "ok";
    case FrfStatus::NoMass: return "no mass";
    case FrfStatus::PreloadFailed: return "preload failed";
    case FrfStatus::ModalDampingNeedsModal: return "modal damping needs the modal method";
    case FrfStatus::Singular: return "singular";
    case FrfStatus::Failed: return "failed";
  }
  return "?";
}

FrfResult frequency_response(const Model& model, const std::vector<DofRef>& inputs, const std::vector<DofRef>& outputs,
                             const Eigen::VectorXd& hz, const LoadSet& preload, const FrfOptions& options) {
  options.validate();
  const DofMap map(model);
  const DynamicSystem sys = dynamic_system(model, map, preload, options.system);
  if (sys.status != DynamicSystemStatus::Succeeded) return frf_failed(from_system(sys.status), sys.message);
  if (options.method == FrfMethod::Direct && model.damping.kind == Damping::Kind::Modal)
    return frf_failed(FrfStatus::ModalDampingNeedsModal, "modal damping (a ratio per mode) needs \"method\": \"modal\"");
  std::vector<int> raw_in, raw_out;
  for (const DofRef& d : inputs) raw_in.push_back(map.raw_index(d));
  for (const DofRef& d : outputs) raw_out.push_back(map.raw_index(d));
  const Eigen::MatrixXd F = input_forces(map, raw_in);
  const auto O = output_rows(map, raw_out);
  FrfResult r;
  r.receptance.assign(inputs.size(), Eigen::MatrixXcd::Zero(hz.size(), static_cast<Eigen::Index>(outputs.size())));
  if (options.method == FrfMethod::Direct)
    solve_direct(sys, F, O, hz, r);
  else
    solve_by_modes(model, map, sys, F, O, hz, preload, options, r);
  if (r.status != FrfStatus::Succeeded) return r;
  r.message = options.method == FrfMethod::Direct
                  ? fmt::format("frf: direct, {} free DOFs, {} frequencies, {} factorisations", map.free_size(), hz.size(), r.factorizations)
                  : fmt::format("frf: modal, {} modes ({:.6g} to {:.6g} Hz){}, {} frequencies", r.mode_frequencies.size(),
                                r.mode_frequencies.size() ? r.mode_frequencies[0] : 0.0,
                                r.mode_frequencies.size() ? r.mode_frequencies[r.mode_frequencies.size() - 1] : 0.0,
                                options.residual_flexibility ? " with residual flexibility" : "", hz.size());
  return r;
}

}  // namespace beamfea
