#!/usr/bin/env bash
# Installs the Debian 12 packages dnurbs needs, only those that are missing.
# Run as root (or with sudo available). Safe to run again.
set -euo pipefail

packages=(
  build-essential cmake git pkg-config
  ninja-build            # the build tool of scripts/build.sh (less overhead than make on a
                         # full build, and one scheduler across all targets)
  libeigen3-dev          # linear algebra (dense and sparse)
  libnlopt-cxx-dev       # optimization (design and fitting)
  libassimp-dev          # mesh export and import
  nlohmann-json3-dev     # shape and scene files (JSON)
  libcli11-dev           # the dnurbs command's options (tools/command_line.h; header-only)
  libsuitesparse-dev     # CHOLMOD: supernodal sparse Cholesky for large blocks (core/sparse_cholesky.h)
  libopenblas-dev        # fast BLAS under CHOLMOD's supernodes (Debian's alternatives switch
                         # libblas.so.3 to OpenBLAS; dnurbs pins it to one thread at run time)
  libpng-dev             # vision/: PNG images for T-snakes (libpng's simplified API)
  zlib1g-dev             # vision/: gzip-encoded NRRD volumes for T-surfaces
  libgtest-dev libgmock-dev
  clang-tidy clang-format  # CI's style checks (scripts/clang_tidy_check.sh)
  # clang with its sanitizer and libFuzzer runtimes: CI's sanitizer build and the fuzz targets
  # (scripts/sanitize_check.sh, scripts/fuzz.sh)
  clang libclang-rt-14-dev
  libbenchmark-dev       # bench/
  python3 python3-matplotlib python3-numpy  # PNG previews and bench plots
  # The Python module (python/, docs/python.md): pybind11 bindings built against the
  # interpreter's headers; SciPy for sparse matrices out of it, pytest for its tests
  python3-dev pybind11-dev python3-scipy python3-pytest
  # `dnurbs serve` (sculpt/, docs/serve.md): Boost.Beast for HTTP and WebSocket (header-only),
  # three.js r111 for the page (served from /usr/share/javascript/three, never fetched), and
  # Chromium for the browser tests (tests/web)
  libboost-dev libjs-three chromium
  # CAD exchange (cad/, docs/cad-exchange.md): Open CASCADE's STEP and IGES translators
  libocct-data-exchange-dev
)
# Node.js runs the browser tests; a machine may already have it from elsewhere (NodeSource)
if ! command -v node >/dev/null 2>&1; then
  packages+=(nodejs npm)
fi

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -gt 0 ]; then
  echo "dnurbs: installing ${missing[*]}"
  sudo_prefix=""
  if [ "$(id -u)" -ne 0 ]; then
    sudo_prefix="sudo"
  fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo_prefix apt-get update -qq
  $sudo_prefix apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The browser tests' npm packages (playwright-core, ws, pngjs), pinned by package-lock.json
web_tests="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/tests/web"
if [ -f "$web_tests/package-lock.json" ] &&
   { [ ! -d "$web_tests/node_modules" ] ||
     [ "$web_tests/package-lock.json" -nt "$web_tests/node_modules" ]; }; then
  echo "dnurbs: installing the npm packages of tests/web"
  (cd "$web_tests" && npm ci --no-audit --no-fund --loglevel=error && touch node_modules)
fi
