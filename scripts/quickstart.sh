#!/usr/bin/env bash
# Fresh machine -> the main job: install, build, and run the bundled space-frame example.
# Writes out/01_space_frame/results.json and lin.vtu (open it in ParaView).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh build
build/cli/beamfea run examples/01_space_frame/model.json --out out/01_space_frame
echo "results: out/01_space_frame/results.json   ParaView: out/01_space_frame/lin.vtu"
