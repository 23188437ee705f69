#!/usr/bin/env bash
# Builds impactfe and runs the Release test suite: formatting and layer checks, then ctest
# (unit, verification, regression, Verification Manual acceptance set, Python, report, MPI).
# The sanitizer suite and the fuzzer are separate (scripts/test-sanitizers.sh, scripts/fuzz.sh);
# .ci/run runs all three.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/check-format.sh
python3 scripts/check-layers.py
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "$(nproc)"
