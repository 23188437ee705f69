#!/usr/bin/env bash
# Builds impactfe and runs the whole test suite (formatting check + ctest). RUN_SANITIZERS=1 also
# runs the suite under AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/), RUN_FUZZ=1 a
# one-minute fuzzing run of the deck reader (build-fuzz/). Both are off until they have been
# run once on the CI machine (issue 12: their time and findings are not measured yet).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/check-format.sh
python3 scripts/check-layers.py
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "$(nproc)"
if [ "${RUN_SANITIZERS:-0}" = 1 ]; then bash scripts/test-sanitizers.sh; fi
if [ "${RUN_FUZZ:-0}" = 1 ]; then bash scripts/fuzz.sh 60; fi
