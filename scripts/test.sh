#!/usr/bin/env bash
# Fresh machine -> a tested build: install, build, and run the whole test suite.
#
# The C++ suite runs under GCC's AddressSanitizer and UndefinedBehaviorSanitizer (build-asan/:
# -fsanitize=address,undefined, every undefined behaviour fatal, leak detection with OpenMPI's own
# leaks suppressed by tests/fuzz/lsan.supp; libraries at -O1 -g1 with assertions on, the tests' own
# code at -O0; no benchmarks, no Python module). The Release tree (build/) builds the libraries,
# the program, the Python module and the benchmarks, and runs the pytest suites (a sanitized
# extension cannot be loaded into Debian's Python). Compiling the C++ tests once instead of twice
# keeps CI within its budget (docs/testing.md has the times).
# BEAMFEA_SANITIZE_SUITE=0: the C++ suite in the Release tree instead, no sanitizer build.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${BEAMFEA_SANITIZE_SUITE:-1}" = "0" ]; then
  scripts/build.sh build
  ctest --test-dir build --output-on-failure -j "$(nproc)" --timeout 600
  exit 0
fi
BEAMFEA_CXX_TESTS=OFF scripts/build.sh build
ctest --test-dir build --output-on-failure -j "$(nproc)" --timeout 600
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
      -DBEAMFEA_SANITIZE=ON -DBEAMFEA_BUILD_BENCHMARKS=OFF -DBEAMFEA_BUILD_PYTHON=OFF
cmake --build build-asan -j "$(nproc)"
ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS="suppressions=$PWD/tests/fuzz/lsan.supp" \
  ctest --test-dir build-asan --output-on-failure -j "$(nproc)" --timeout 1200
