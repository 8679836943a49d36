#!/usr/bin/env bash
# Configures the sanitizer build directory shared by sanitize_check.sh and fuzz.sh: clang, -O1 -g1
# (the sanitizers' recommended optimization, line tables for the reports, and a build about three
# times faster than RelWithDebInfo), AddressSanitizer + UndefinedBehaviorSanitizer, and the
# libFuzzer targets (DNURBS_FUZZ, which instruments the library for coverage). Without the
# examples, benchmarks and Python module, which these checks do not run.
# Usage: scripts/configure_sanitize.sh BUILD_DIR
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$1"
clang="$(command -v clang++-14 || command -v clang++ || true)"
if [ -z "$clang" ]; then
  echo "configure_sanitize: clang++ is missing (scripts/install_dependencies.sh installs it)" >&2
  exit 1
fi
generator=()
if command -v ninja >/dev/null && [ ! -f "$build/CMakeCache.txt" ]; then
  generator=(-G Ninja)
fi
cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_CXX_COMPILER="$clang" \
      -DCMAKE_BUILD_TYPE=Sanitize -DCMAKE_CXX_FLAGS_SANITIZE="-O1 -g1" -DDNURBS_FUZZ=ON \
      -DDNURBS_WARNINGS_AS_ERRORS=ON -DDNURBS_BUILD_EXAMPLES=OFF -DDNURBS_BUILD_BENCH=OFF >/dev/null
