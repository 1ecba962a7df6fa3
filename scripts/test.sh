#!/usr/bin/env bash
# Fresh machine -> a tested build: install, build, and run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh build
ctest --test-dir build --output-on-failure -j "$(nproc)" --timeout 600
