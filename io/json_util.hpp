#pragma once
// Typed access to JSON input with errors that carry the JSON pointer of the field at fault.
// Pointers are json_in::Pointer (io/json_pointer.hpp): rendered only when an error is thrown;
// `what` (the entity named in the message) is only read then too.
#include <nlohmann/json.hpp>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "core/errors.hpp"
#include "core/rotation.hpp"
#include "elements/beam_mass.hpp"
#include "io/json_pointer.hpp"

namespace beamfea::json_in {

using json = nlohmann::json;

// The one key policy of every input object (model, analysis specs, stop/control blocks, sweep
// files): a key of `obj` that is not in `known` is an InputError at its pointer, suggesting the
// nearest known key by edit distance ("did you mean 'supports'?"). Keys starting with '_' and
// the key "comment" are free (for the user's notes). Adding a key to the format is adding it to
// the `known` list at the call site: one line. Does nothing when `obj` is not an object (the
// caller's type check reports that).
void expect_keys(const json& obj, const Pointer& pointer, std::initializer_list<std::string_view> known);
// The known key nearest to `key` by edit distance, or "" when none is close enough to suggest.
std::string nearest_key(std::string_view key, std::initializer_list<std::string_view> known);
// The same over names known only at run time (the links of a robot description).
std::string nearest_key(std::string_view key, const std::vector<std::string>& known);

// The entity named in a message ("element 'e1' material"), up to three parts joined only when a
// message is built: a reader names every field it reads and almost never needs the name. The parts
// are views (of literals, of the caller's strings, of a temporary string passed along): a What is
// a parameter of the helpers below, never kept beyond the call.
class What {
 public:
  What(std::string_view a, std::string_view b = {}, std::string_view c = {}) : a_(a), b_(b), c_(c) {}
  What(const std::string& a) : a_(a) {}
  What(const char* a) : a_(a) {}
  std::string str() const {
    std::string s;
    s.reserve(a_.size() + b_.size() + c_.size());
    return s.append(a_).append(b_).append(c_);
  }

 private:
  std::string_view a_, b_, c_;
};

// An object's known fields, found in one pass over its keys (a reader that checks the keys and
// then looks up each field it reads searches the object's map once per field):
//   const Fields f(o, p, {"id", "xyz"});       // expect_keys(o, p, {...}): an unknown key throws
//   id_into(node.id, f.require("id", "node"), child(p, "id"), "node");
//   if (const json* v = f.get("orientation")) ...
// A Fields views `obj`, `pointer` (not a temporary) and the keys of `obj`: it lives while they do.
// Not an object: no fields (require() then throws "expected an object", as json_in::require does).
class Fields {
 public:
  static constexpr std::size_t kMaxKnown = 32;
  Fields(const json& obj, const Pointer& pointer, std::initializer_list<std::string_view> known);
  Fields(const json&, Pointer&&, std::initializer_list<std::string_view>) = delete;
  // The value of `key` (one of the known keys), or null when the object lacks it.
  const json* get(std::string_view key) const {
    for (std::size_t i = 0; i < n_; ++i)
      if (keys_[i] == key) return values_[i];
    return nullptr;
  }
  // The value of `key`; missing: the InputError of json_in::require.
  const json& require(std::string_view key, const What& what) const {
    if (const json* v = get(key)) return *v;
    missing(key, what);
  }

 private:
  [[noreturn]] void missing(std::string_view key, const What& what) const;
  const json& obj_;
  const Pointer& pointer_;
  std::string_view keys_[kMaxKnown];
  const json* values_[kMaxKnown];
  std::size_t n_ = 0;
};

// Largest magnitude of an input number: squares and products of a few such values (lengths
// squared, E I / L^3, ...) stay far inside double range (1.8e308). docs/input-format.md.
inline constexpr double kMaxMagnitude = 1e100;

const json& require(const json& obj, const Pointer& pointer, std::string_view key, const What& what);
// A finite number of magnitude at most kMaxMagnitude.
double number(const json& v, const Pointer& pointer, const What& what);
double positive(const json& v, const Pointer& pointer, const What& what);
// An integer that fits an int (values beyond it are an error, never wrapped).
int integer(const json& v, const Pointer& pointer, const What& what);
// An integer no smaller than `min`.
int integer_at_least(const json& v, const Pointer& pointer, const What& what, int min);
// An integer in [min, max] (documented bounds on sizes that would exhaust memory or time).
int integer_in(const json& v, const Pointer& pointer, const What& what, int min, int max);
bool boolean(const json& v, const Pointer& pointer, const What& what);
std::string string(const json& v, const Pointer& pointer, const What& what);
// An id: a string or an integer, returned as a string.
std::string id(const json& v, const Pointer& pointer, const What& what);
// The same, written over `out` (its storage reused).
void id_into(std::string& out, const json& v, const Pointer& pointer, const What& what);
// The value of `key` in object `obj`, or null when absent (or `obj` is not an object): one search
// where contains() then operator[] would make two.
inline const json* field(const json& obj, std::string_view key) {
  if (!obj.is_object()) return nullptr;
  const auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}
Vec3 vec3(const json& v, const Pointer& pointer, const What& what);
std::vector<double> numbers(const json& v, const Pointer& pointer, const What& what);
const json& array(const json& v, const Pointer& pointer, const What& what);
const json& object(const json& v, const Pointer& pointer, const What& what);

// The readers of names every spec shares. A DOF name ("ux" ... "rz", core/model.hpp's dof_index):
// its index; a non-string is an InputError naming `what`, an unknown name the InputError
// "<context>unknown <noun> '<name>' (expected ux uy uz rx ry rz)".
int dof_name(const json& v, const Pointer& pointer, const What& what, const What& context, std::string_view noun = "DOF");
// A mass kind, "consistent" or "lumped"; an unknown kind is the InputError
// "<context>: unknown mass '<kind>' (expected consistent or lumped)".
MassKind mass_kind(const json& v, const Pointer& pointer, const What& what, std::string_view context);
// "full" or "axial" (elements/frame_element.hpp, GeometricStiffness).
GeometricStiffness geometric_stiffness_kind(const json& v, const Pointer& pointer, const What& what, std::string_view context);

}  // namespace beamfea::json_in
