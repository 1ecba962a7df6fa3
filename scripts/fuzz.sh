#!/usr/bin/env bash
# Runs one of the libFuzzer targets (tests/fuzz) for a chosen time (docs/testing.md):
#   scripts/fuzz.sh model|sweep SECONDS [more libFuzzer options]
# Builds build-fuzz/ first if needed (clang-14, -O1 -g, ASan + UBSan + the fuzzer's coverage), then
# runs the target with its dictionary over its seed corpus (tests/fuzz/corpus or corpus_sweep, read
# only) and the inputs it found before (fuzz-work/<target>/corpus, where new ones go), one process
# at a time (-fork=1) at a low priority, going on after a crash, a hang or running out of memory.
# Each finding is saved in fuzz-work/<target>/crashes/ (crash-*, timeout-*, oom-*, leak-*; slow-unit-*
# for an input over 10 s, not counted as a finding); replay one with
#   build-fuzz/tests/fuzz/fuzz_<target> fuzz-work/<target>/crashes/crash-<hash>
# The run's log is fuzz-work/<target>/fuzz.log: its last "#<n> ... cov: ... ft: ..." lines give the
# inputs run, the coverage and the features reached. Environment: BEAMFEA_FUZZ_BUILD (the build
# folder), BEAMFEA_FUZZ_WORK (the work folder), BEAMFEA_FUZZ_JOBS (build jobs, default 2),
# BEAMFEA_FUZZ_NICE (default 10), BEAMFEA_FUZZ_TIMEOUT (seconds one input may take, default 60).
set -euo pipefail
usage() { echo "usage: scripts/fuzz.sh model|sweep SECONDS [libFuzzer options]" >&2; exit 2; }
[ $# -ge 2 ] || usage
target=$1 seconds=$2
shift 2
case "$target" in
  model) seeds=corpus dict=model.dict ;;
  sweep) seeds=corpus_sweep dict=sweep.dict ;;
  *) usage ;;
esac
[[ "$seconds" =~ ^[0-9]+$ ]] || usage
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BEAMFEA_FUZZ_BUILD:-$root/build-fuzz}
work=${BEAMFEA_FUZZ_WORK:-$root/fuzz-work}/$target
exe=$build/tests/fuzz/fuzz_$target

if [ ! -f "$build/build.ninja" ]; then
  CC=clang-14 CXX=clang++-14 cmake -S "$root" -B "$build" -G Ninja \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" \
    -DBEAMFEA_BUILD_FUZZERS=ON -DBEAMFEA_BUILD_TESTS=OFF -DBEAMFEA_BUILD_BENCHMARKS=OFF \
    -DBEAMFEA_BUILD_PYTHON=OFF -DBEAMFEA_BUILD_CLI=OFF
fi
cmake --build "$build" --target "fuzz_$target" -j "${BEAMFEA_FUZZ_JOBS:-2}"

mkdir -p "$work/corpus" "$work/crashes"
cd "$work"  # fork mode's temporary files
echo "fuzz_$target for $seconds s; log: $work/fuzz.log" >&2
status=0
ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}" LSAN_OPTIONS="suppressions=$root/tests/fuzz/lsan.supp" \
  nice -n "${BEAMFEA_FUZZ_NICE:-10}" "$exe" -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
  -max_total_time="$seconds" -timeout="${BEAMFEA_FUZZ_TIMEOUT:-60}" -rss_limit_mb=4096 -print_final_stats=1 \
  -dict="$root/tests/fuzz/$dict" -artifact_prefix="$work/crashes/" "$@" \
  "$work/corpus" "$root/tests/fuzz/$seeds" > "$work/fuzz.log" 2>&1 || status=$?
grep -E "^#[0-9]+" "$work/fuzz.log" | tail -n 1 >&2 || true
# Findings: crashes (sanitizer reports and broken rules included), hangs, memory exhaustion, leaks.
# A slow-unit-* file (an input over libFuzzer's 10 s mark: on a busy machine often only starved of
# CPU) is listed apart: replay it to see whether it is slow alone.
found=$(find "$work/crashes" -type f \( -name 'crash-*' -o -name 'timeout-*' -o -name 'oom-*' -o -name 'leak-*' \) | wc -l)
slow=$(find "$work/crashes" -type f -name 'slow-unit-*' | wc -l)
echo "fuzz_$target: exit $status, $found finding(s) and $slow slow input(s) in $work/crashes" >&2
[ "$found" -eq 0 ]
