#pragma once
// Error hierarchy of beamfea.
//
// Bad input is an exception that names what is at fault:
//   InputError  carries the JSON pointer of the bad field ("/elements/3/section");
//   ModelError  names the node, element, joint or DOF of a model that is inconsistent.
// Non-convergence and singular tangents are *outcomes* reported in solver summaries,
// never exceptions.
#include <stdexcept>
#include <string>

namespace beamfea {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Malformed or inconsistent input; `pointer` is an RFC 6901 JSON pointer ("" when unknown).
class InputError : public Error {
 public:
  InputError(std::string pointer, const std::string& message)
      : Error(pointer.empty() ? message : pointer + ": " + message), pointer_(std::move(pointer)) {}
  const std::string& pointer() const { return pointer_; }

 private:
  std::string pointer_;
};

// A model that cannot be analysed as given; `entity` is e.g. "element 'e3'" or "node 'A' dof uz".
class ModelError : public Error {
 public:
  ModelError(std::string entity, const std::string& message)
      : Error(entity.empty() ? message : entity + ": " + message), entity_(std::move(entity)) {}
  const std::string& entity() const { return entity_; }

 private:
  std::string entity_;
};

}  // namespace beamfea
