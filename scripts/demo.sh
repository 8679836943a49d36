#!/usr/bin/env bash
# README command 1: install what is missing, build, run the default demo scene.
# Results (OBJ meshes, PNG preview) go to dnurbs-out/ unless a directory is given.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/dnurbs-out}"
"$root/scripts/install_dependencies.sh"
"$root/scripts/build.sh"
"$root/build/tools/dnurbs" run --out "$out"
