#pragma once
// The exception a call throws, for the tests of error messages.
#include <optional>
#include <utility>

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

}  // namespace beamfea::test
