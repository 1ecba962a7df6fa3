// libFuzzer target over the model file: parsing, the shared validation (`check`) and a bounded
// run of small models. Built only with clang (-DBEAMFEA_BUILD_FUZZERS=ON); how to build
// and run it: docs/testing.md.
//
// The rules it enforces beside "no crash, no sanitizer report": reading and checking throw only
// beamfea's own errors (InputError, ModelError), never a library's exception; a run after a
// successful check throws nothing at all (failures are outcomes). A case that breaks a rule
// aborts, and libFuzzer saves it; add it to tests/fuzz/corpus/ once fixed (the corpus replay
// test runs every file there through the program on every build).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <string>

#include "fuzz/harness.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  beamfea::fuzz::run_one_case(text);
  return 0;
}
