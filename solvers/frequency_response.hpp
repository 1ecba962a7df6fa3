#pragma once
// Frequency response: the complex receptance H(omega) = x / f of a linear structure under a
// harmonic generalised force f e^{i omega t} at one input DOF, at output DOFs,
//     (K - omega^2 M + i omega C) x = f,   x(t) = H f e^{i omega t}
// (a displacement per unit force, or a rotation per unit moment): the phase lags, -90 degrees at an
// undamped resonance. K, M, C: solvers/dynamic_system.hpp (about a loaded state: K + K_g).
//
// Methods
//   Direct  the complex system above at each frequency, by UMFPACK's complex LU (Eigen's
//           UmfPackLU<SparseMatrix<std::complex<double>>>): the symbolic analysis of the pattern
//           of K, M and C once, a numeric factorisation per frequency. Modal damping is no matrix:
//           rejected (FrfStatus::ModalDampingNeedsModal).
//   Modal   superposition of the lowest `modes` mass-normalised modes (solvers/modal.hpp),
//           x = Phi q with (Lambda - omega^2 I + i omega C_q) q = Phi^T f (Ewins, Modal Testing,
//           2nd ed. 2000, chapter 2: the receptance as a sum over modes). C_q = diag(2 zeta_r omega_r) for modal
//           damping; diag(alpha + beta omega_r^2) for Rayleigh (zeta_r = alpha / (2 omega_r) +
//           beta omega_r / 2); joint damping adds Phi^T C_joint Phi, non-proportional, and the
//           k x k system is then solved as a whole at each frequency. With
//           `residual_flexibility`, the static contribution of the modes left out is added,
//           K^-1 f - sum_r phi_r phi_r^T f / omega_r^2 (the residual flexibility of Craig & Kurdila,
//           Fundamentals of Structural Dynamics, 2nd ed. 2006, chapter 14): K must then be non-singular.
#include <complex>
#include <string>
#include <vector>

#include "core/model.hpp"
#include "solvers/dynamic_system.hpp"

namespace beamfea {

enum class FrfMethod { Direct, Modal };

struct FrfOptions {
  FrfMethod method = FrfMethod::Direct;
  int modes = 20;                     // Modal: the number of modes superposed
  bool residual_flexibility = false;  // Modal: add the static part of the modes left out
  DynamicSystemOptions system;        // mass kind, preload
  void validate() const;
};

enum class FrfStatus {
  Succeeded,
  NoMass,
  PreloadFailed,
  ModalDampingNeedsModal,  // direct method with modal damping
  Singular,                // the dynamic stiffness is singular at a frequency (an undamped resonance)
  Failed,                  // modal: the eigen-solver failed; residual flexibility: K singular
};
const char* to_string(FrfStatus s);

struct FrfResult {
  FrfStatus status = FrfStatus::Failed;
  std::string message;
  // receptance[i](k, o): input i, frequency k, output o.
  std::vector<Eigen::MatrixXcd> receptance;
  Eigen::VectorXd mode_frequencies;  // Modal: the frequencies (Hz) of the modes superposed
  int factorizations = 0;            // Direct: the numeric factorisations made
  std::string brief_report() const { return message; }
};

// The receptances at the raw DOFs `outputs` for unit forces at each raw DOF of `inputs`, at the
// frequencies `hz` (Hz, positive); `preload`: the loads of a loaded state (options.system.preload).
FrfResult frequency_response(const Model& model, const std::vector<DofRef>& inputs, const std::vector<DofRef>& outputs,
                             const Eigen::VectorXd& hz, const LoadSet& preload, const FrfOptions& options);

}  // namespace beamfea
