#!/usr/bin/env bash
# Installs the dependencies (skipping what is present), configures and builds beamfea.
# Usage: scripts/build.sh [build-dir]     (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
scripts/install-deps.sh
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" -j "$(nproc)"
