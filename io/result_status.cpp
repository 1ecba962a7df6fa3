#include "io/result_status.hpp"

namespace beamfea {

namespace {
constexpr const char* kOk = "ok";
}  // namespace

const char* result_status(SolveStatus s) {
  switch (s) {
    case SolveStatus::Succeeded: return kOk;
    case SolveStatus::Mechanism: return "mechanism";
    case SolveStatus::Failed: return "failed";
    case SolveStatus::NotConverged: return "not converged";
  }
  return "failed";
}

const char* result_status(BucklingStatus s) {
  switch (s) {
    case BucklingStatus::Succeeded: return kOk;
    case BucklingStatus::NoCompression: return "no buckling";
    case BucklingStatus::Mechanism: return "mechanism";
    case BucklingStatus::NotConverged: return "not converged";
    case BucklingStatus::Failed: return "failed";
  }
  return "failed";
}

const char* result_status(ModalStatus s) {
  switch (s) {
    case ModalStatus::Succeeded: return kOk;
    case ModalStatus::NoMass: return "no mass";
    case ModalStatus::MasslessMechanism: return "massless mechanism";
    case ModalStatus::PreloadFailed: return "preload failed";
    case ModalStatus::Failed: return "failed";
  }
  return "failed";
}

const char* stiffness_status(bool condensed) { return condensed ? kOk : "mechanism"; }

const char* path_status(bool completed) { return completed ? kOk : "failed"; }

const char* allocation_status(int valid_schemes) { return valid_schemes > 0 ? kOk : "no_valid_scheme"; }

std::string scheme_rank_status(const SchemeRank& rank, const char* component) {
  switch (rank.status) {
    case SchemeRankStatus::Ranked: return kOk;
    case SchemeRankStatus::InvalidAtPose: return rank.reason + " at " + rank.failed_pose;
    case SchemeRankStatus::NoValueAtPose: return std::string("no ") + component + " at " + rank.failed_pose;
  }
  return kOk;
}

}  // namespace beamfea
