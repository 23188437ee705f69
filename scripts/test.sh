#!/usr/bin/env bash
# Builds impactfe and runs the whole test suite (formatting check + ctest).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/check-format.sh
python3 scripts/check-layers.py
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "$(nproc)"
