#include "io/json_util.hpp"

#include "core/model.hpp"

#include <algorithm>
#include <charconv>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace beamfea::json_in {

namespace {

// `what` followed by `tail`: an error message.
std::string msg(const What& what, std::string_view tail) {
  std::string m = what.str();
  m += tail;
  return m;
}

// Levenshtein distance (insertions, deletions, substitutions), O(|a| |b|).
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

// Keys longer than this are not compared (a suggestion for them would mean nothing anyway).
constexpr std::size_t kMaxSuggestedKeyLength = 64;

// nearest_key over any range of names.
template <class Names>
std::string nearest_name(std::string_view key, const Names& known) {
  if (key.size() > kMaxSuggestedKeyLength) return "";
  std::string best;
  std::size_t best_d = std::numeric_limits<std::size_t>::max();
  for (std::string_view k : known) {
    const std::size_t d = edit_distance(key, k);
    if (d < best_d) {
      best_d = d;
      best = std::string(k);
    }
  }
  // A suggestion only when at most about a third of the key differs (or a case change).
  const std::size_t limit = std::max<std::size_t>(2, key.size() / 3);
  if (best_d <= limit) return best;
  for (std::string_view k : known) {
    if (k.size() != key.size()) continue;
    bool same = true;
    for (std::size_t i = 0; i < k.size() && same; ++i) same = std::tolower(static_cast<unsigned char>(k[i])) ==
                                                             std::tolower(static_cast<unsigned char>(key[i]));
    if (same) return std::string(k);
  }
  return "";
}

}  // namespace

std::string nearest_key(std::string_view key, std::initializer_list<std::string_view> known) { return nearest_name(key, known); }

std::string nearest_key(std::string_view key, const std::vector<std::string>& known) { return nearest_name(key, known); }

namespace {

// Keys the user may add anywhere: notes.
bool is_free_key(const std::string& k) {
  return (!k.empty() && k[0] == '_') || (k.size() == 7 && k[0] == 'c' && k == "comment");
}

// Lengths are compared before the characters, and the characters by a loop rather than a call of
// memcmp: every key of every object of a model passes here, most known keys differ from it in
// length, and the keys are a few characters (a small model's read spent 5 % of its time in these
// comparisons when each was a memcmp).
bool is_known_key(std::string_view k, std::initializer_list<std::string_view> known) {
  for (std::string_view n : known) {
    if (n.size() != k.size()) continue;
    std::size_t i = 0;
    while (i < k.size() && n[i] == k[i]) ++i;
    if (i == k.size()) return true;
  }
  return false;
}

[[noreturn]] void unknown_key(const std::string& k, const Pointer& pointer, std::initializer_list<std::string_view> known) {
  std::string message = "unknown key '" + k + "'";
  const std::string near = nearest_key(k, known);
  if (!near.empty()) message += " (did you mean '" + near + "'?)";
  else {
    message += " (known keys:";
    for (std::string_view n : known) message.append(" ").append(n);
    message += "; keys starting with '_' and \"comment\" are free)";
  }
  throw InputError(child(pointer, k), message);
}

// The key policy over an object's keys: on_known(key, value) for each known key, in the object's
// order; the first unknown key throws. Nothing when `obj` is not an object. The object's map is
// walked itself: items() makes a proxy (with a string for array indices) per key.
template <class F>
void walk_keys(const json& obj, const Pointer& pointer, std::initializer_list<std::string_view> known, F&& on_known) {
  if (!obj.is_object()) return;
  for (const auto& [k, v] : obj.get_ref<const json::object_t&>()) {
    if (is_free_key(k)) continue;
    if (!is_known_key(k, known)) unknown_key(k, pointer, known);
    on_known(k, v);
  }
}

}  // namespace

void expect_keys(const json& obj, const Pointer& pointer, std::initializer_list<std::string_view> known) {
  walk_keys(obj, pointer, known, [](const std::string&, const json&) {});
}

Fields::Fields(const json& obj, const Pointer& pointer, std::initializer_list<std::string_view> known)
    : obj_(obj), pointer_(pointer) {
  if (known.size() > kMaxKnown) throw std::logic_error("json_in::Fields: more known keys than kMaxKnown");
  walk_keys(obj, pointer, known, [&](const std::string& k, const json& v) {
    keys_[n_] = k;  // the keys are distinct known keys: at most known.size() of them
    values_[n_++] = &v;
  });
}

void Fields::missing(std::string_view key, const What& what) const {
  json_in::require(obj_, pointer_, key, what);  // throws: not an object, or no `key`
  throw std::logic_error("json_in::Fields: '" + std::string(key) + "' read but not among the known keys");
}

const json& require(const json& obj, const Pointer& pointer, std::string_view key, const What& what) {
  if (!obj.is_object()) throw InputError(pointer, msg(what, ": expected an object"));
  auto it = obj.find(key);
  if (it == obj.end()) throw InputError(child(pointer, key), msg(what, ": missing field '").append(key) + "'");
  return *it;
}

double number(const json& v, const Pointer& pointer, const What& what) {
  if (!v.is_number()) throw InputError(pointer, msg(what, ": expected a number"));
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw InputError(pointer, msg(what, ": must be finite"));
  if (std::abs(x) > kMaxMagnitude)
    throw InputError(pointer, msg(what, ": ") + v.dump() + " is beyond the largest magnitude accepted, 1e100 (products of "
                                         "such values overflow double precision in the analysis)");
  return x;
}

double positive(const json& v, const Pointer& pointer, const What& what) {
  const double x = number(v, pointer, what);
  if (!(x > 0.0)) throw InputError(pointer, msg(what, ": must be positive (got ") + v.dump() + ")");
  return x;
}

int integer(const json& v, const Pointer& pointer, const What& what) {
  if (!v.is_number_integer()) throw InputError(pointer, msg(what, ": expected an integer"));
  constexpr auto lo = std::numeric_limits<int>::min();
  constexpr auto hi = std::numeric_limits<int>::max();
  if (v.is_number_unsigned() ? v.get<std::uint64_t>() > static_cast<std::uint64_t>(hi)
                             : (v.get<std::int64_t>() < lo || v.get<std::int64_t>() > hi))
    throw InputError(pointer, msg(what, ": ") + v.dump() + " is out of range for an integer here");
  return v.get<int>();
}

int integer_at_least(const json& v, const Pointer& pointer, const What& what, int min) {
  const int x = integer(v, pointer, what);
  if (x < min) throw InputError(pointer, msg(what, " must be at least ") + std::to_string(min) + " (got " + std::to_string(x) + ")");
  return x;
}

int integer_in(const json& v, const Pointer& pointer, const What& what, int min, int max) {
  const int x = integer(v, pointer, what);
  if (x < min || x > max)
    throw InputError(pointer, msg(what, " must be between ") + std::to_string(min) + " and " + std::to_string(max) +
                                  " (got " + std::to_string(x) + ")");
  return x;
}

bool boolean(const json& v, const Pointer& pointer, const What& what) {
  if (!v.is_boolean()) throw InputError(pointer, msg(what, ": expected true or false"));
  return v.get<bool>();
}

std::string string(const json& v, const Pointer& pointer, const What& what) {
  if (!v.is_string()) throw InputError(pointer, msg(what, ": expected a string"));
  return v.get<std::string>();
}

std::string id(const json& v, const Pointer& pointer, const What& what) {
  std::string s;
  id_into(s, v, pointer, what);
  return s;
}

void id_into(std::string& out, const json& v, const Pointer& pointer, const What& what) {
  if (v.is_string()) {
    const auto& s = v.get_ref<const std::string&>();
    if (s.empty()) throw InputError(pointer, msg(what, ": id must not be empty"));
    out.assign(s);
    return;
  }
  char digits[24];
  std::to_chars_result r;
  if (v.is_number_unsigned()) r = std::to_chars(digits, digits + sizeof digits, v.get<std::uint64_t>());
  else if (v.is_number_integer()) r = std::to_chars(digits, digits + sizeof digits, v.get<long long>());
  else throw InputError(pointer, msg(what, ": an id must be a string or an integer"));
  out.assign(digits, r.ptr);
}

Vec3 vec3(const json& v, const Pointer& pointer, const What& what) {
  if (!v.is_array() || v.size() != 3) throw InputError(pointer, msg(what, ": expected an array of 3 numbers"));
  Vec3 x;
  for (int i = 0; i < 3; ++i) x[i] = number(v[i], child(pointer, i), what);
  return x;
}

std::vector<double> numbers(const json& v, const Pointer& pointer, const What& what) {
  if (!v.is_array()) throw InputError(pointer, msg(what, ": expected an array of numbers"));
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i) out.push_back(number(v[i], child(pointer, i), what));
  return out;
}

const json& array(const json& v, const Pointer& pointer, const What& what) {
  if (!v.is_array()) throw InputError(pointer, msg(what, ": expected an array"));
  return v;
}

const json& object(const json& v, const Pointer& pointer, const What& what) {
  if (!v.is_object()) throw InputError(pointer, msg(what, ": expected an object"));
  return v;
}

int dof_name(const json& v, const Pointer& pointer, const What& what, const What& context, std::string_view noun) {
  const std::string name = string(v, pointer, what);
  const int d = dof_index(name);
  if (d < 0)
    throw InputError(pointer, context.str() + "unknown " + std::string(noun) + " '" + name + "' (expected ux uy uz rx ry rz)");
  return d;
}

MassKind mass_kind(const json& v, const Pointer& pointer, const What& what, std::string_view context) {
  const std::string kind = string(v, pointer, what);
  if (kind == "consistent") return MassKind::Consistent;
  if (kind == "lumped") return MassKind::Lumped;
  throw InputError(pointer, std::string(context) + ": unknown mass '" + kind + "' (expected consistent or lumped)");
}

GeometricStiffness geometric_stiffness_kind(const json& v, const Pointer& pointer, const What& what, std::string_view context) {
  const std::string kind = string(v, pointer, what);
  if (kind == "full") return GeometricStiffness::Full;
  if (kind == "axial") return GeometricStiffness::Axial;
  throw InputError(pointer, std::string(context) + ": unknown geometric_stiffness '" + kind + "' (expected full or axial)");
}

}  // namespace beamfea::json_in
