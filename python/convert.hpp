#pragma once
// Conversions between Python objects and the JSON of beamfea's documents.
//
// In:  dict -> object, list/tuple -> array, str, int, float, bool, None, and NumPy arrays and
//      scalars (through their .tolist()/.item()). Anything else, a non-string key or a NaN is an
//      InputError naming the JSON pointer where it sits.
// Out: the results' JSON, generically (no list of keys): every array of numbers, and every
//      array of equal-shaped such arrays, becomes a float64 ndarray (2-D for a matrix, N-D
//      deeper); null inside such an array is NaN. Other arrays become lists, objects dicts, a
//      non-finite scalar None (as results.json writes it), integers int, strings str.
#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>
#include <string>
#include <vector>

namespace beamfea::python {

nlohmann::json json_from_python(pybind11::handle value, const std::string& pointer);

pybind11::object python_from_json(const nlohmann::ordered_json& value);

// Imports NumPy; called once when the module is imported.
void init_conversions();

// A new C-contiguous float64 numpy.ndarray of `shape`; `data` receives its first element.
// Made by numpy.empty and filled through the buffer protocol, so that nothing here depends on
// NumPy's C ABI (which changed in NumPy 2; pybind11 before 2.12 reads the old layout).
pybind11::object new_float_array(const std::vector<pybind11::ssize_t>& shape, double*& data);

}  // namespace beamfea::python
