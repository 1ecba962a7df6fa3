#pragma once
// Reading loads (docs/input-format.md, "Loads, load cases, masses"): nodal, joint and member
// loads, gravity, point masses, load cases and combinations. Errors are InputErrors with the JSON
// pointer of the field at fault.
#include <nlohmann/json.hpp>
#include <string>

#include "core/model.hpp"
#include "io/json_pointer.hpp"

namespace beamfea {

// A list of loads ("loads" at the top level or in a load case) at `pointer`.
LoadSet read_load_list(const Model& m, const nlohmann::json& list, const json_in::Pointer& pointer);

// "gravity", "masses", "loads", "load_cases" and "combinations" of the document, into `m`
// (members, nodes and joints must be read already).
void read_loads_and_cases(const nlohmann::json& doc, Model& m);

// A material's "density", given its value in the material object (null when absent: 0; negative:
// InputError at pointer/density).
double read_density(const nlohmann::json* density, const json_in::Pointer& pointer, const std::string& what);

// An analysis's "load_case" (a case or a combination of the model, or "default": the top-level
// loads and gravity), checked: its id, "" when the spec names none (Model::loads_for takes both).
// An id that selects nothing is an InputError at pointer/load_case naming the known ids.
std::string read_load_case(const Model& m, const nlohmann::json& spec, const json_in::Pointer& pointer);

}  // namespace beamfea
