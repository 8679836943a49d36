#!/usr/bin/env bash
# clang-tidy with the repository's .clang-tidy over every library and tool source (CI runs it):
# needs a build directory configured with CMAKE_EXPORT_COMPILE_COMMANDS=ON (scripts/build.sh does
# that). Any warning fails the check. Also checks the size limits of the library: no file over
# 600 lines (functions over 120 lines are clang-tidy's readability-function-size), and that
# every C++ file of the library, tools, tests, benchmarks and examples is clang-format clean and
# includes the library's headers with the dnurbs/ prefix.
# Usage: scripts/clang_tidy_check.sh [BUILD_DIR]; JOBS=N runs N clang-tidy processes.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
jobs="${JOBS:-$(nproc)}"
cd "$root"
if [ ! -f "$build/compile_commands.json" ]; then
  echo "clang_tidy_check: $build/compile_commands.json is missing (configure with" \
       "-DCMAKE_EXPORT_COMPILE_COMMANDS=ON, as scripts/build.sh does)" >&2
  exit 1
fi
folders=(core nurbs surface vision dynamics constraints cad design io sculpt tools python)
existing=()
for folder in "${folders[@]}"; do
  # cad/ only when the build compiled it (DNURBS_WITH_CAD, Open CASCADE found)
  if [ "$folder" = cad ] && ! grep -q "/cad/" "$build/compile_commands.json"; then
    continue
  fi
  # python/ only when the build compiled the Python module (DNURBS_BUILD_PYTHON)
  if [ "$folder" = python ] && ! grep -q "/python/src/" "$build/compile_commands.json"; then
    continue
  fi
  [ -d "$folder" ] && existing+=("$folder")
done
status=0
while IFS= read -r file; do
  lines=$(wc -l <"$file")
  if [ "$lines" -gt 600 ]; then
    echo "clang_tidy_check: $file has $lines lines (limit 600)" >&2
    status=1
  fi
done < <(find "${existing[@]}" -name '*.cpp' -o -name '*.h' | sort)
formatted=(tests bench examples fuzz)
unformatted="$(find "${existing[@]}" "${formatted[@]}" -name '*.cpp' -o -name '*.h' | sort |
  xargs clang-format --dry-run 2>&1 | grep -E "warning:" | cut -d: -f1 | sort -u || true)"
if [ -n "$unformatted" ]; then
  echo "clang_tidy_check: not clang-format clean (run clang-format -i on them):" >&2
  echo "$unformatted" >&2
  status=1
fi
# The library's headers are included with the project prefix everywhere ("dnurbs/io/scene.h",
# CMakeLists.txt): an installed header that included "io/scene.h" would not compile for a user.
library_folders="core|nurbs|surface|vision|dynamics|constraints|cad|design|io|sculpt"
unprefixed="$(find "${existing[@]}" "${formatted[@]}" -name '*.cpp' -o -name '*.h' -o -name '*.def' |
  sort | xargs grep -nE "^#[[:space:]]*include[[:space:]]+\"(${library_folders})/" || true)"
if [ -n "$unprefixed" ]; then
  echo "clang_tidy_check: library headers included without the dnurbs/ prefix:" >&2
  echo "$unprefixed" >&2
  status=1
fi
start=$(date +%s)
log="$(mktemp)"
# The build's precompiled headers are g++'s, which clang cannot read: clang-tidy parses every
# file from its own includes instead (so a file that leans on the precompiled header for an
# include it lacks fails here)
database="$(mktemp -d)"
trap 'rm -rf "$log" "$database"' EXIT
sed -E 's# -Winvalid-pch##g; s# -include [^ ]*cmake_pch\.hxx##g' "$build/compile_commands.json" \
  >"$database/compile_commands.json"
find "${existing[@]}" -name '*.cpp' | sort |
  xargs -P "$jobs" -n 4 clang-tidy -p "$database" --quiet --warnings-as-errors='*' >"$log" 2>&1 ||
  status=1
if grep -E "(warning|error):" "$log" >/dev/null; then
  grep -E -A3 "(warning|error):" "$log" >&2
  status=1
fi
echo "clang_tidy_check: $(find "${existing[@]}" -name '*.cpp' | wc -l) files in $(( $(date +%s) - start )) s, exit $status"
exit "$status"
