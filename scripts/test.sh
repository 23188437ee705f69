#!/usr/bin/env bash
# Builds impactfe and runs the whole test suite: formatting and layer checks, ctest (Release),
# then the suite again under AddressSanitizer + UndefinedBehaviorSanitizer
# (scripts/test-sanitizers.sh, build-asan/) and a one-minute fuzzing run of the deck reader
# (scripts/fuzz.sh, same build). RUN_SANITIZERS=0 / RUN_FUZZ=0 skip those two (a quick local
# check); CI runs everything (docs/reliability.md: ~12 min for the sanitizer suite on 2 cores).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/check-format.sh
python3 scripts/check-layers.py
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "$(nproc)"
if [ "${RUN_SANITIZERS:-1}" = 1 ]; then bash scripts/test-sanitizers.sh; fi
if [ "${RUN_FUZZ:-1}" = 1 ]; then bash scripts/fuzz.sh "${FUZZ_SECONDS:-60}"; fi
