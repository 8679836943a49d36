#!/usr/bin/env bash
# Builds test_io and the dnurbs command with AddressSanitizer + UndefinedBehaviorSanitizer
# (-DDNURBS_SANITIZE=ON) in a second build directory, runs the io tests there (ctest -L io) and
# the sanitized dnurbs command on the default demo and a constrained scene.
# Usage: scripts/sanitize_check.sh [BUILD_DIR] (default build-sanitize/); JOBS=N sets the
# parallel build jobs (default 2).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build-sanitize}"
jobs="${JOBS:-2}"
start=$(date +%s)
# RelWithDebInfo: sanitizer reports with line numbers at a usable speed
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDNURBS_SANITIZE=ON \
      -DDNURBS_WARNINGS_AS_ERRORS=ON -DDNURBS_BUILD_EXAMPLES=OFF -DDNURBS_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" --parallel "$jobs" --target test_io dnurbs_tool
# Any sanitizer report fails the test that triggered it
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
(cd "$build" && ctest -L io --output-on-failure)
# The sanitized command on the default demo and on a scene with constraints
"$build/tools/dnurbs" run --out "$build/sanitize-demo" --resolution 6 --no-preview >/dev/null
"$build/tools/dnurbs" run "$root/examples/scenes/constraints.json" --out "$build/sanitize-constraints" \
    --resolution 4 >/dev/null
echo "sanitize_check: passed in $(( $(date +%s) - start )) s"
