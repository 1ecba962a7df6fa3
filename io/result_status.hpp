#pragma once
// results.json's "status" strings: a contract (docs/results.md and docs/analyses/), made here from
// the outcome enums of the solvers, in one place. The program's own vocabulary for the exit code
// and the one-line reports is AnalysisTermination (io/analysis.hpp).
#include <string>

#include "solvers/buckling.hpp"
#include "solvers/linear_static.hpp"
#include "solvers/modal.hpp"
#include "solvers/scheme_ranking.hpp"

namespace beamfea {

// Any analysis that threw or gave a non-finite result (io/run.cpp).
inline constexpr const char* kFailedStatus = "failed";
// linear_static: "ok", "mechanism", "failed".
const char* result_status(SolveStatus s);
// buckling: "ok", "no buckling", "mechanism", "not converged", "failed".
const char* result_status(BucklingStatus s);
// modal: "ok", "no mass", "massless mechanism", "preload failed", "failed".
const char* result_status(ModalStatus s);
// stiffness: "ok", or "mechanism" where the condensation found one.
const char* stiffness_status(bool condensed);
// path: "ok" when the path was followed to its end, otherwise "failed".
const char* path_status(bool completed);
// actuator_allocation: "ok", or "no_valid_scheme" when no scheme is valid at every pose.
const char* allocation_status(int valid_schemes);
// A scheme of an actuator allocation (its "invalid" and its ranking "status"): "ok",
// "<scheme status> at <pose>" or "no <component> at <pose>".
std::string scheme_rank_status(const SchemeRank& rank, const char* component);

}  // namespace beamfea
