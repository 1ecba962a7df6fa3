#!/usr/bin/env bash
# Installs the dependencies (skipping what is present), configures and builds beamfea.
# Usage: scripts/build.sh [build-dir]     (default: build)
# BEAMFEA_CXX_TESTS=OFF builds no GoogleTest executables (scripts/test.sh's Release tree); stated on
# every configure, so that a tree once configured so gets them back from a plain build.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
scripts/install-deps.sh
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DBEAMFEA_CXX_TESTS="${BEAMFEA_CXX_TESTS:-ON}"
cmake --build "$build" -j "$(nproc)"
