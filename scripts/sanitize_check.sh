#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer check of the input paths (CI runs it after the
# tests): builds test_io and the dnurbs command with -DDNURBS_SANITIZE=ON in a second build
# directory, runs the io tests there (the scene round trip and the corpus of malformed scenes in
# tests/data/bad_scenes) and the sanitized command on every malformed scene (exit 1 with its
# message, never a sanitizer report or a signal), the default demo and a constrained scene; then
# the sculpting session's tests (every client message validated) and the sanitized `dnurbs
# serve` against hostile clients (tests/web/hostile_clients.mjs).
# Usage: scripts/sanitize_check.sh [BUILD_DIR] (default build-sanitize/); JOBS=N sets the
# parallel build jobs (default: the number of cores).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build-sanitize}"
jobs="${JOBS:-$(nproc)}"
start=$(date +%s)
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
# -O1 -g1: the sanitizers' recommended optimization, line tables for the reports, and a build
# about three times faster than RelWithDebInfo
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Sanitize -DCMAKE_CXX_FLAGS_SANITIZE="-O1 -g1" \
      -DDNURBS_SANITIZE=ON -DDNURBS_WARNINGS_AS_ERRORS=ON -DDNURBS_BUILD_EXAMPLES=OFF \
      -DDNURBS_BUILD_BENCH=OFF "${launcher[@]}" >/dev/null
cmake --build "$build" --parallel "$jobs" --target test_io test_sculpt dnurbs_tool
# Any sanitizer report fails the run
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
(cd "$build" && ctest -L "^(io|sculpt)$" --output-on-failure --parallel "$jobs")
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
echo "sanitize_check: $count malformed scenes, the demo, a constrained scene and hostile" \
     "clients of dnurbs serve passed in" \
     "$(( $(date +%s) - start )) s"
