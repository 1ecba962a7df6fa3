#pragma once
// Input shared by the dynamic analyses (frf, transient): the check that the model has masses, a
// DOF named by {"node", "dof"} or {"joint", "coordinate"}, the damping a method accepts, and the
// time functions of transient loads.
#include <nlohmann/json.hpp>
#include <string>

#include "core/dof_map.hpp"
#include "core/model.hpp"
#include "io/json_pointer.hpp"
#include "solvers/transient.hpp"

namespace beamfea {

// InputError at `p` (the analysis) when nothing of the model has mass: no member of a material
// with a density, no point mass.
void check_dynamic_mass(const Model& model, const json_in::Pointer& p, const std::string& type);

// A DOF {"node": n, "dof": d} or {"joint": j, "coordinate": c} (no other key); when `map` is
// given, an InputError where the DOF is held (a support, a prescribed value).
DofRef read_dynamic_dof(const Model& model, const nlohmann::json& v, const json_in::Pointer& p, const std::string& what,
                        const DofMap* map);

// The DOF's name in files and results: "<node>.<dof>" or "<joint>.q<c>".
std::string dof_label(const Model& model, const DofRef& d);

// InputError at /damping when the model's damping is modal and the analysis (at `p`) cannot use it.
void reject_modal_damping(const Model& model, const json_in::Pointer& p, const std::string& why);

// {"type": "step" | "ramp" | "sine" | "table", ...} (solvers/transient.hpp, TimeFunction).
TimeFunction read_time_function(const nlohmann::json& v, const json_in::Pointer& p);

}  // namespace beamfea
