#!/usr/bin/env bash
# Builds test_io and the dnurbs command with AddressSanitizer + UndefinedBehaviorSanitizer
# (-DDNURBS_SANITIZE=ON) in a second build directory and runs the io tests there (ctest -L io).
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
echo "sanitize_check: passed in $(( $(date +%s) - start )) s"
