#!/usr/bin/env bash
# Configures and builds dnurbs in Release into build/ (warnings are errors), with Ninja when it is
# installed and build/ is new (a build/ configured earlier keeps its generator). The CAD exchange
# (cad/) is on: scripts/install_dependencies.sh installs Open CASCADE, and a build/ configured
# before it was installed turns it on now.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
generator=()
if command -v ninja >/dev/null && [ ! -f "$root/build/CMakeCache.txt" ]; then
  generator=(-G Ninja)
fi
cmake -S "$root" -B "$root/build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DDNURBS_WARNINGS_AS_ERRORS=ON \
      -DDNURBS_WITH_CAD=ON -DCMAKE_EXPORT_COMPILE_COMMANDS=ON "$@" >/dev/null
cmake --build "$root/build" --parallel "$(nproc)"
