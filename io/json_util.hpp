#pragma once
// Typed access to JSON input with errors that carry the JSON pointer of the field at fault.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "core/rotation.hpp"

namespace beamfea::json_in {

using json = nlohmann::json;

// Appends a key or index to a pointer, escaping per RFC 6901.
std::string child(const std::string& pointer, const std::string& key);
std::string child(const std::string& pointer, std::size_t index);

const json& require(const json& obj, const std::string& pointer, const std::string& key, const std::string& what);
double number(const json& v, const std::string& pointer, const std::string& what);
double positive(const json& v, const std::string& pointer, const std::string& what);
int integer(const json& v, const std::string& pointer, const std::string& what);
// An integer no smaller than `min`.
int integer_at_least(const json& v, const std::string& pointer, const std::string& what, int min);
bool boolean(const json& v, const std::string& pointer, const std::string& what);
std::string string(const json& v, const std::string& pointer, const std::string& what);
// An id: a string or an integer, returned as a string.
std::string id(const json& v, const std::string& pointer, const std::string& what);
Vec3 vec3(const json& v, const std::string& pointer, const std::string& what);
std::vector<double> numbers(const json& v, const std::string& pointer, const std::string& what);
const json& array(const json& v, const std::string& pointer, const std::string& what);
const json& object(const json& v, const std::string& pointer, const std::string& what);

}  // namespace beamfea::json_in
