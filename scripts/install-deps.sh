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
  libcli11-dev libfmt-dev libhdf5-dev \
  libgtest-dev libgmock-dev libbenchmark-dev \
  clang-format python3 nlohmann-json3-dev chromium fonts-dejavu-core \
  clang-14 libclang-rt-14-dev libomp-14-dev
# clang-14 with compiler-rt (libFuzzer, sanitizers) and its OpenMP runtime build the fuzzing
# harness (scripts/fuzz.sh); gcc's own sanitizers serve scripts/test-sanitizers.sh.
# node and npm fetch the report page's libraries at build time (report/package-lock.json); the
# machine image may already carry a newer node, which is kept.
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  $SUDO apt-get install -y --no-install-recommends nodejs npm
fi
