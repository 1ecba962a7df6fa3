#!/usr/bin/env bash
# Fresh machine -> a tested build: install, build, and run the whole test suite (C++ and Python)
# under GCC's AddressSanitizer and UndefinedBehaviorSanitizer, in build-asan/:
# -fsanitize=address,undefined with every undefined behaviour fatal, libraries and tests at -O1 (no debug information: reports name
# functions, not lines) with assertions on, unity batches; leak detection with OpenMPI's own leaks suppressed
# (tests/fuzz/lsan.supp); the Python suites load the sanitized module into Debian's Python with the
# ASan runtime preloaded. No benchmarks. One build instead of a Release one and a sanitized one
# keeps CI within its budget (docs/testing.md has the times).
# BEAMFEA_SANITIZE_SUITE=0: the Release build (scripts/build.sh, build/) and its suite instead.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${BEAMFEA_SANITIZE_SUITE:-1}" = "0" ]; then
  scripts/build.sh build
  exec ctest --test-dir build --output-on-failure -j "$(nproc)" --timeout 600
fi
scripts/install-deps.sh
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1" \
      -DBEAMFEA_SANITIZE=ON -DBEAMFEA_BUILD_BENCHMARKS=OFF
cmake --build build-asan -j "$(nproc)"
ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS="suppressions=$PWD/tests/fuzz/lsan.supp" \
  ctest --test-dir build-asan --output-on-failure -j "$(nproc)" --timeout 1200
