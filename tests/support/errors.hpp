#pragma once
// The exception a call throws, for the tests of error messages.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>

#include "core/errors.hpp"
#include "io/run.hpp"

namespace beamfea::test {

// The exception of type E that `f` throws (copied), or none when it returns; an exception of
// another type passes through.
template <class E, class F>
std::optional<E> thrown(F&& f) {
  try {
    std::forward<F>(f)();
  } catch (const E& e) {
    return e;
  }
  return std::nullopt;
}

// The JSON pointer of the InputError that reading and checking `doc` raises, "(no error)" if none.
inline std::string input_error_pointer(const nlohmann::json& doc) {
  const auto e = thrown<InputError>([&] { load_and_check(doc); });
  return e ? e->pointer() : "(no error)";
}

}  // namespace beamfea::test
