#!/usr/bin/env bash
# Configures and builds impactfe (Release) into build/ (ccache is used when it is installed).
# usage: scripts/build.sh [TARGET ...]   no target: everything (program, tests, benchmarks);
#        scripts/build.sh impactfe       the program alone (the README's main job)
set -euo pipefail
cd "$(dirname "$0")/.."
launcher=()
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}"
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build build -j "$(nproc)" "${targets[@]}"
