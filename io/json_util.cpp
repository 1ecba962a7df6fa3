#include "io/json_util.hpp"

#include <cmath>

namespace beamfea::json_in {

std::string child(const std::string& pointer, const std::string& key) {
  std::string k;
  for (char c : key) {
    if (c == '~') k += "~0";
    else if (c == '/') k += "~1";
    else k += c;
  }
  return pointer + "/" + k;
}

std::string child(const std::string& pointer, std::size_t index) { return pointer + "/" + std::to_string(index); }

const json& require(const json& obj, const std::string& pointer, const std::string& key, const std::string& what) {
  if (!obj.is_object()) throw InputError(pointer, what + ": expected an object");
  auto it = obj.find(key);
  if (it == obj.end()) throw InputError(child(pointer, key), what + ": missing field '" + key + "'");
  return *it;
}

double number(const json& v, const std::string& pointer, const std::string& what) {
  if (!v.is_number()) throw InputError(pointer, what + ": expected a number");
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw InputError(pointer, what + ": must be finite");
  return x;
}

double positive(const json& v, const std::string& pointer, const std::string& what) {
  const double x = number(v, pointer, what);
  if (!(x > 0.0)) throw InputError(pointer, what + ": must be positive (got " + v.dump() + ")");
  return x;
}

int integer(const json& v, const std::string& pointer, const std::string& what) {
  if (!v.is_number_integer()) throw InputError(pointer, what + ": expected an integer");
  return v.get<int>();
}

int integer_at_least(const json& v, const std::string& pointer, const std::string& what, int min) {
  const int x = integer(v, pointer, what);
  if (x < min) throw InputError(pointer, what + " must be at least " + std::to_string(min) + " (got " + std::to_string(x) + ")");
  return x;
}

bool boolean(const json& v, const std::string& pointer, const std::string& what) {
  if (!v.is_boolean()) throw InputError(pointer, what + ": expected true or false");
  return v.get<bool>();
}

std::string string(const json& v, const std::string& pointer, const std::string& what) {
  if (!v.is_string()) throw InputError(pointer, what + ": expected a string");
  return v.get<std::string>();
}

std::string id(const json& v, const std::string& pointer, const std::string& what) {
  if (v.is_string()) {
    auto s = v.get<std::string>();
    if (s.empty()) throw InputError(pointer, what + ": id must not be empty");
    return s;
  }
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  throw InputError(pointer, what + ": an id must be a string or an integer");
}

Vec3 vec3(const json& v, const std::string& pointer, const std::string& what) {
  if (!v.is_array() || v.size() != 3) throw InputError(pointer, what + ": expected an array of 3 numbers");
  Vec3 x;
  for (int i = 0; i < 3; ++i) x[i] = number(v[i], child(pointer, i), what);
  return x;
}

std::vector<double> numbers(const json& v, const std::string& pointer, const std::string& what) {
  if (!v.is_array()) throw InputError(pointer, what + ": expected an array of numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i) out.push_back(number(v[i], child(pointer, i), what));
  return out;
}

const json& array(const json& v, const std::string& pointer, const std::string& what) {
  if (!v.is_array()) throw InputError(pointer, what + ": expected an array");
  return v;
}

const json& object(const json& v, const std::string& pointer, const std::string& what) {
  if (!v.is_object()) throw InputError(pointer, what + ": expected an object");
  return v;
}

}  // namespace beamfea::json_in
