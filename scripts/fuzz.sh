#!/usr/bin/env bash
# In-process fuzzing of the input readers with libFuzzer (fuzz/): the scene reader, the shape-file
# readers, the checkpoint reader and the mesh importer, built with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer in the sanitizer build directory (shared with sanitize_check.sh).
# Each target runs for SECONDS from its seed corpus (the example scenes, the malformed-scene
# corpus, the test shapes, fuzz/corpus) with the JSON dictionary fuzz/json.dict; what it finds
# is kept in BUILD_DIR/fuzz-corpus/<target> for the next run. A crash, a sanitizer report, a
# leak, a timeout or a broken round trip (fuzz/fuzz_support.h) fails the script, which prints
# the log's end and the saved input. The timeout is 60 s: a valid scene that a 30-minute run
# found, a degree-6 L-shaped triangular sheet, takes 16 s to read in this build (its basis is
# built at load to check the knot clouds). Prints, per target, the executions, the edges
# covered and the corpus size.
# Usage: scripts/fuzz.sh [SECONDS [TARGET...]] (default 60 s, every target); CI runs 60 s, a
# local long run is `scripts/fuzz.sh 1800`. BUILD_DIR (default build-sanitize/), JOBS targets
# at once (default: the number of cores).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build-sanitize}"
jobs="${JOBS:-$(nproc)}"
seconds="${1:-60}"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(scene_reader shape_reader checkpoint_reader mesh_import)
fi
if ! [[ "$seconds" =~ ^[1-9][0-9]*$ ]]; then
  echo "fuzz.sh: SECONDS must be a positive whole number, got \"$seconds\"" >&2
  exit 2
fi
declare -A seeds=(
  [scene_reader]="$root/examples/scenes $root/tests/data/bad_scenes"
  [shape_reader]="$root/tests/data $root/fuzz/corpus/shape"
  [checkpoint_reader]="$root/fuzz/corpus/checkpoint"
  [mesh_import]="$root/fuzz/corpus/mesh"
)
for target in "${targets[@]}"; do
  if [ -z "${seeds[$target]+set}" ]; then
    echo "fuzz.sh: unknown target \"$target\" (known: ${!seeds[*]})" >&2
    exit 2
  fi
done
"$root/scripts/configure_sanitize.sh" "$build"
cmake --build "$build" --parallel "$jobs" --target "${targets[@]/#/fuzz_}"

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
run_target() {
  local target="$1" corpus="$build/fuzz-corpus/$1" artifacts="$build/fuzz-artifacts/$1"
  mkdir -p "$corpus" "$artifacts"
  # shellcheck disable=SC2086  # the seed folders are a space-separated list
  "$build/fuzz/fuzz_$target" -max_total_time="$seconds" -timeout=60 -rss_limit_mb=2048 \
    -dict="$root/fuzz/json.dict" -print_final_stats=1 -artifact_prefix="$artifacts/" \
    "$corpus" ${seeds[$target]} >"$build/fuzz-$target.log" 2>&1
  echo $? >"$build/fuzz-$target.status"
}
summary() {
  local log="$build/fuzz-$1.log"
  local runs coverage
  runs="$(grep -oE "Done [0-9]+ runs in [0-9]+ second" "$log" | tail -1 | grep -oE "[0-9]+" |
    head -1 || true)"
  coverage="$(grep -oE "cov: [0-9]+ ft: [0-9]+ corp: [0-9]+" "$log" | tail -1 || true)"
  echo "fuzz: $1: ${runs:-?} executions in $seconds s; ${coverage:-no coverage line}"
}
for target in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do
    wait -n || true
  done
  rm -f "$build/fuzz-$target.status"
  (set +e; run_target "$target") &
done
wait
status=0
for target in "${targets[@]}"; do
  if [ "$(cat "$build/fuzz-$target.status" 2>/dev/null)" = 0 ]; then
    summary "$target"
  else
    status=1
    echo "fuzz: $target FAILED; the end of $build/fuzz-$target.log:" >&2
    tail -40 "$build/fuzz-$target.log" >&2
    echo "fuzz: saved inputs: $(ls "$build/fuzz-artifacts/$target")" >&2
  fi
done
exit "$status"
