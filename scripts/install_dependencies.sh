#!/usr/bin/env bash
# Installs the Debian 12 packages dnurbs needs, only those that are missing.
# Run as root (or with sudo available). Safe to run again.
set -euo pipefail

packages=(
  build-essential cmake git pkg-config
  libeigen3-dev          # linear algebra (dense and sparse)
  libnlopt-cxx-dev       # optimization (design and fitting)
  libassimp-dev          # mesh export and import
  nlohmann-json3-dev     # shape and scene files (JSON)
  libsuitesparse-dev     # CHOLMOD: supernodal sparse Cholesky for large blocks (core/sparse_cholesky.h)
  libopenblas-dev        # fast BLAS under CHOLMOD's supernodes (Debian's alternatives switch
                         # libblas.so.3 to OpenBLAS; dnurbs pins it to one thread at run time)
  libpng-dev             # vision/: PNG images for T-snakes (libpng's simplified API)
  zlib1g-dev             # vision/: gzip-encoded NRRD volumes for T-surfaces
  libgtest-dev libgmock-dev
  clang-tidy clang-format  # CI's style checks (scripts/clang_tidy_check.sh)
  libbenchmark-dev       # bench/
  python3 python3-matplotlib python3-numpy  # PNG previews and bench plots
  # The Python module (python/, docs/python.md): pybind11 bindings built against the
  # interpreter's headers; SciPy for sparse matrices out of it, pytest for its tests
  python3-dev pybind11-dev python3-scipy python3-pytest
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "dnurbs: installing ${missing[*]}"
sudo_prefix=""
if [ "$(id -u)" -ne 0 ]; then
  sudo_prefix="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$sudo_prefix apt-get update -qq
$sudo_prefix apt-get install -y -qq --no-install-recommends "${missing[@]}"
