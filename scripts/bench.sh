#!/usr/bin/env bash
# The whole benchmark in one command (bench/README.md): installs the dependencies, builds Release
# into build-bench, runs dnurbs-bench, evaluation_bench and test_hardcase (when those targets
# exist), then bench/plot_results.py, which writes bench/RESULTS.md and bench/results/*.png.
# CSV and XML files stay in build-bench/bench-results. Usage: scripts/bench.sh [--quick]
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${root}/build-bench"
data="${build}/bench-results"
quick=()
if [ "${1:-}" = "--quick" ]; then
  quick=(--quick)
fi

"${root}/scripts/install_dependencies.sh"
# OpenCASCADE for the evaluation and closest-point comparisons: optional. Geom (TKG3d) is in
# modeling-data; GeomAPI_ProjectPointOnCurve/_OnSurf (TKGeomAlgo) in modeling-algorithms.
sudo_prefix=""
if [ "$(id -u)" -ne 0 ]; then
  sudo_prefix="sudo"
fi
${sudo_prefix} apt-get install -y libocct-modeling-data-dev libocct-modeling-algorithms-dev \
  >/dev/null 2>&1 ||
  echo "bench.sh: OCCT packages not available; evaluation and closest-point benches run without OCCT"

launcher=()
if command -v ccache >/dev/null 2>&1; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
cmake -S "${root}" -B "${build}" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >/dev/null
jobs="$(nproc)"
cmake --build "${build}" --target dnurbs_bench -j"${jobs}"
for optional in spring_step_bench free_step_bench floor_bench normal_step_bench face_refinement_bench evaluation_bench closest_point_bench test_hardcase; do
  cmake --build "${build}" --target "${optional}" -j"${jobs}" >/dev/null 2>&1 ||
    echo "bench.sh: target ${optional} not built (absent or failing); its table is skipped"
done

mkdir -p "${data}"
rm -f "${data}"/*.csv "${data}"/*.xml
start=$(date +%s)
status=0
"${build}/bench/dnurbs-bench" --out "${data}" "${quick[@]}" ||
  { status=$?; echo "bench.sh: dnurbs-bench exceeded a bound (see BOUND EXCEEDED above)"; }
springs="$(find "${build}/bench" -maxdepth 3 -type f -name spring_step_bench -perm -u+x | head -n 1)"
if [ -n "${springs}" ]; then
  if [ "${#quick[@]}" -gt 0 ]; then
    "${springs}" --out "${data}" --quick || { status=$?; echo "bench.sh: spring_step_bench failed"; }
  else
    "${springs}" --out "${data}" || { status=$?; echo "bench.sh: spring_step_bench failed"; }
  fi
fi
free_weights="$(find "${build}/bench" -maxdepth 3 -type f -name free_step_bench -perm -u+x | head -n 1)"
if [ -n "${free_weights}" ]; then
  "${free_weights}" --out "${data}" "${quick[@]}" || { status=$?; echo "bench.sh: free_step_bench failed"; }
fi
floor="$(find "${build}/bench" -maxdepth 3 -type f -name floor_bench -perm -u+x | head -n 1)"
if [ -n "${floor}" ]; then
  if [ "${#quick[@]}" -gt 0 ]; then
    "${floor}" --out "${data}" --quick || { status=$?; echo "bench.sh: floor_bench failed"; }
  else
    "${floor}" --out "${data}" || { status=$?; echo "bench.sh: floor_bench failed"; }
  fi
fi
normals="$(find "${build}/bench" -maxdepth 3 -type f -name normal_step_bench -perm -u+x | head -n 1)"
if [ -n "${normals}" ]; then
  "${normals}" --out "${data}" "${quick[@]}" || { status=$?; echo "bench.sh: normal_step_bench failed"; }
fi
face="$(find "${build}/bench" -maxdepth 3 -type f -name face_refinement_bench -perm -u+x | head -n 1)"
if [ -n "${face}" ]; then
  "${face}" --out "${data}" "${quick[@]}" || { status=$?; echo "bench.sh: face_refinement_bench failed"; }
fi
evaluation="$(find "${build}/bench" -maxdepth 3 -type f -name evaluation_bench -perm -u+x | head -n 1)"
if [ -n "${evaluation}" ]; then
  "${evaluation}" --out "${data}" || { status=$?; echo "bench.sh: evaluation_bench failed"; }
fi
closest="$(find "${build}/bench" -maxdepth 3 -type f -name closest_point_bench -perm -u+x | head -n 1)"
if [ -n "${closest}" ]; then
  "${closest}" --out "${data}" || { status=$?; echo "bench.sh: closest_point_bench missed minima"; }
fi
hardcase="$(find "${build}/tests" -maxdepth 3 -type f -name test_hardcase -perm -u+x | head -n 1)"
if [ -n "${hardcase}" ]; then
  "${hardcase}" --gtest_output="xml:${data}/hardcase.xml" >/dev/null ||
    { status=$?; echo "bench.sh: test_hardcase has failing tests (pass column of RESULTS.md)"; }
fi
/usr/bin/python3 "${root}/bench/plot_results.py" --data "${data}" --plots "${root}/bench/results" \
  --markdown "${root}/bench/RESULTS.md"
echo "bench.sh: benchmarks ran in $(($(date +%s) - start)) s (build not counted); exit ${status}"
echo "bench.sh: bench/RESULTS.md, bench/results/*.png; CSV in ${data}"
exit "${status}"
