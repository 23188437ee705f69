#!/usr/bin/env bash
# Installs every build and test dependency of impactfe from Debian packages (run as root).
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update
$SUDO apt-get install -y --no-install-recommends \
  build-essential cmake ninja-build pkg-config \
  libeigen3-dev libsuitesparse-dev libmetis-dev libspectra-dev \
  libcli11-dev libfmt-dev libhdf5-dev libopenblas0-openmp zlib1g-dev libdeflate-dev \
  libgtest-dev libgmock-dev libbenchmark-dev \
  clang-format python3 nlohmann-json3-dev chromium fonts-dejavu-core \
  python3-numpy python3-h5py python3-pandas python3-pytest python3-vtk9 \
  clang-14 libclang-rt-14-dev libomp-14-dev \
  libmumps-dev libopenmpi-dev openmpi-bin libgmsh-dev
# Gmsh: free meshing (MSHAPE,1, non-mappable areas and volumes; src/geometry/free_mesher.cpp).
# MUMPS and Open MPI: the distributed solver (`--solver mumps`, docs/scaling.md).
# clang-14 with compiler-rt (libFuzzer, AddressSanitizer, UBSan) and its OpenMP runtime: the
# sanitizer build of scripts/test-sanitizers.sh and scripts/fuzz.sh (scripts/sanitizer-build.sh).
# node and npm fetch the report page's libraries at build time (report/package-lock.json); the
# machine image may already carry a newer node, which is kept.
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  $SUDO apt-get install -y --no-install-recommends nodejs npm
fi
