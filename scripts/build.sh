#!/usr/bin/env bash
# Configures and builds dnurbs in Release into build/ (warnings are errors).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release -DDNURBS_WARNINGS_AS_ERRORS=ON \
      -DCMAKE_EXPORT_COMPILE_COMMANDS=ON "$@" >/dev/null
cmake --build "$root/build" --parallel "$(nproc)"
