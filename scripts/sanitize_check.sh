#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer check of the input paths (CI runs it after the
# tests): builds test_io, test_sculpt, the dnurbs command and the fuzz targets in a second build
# directory, runs the io tests there (the scene round trip and the corpus of malformed scenes in
# tests/data/bad_scenes) and the sanitized command on every malformed scene (exit 1 with its
# message, never a sanitizer report or a signal), the default demo and a constrained scene; then
# the sculpting session's tests (every client message validated) and the sanitized `dnurbs
# serve` against hostile clients (tests/web/hostile_clients.mjs); last, each libFuzzer target of
# fuzz/ for FUZZ_SECONDS (default 60; scripts/fuzz.sh). The build is clang's
# (scripts/configure_sanitize.sh), instrumented for the fuzzer as well.
# Usage: scripts/sanitize_check.sh [BUILD_DIR] (default build-sanitize/); JOBS=N sets the
# parallel build jobs and fuzz targets at once (default: the number of cores).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build-sanitize}"
jobs="${JOBS:-$(nproc)}"
start=$(date +%s)
"$root/scripts/configure_sanitize.sh" "$build"
cmake --build "$build" --parallel "$jobs" --target test_io test_sculpt dnurbs_tool \
  fuzz_scene_reader fuzz_shape_reader fuzz_checkpoint_reader fuzz_mesh_import
# Any sanitizer report fails the run
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
# Open CASCADE's process-lifetime allocations (scripts/lsan_suppressions.txt)
export LSAN_OPTIONS="suppressions=$root/scripts/lsan_suppressions.txt"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Whole-scene physics runs that read no more input than the scene tests before them are left to
# the optimized build: under the sanitizers the data-force tracking run alone takes 170 s of the
# 220 s (its 300 steps search 200 nearest points each), and it checks motion, not input handling
physics_runs="^SuperquadricTracksPoints\\."
(cd "$build" && ctest -L "^(io|sculpt)$" -E "$physics_runs" --output-on-failure --parallel "$jobs")
dnurbs="$build/tools/dnurbs"
corpus="$root/tests/data/bad_scenes"
count=0
while IFS=$'\t' read -r file expected _; do
  [[ -z "$file" || "$file" == \#* ]] && continue
  set +e
  message="$("$dnurbs" run "$corpus/$file" --out "$build/sanitize-bad" --no-preview 2>&1)"
  status=$?
  set -e
  if [[ $status -ne 1 || "$message" != *"$expected"* ]]; then
    echo "sanitize_check: $file: exit $status (expected 1 and \"$expected\"):" >&2
    echo "$message" >&2
    exit 1
  fi
  count=$((count + 1))
done <"$corpus/expected_messages.tsv"
"$dnurbs" run --out "$build/sanitize-demo" --resolution 6 --no-preview >/dev/null
"$dnurbs" run "$root/examples/scenes/constraints.json" --out "$build/sanitize-constraints" \
    --resolution 4 --no-preview >/dev/null
node "$root/tests/web/hostile_clients.mjs" --dnurbs "$dnurbs" --out "$build/sanitize-serve"
BUILD_DIR="$build" "$root/scripts/fuzz.sh" "${FUZZ_SECONDS:-60}"
echo "sanitize_check: $count malformed scenes, the demo, a constrained scene, hostile" \
     "clients of dnurbs serve and ${FUZZ_SECONDS:-60} s of each fuzz target passed in" \
     "$(( $(date +%s) - start )) s"
