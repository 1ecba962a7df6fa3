#include "solvers/path/path_types.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"

namespace beamfea {

void PathOptions::validate(const Model& model) const {
  const int nn = static_cast<int>(model.nodes.size());
  if (control == PathControl::Displacement && (control_node < 0 || control_node >= nn || control_dof < 0 || control_dof > 5))
    throw Error("PathOptions: displacement control needs a node and a dof");
  if (increments < 1) throw Error("PathOptions: increments must be at least 1");
  if (!(arc_length > 0.0)) throw Error("PathOptions: arc_length must be positive");
  if (max_steps < 1) throw Error("PathOptions: max_steps must be at least 1");
  if (desired_iterations < 1) throw Error("PathOptions: desired_iterations must be at least 1");
  if (!(critical_tolerance > 0.0 && critical_tolerance < 1.0)) throw Error("PathOptions: critical_tolerance must be in (0, 1)");
  if (stop_beyond && (stop_node < 0 || stop_node >= nn)) throw Error("PathOptions: stop 'beyond' needs a node");
  for (int n : track)
    if (n < 0 || n >= nn) throw Error("PathOptions: tracked node out of range");
  if (frequency_modes < 0) throw Error("PathOptions: frequency_modes must not be negative");
  newton.validate();
}

const char* to_string(CriticalPointType t) {
  switch (t) {
    case CriticalPointType::LimitPoint: return "limit_point";
    case CriticalPointType::Bifurcation: return "bifurcation";
    case CriticalPointType::Singularity: return "singularity";
  }
  return "?";
}

bool is_completed(PathTermination t) {
  switch (t) {
    case PathTermination::Succeeded:
    case PathTermination::StopLoadFactor:
    case PathTermination::StopBeyond:
    case PathTermination::StopSteps: return true;
    case PathTermination::MaxSteps:
    case PathTermination::NoConvergence:
    case PathTermination::NoForwardSolution:
    case PathTermination::InitialStateFailed:
    case PathTermination::NoAutomaticStep:
    case PathTermination::Singularity:
    case PathTermination::RankChanged: return false;
  }
  return false;
}

void PathResult::finish(PathTermination t, double value, int count, std::string detail) {
  termination = t;
  completed = is_completed(t);
  termination_value = value;
  termination_count = count;
  termination_detail = std::move(detail);
}

std::string PathResult::brief_report() const {
  switch (termination) {
    case PathTermination::Succeeded: return "control target reached";
    case PathTermination::StopLoadFactor: return fmt::format("stop: load factor {:.6g} reached", termination_value);
    case PathTermination::StopBeyond: return fmt::format("stop: {} beyond {:.6g}", termination_detail, termination_value);
    case PathTermination::StopSteps: return fmt::format("stop: {} steps", termination_count);
    case PathTermination::MaxSteps: return fmt::format("max_steps ({}) reached", termination_count);
    case PathTermination::NoConvergence:
      return fmt::format("no convergence after {} step cuts at load factor {:.6g}: {}", termination_count,
                         termination_value, termination_detail);
    case PathTermination::NoForwardSolution:
      return fmt::format("no forward solution after {} step cuts at load factor {:.6g}", termination_count,
                         termination_value);
    case PathTermination::InitialStateFailed:
      return "the initial state with the prescribed values did not converge: " + termination_detail;
    case PathTermination::NoAutomaticStep:
      return "arc_length auto: no scale for the first step (the tangent at the start is singular, or the load moves "
             "nothing)";
    case PathTermination::Singularity:
      return fmt::format("singular pose at load factor {:.6g}: {} (no step converged beyond it)", termination_value,
                         termination_detail);
    case PathTermination::RankChanged:
      return fmt::format("the constraint rank changes after load factor {:.6g}: {}", termination_value, termination_detail);
  }
  return "?";
}

}  // namespace beamfea
