#pragma once
// beamfea's C++ errors as the Python exceptions of beamfea/_errors.py:
//   beamfea::InputError -> beamfea.InputError(ValueError), .pointer (JSON pointer) and .entity
//   beamfea::ModelError -> beamfea.ModelError, .entity
//   beamfea::Error      -> beamfea.Error (the base of both)
// The entity of an InputError is named from the document when one is at hand: the pointer
// "/elements/3/section" names "element 'e3'" (the id of the fourth element).
#include <nlohmann/json.hpp>
#include <string>

#include "core/errors.hpp"

namespace beamfea::python {

// The entity at `pointer` in `document` ("node 'A'", "analysis 'K'"); empty when none.
std::string entity_at(const nlohmann::json& document, const std::string& pointer);

// Each sets the Python exception and throws pybind11::error_already_set. Need the GIL.
[[noreturn]] void raise_input_error(const InputError& e, const nlohmann::json* document);
[[noreturn]] void raise_model_error(const ModelError& e);
[[noreturn]] void raise_error(const Error& e);

// Registers a translator for errors that escape without a document at hand.
void register_error_translator();

}  // namespace beamfea::python
