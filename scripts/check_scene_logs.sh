#!/usr/bin/env bash
# Behavior check for refactoring: runs every scene in examples/scenes with the built dnurbs
# command and compares its log.csv with the log recorded in tests/data/scene_logs/<scene>.csv
# (recorded before a change that must not alter behavior): the same rows, every number within
# 1e-8 of its column's scale (scripts/compare_scene_log.py says why not byte for byte).
# A scene that stops as diverged must stop the same way (same exit status, same log).
# Usage: scripts/check_scene_logs.sh [BUILD_DIR] [--record]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
record="${2:-}"
dnurbs="$build/tools/dnurbs"
recorded="$root/tests/data/scene_logs"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
failures=0
count=0
for scene in "$root"/examples/scenes/*.json; do
  name="$(basename "$scene" .json)"
  set +e
  "$dnurbs" run "$scene" --out "$work/$name" --no-preview --resolution 4 >/dev/null 2>"$work/$name.err"
  status=$?
  set -e
  if [ "$record" = "--record" ]; then
    cp "$work/$name/log.csv" "$recorded/$name.csv"
    echo "$status" >"$recorded/$name.status"
    continue
  fi
  count=$((count + 1))
  expected_status="$(cat "$recorded/$name.status")"
  if [ "$status" != "$expected_status" ]; then
    echo "check_scene_logs: $name: exit $status, recorded $expected_status" >&2
    cat "$work/$name.err" >&2
    failures=$((failures + 1))
  elif ! difference="$(/usr/bin/python3 "$root/scripts/compare_scene_log.py" "$recorded/$name.csv" "$work/$name/log.csv")"; then
    echo "check_scene_logs: $name: log.csv differs from $recorded/$name.csv: $difference" >&2
    failures=$((failures + 1))
  fi
done
if [ "$record" = "--record" ]; then
  echo "check_scene_logs: recorded the logs of every scene in $recorded"
  exit 0
fi
if [ "$failures" -ne 0 ]; then
  echo "check_scene_logs: $failures of $count scenes changed" >&2
  exit 1
fi
echo "check_scene_logs: all $count scenes give their recorded log.csv"
