#!/usr/bin/env bash
# Fresh machine -> a tested build: install, build, and run the whole test suite.
# BEAMFEA_SANITIZE_SUITE=1 also builds the suite with GCC's -fsanitize=address,undefined
# (-O1 -g1, no benchmarks, no Python, in build-asan/) and runs it, OpenMPI's own leaks suppressed
# (tests/fuzz/lsan.supp). Off by default until its time on the CI machine is measured
# (docs/testing.md: the compile costs 1.87x a Release build's; the sanitized tests' time is unknown).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh build
ctest --test-dir build --output-on-failure -j "$(nproc)" --timeout 600
if [ "${BEAMFEA_SANITIZE_SUITE:-0}" = "1" ]; then
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
        -DBEAMFEA_SANITIZE=ON -DBEAMFEA_BUILD_BENCHMARKS=OFF -DBEAMFEA_BUILD_PYTHON=OFF
  cmake --build build-asan -j "$(nproc)"
  ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS="suppressions=$PWD/tests/fuzz/lsan.supp" \
    ctest --test-dir build-asan --output-on-failure -j "$(nproc)" --timeout 1200
fi
