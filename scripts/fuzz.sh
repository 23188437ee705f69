#!/usr/bin/env bash
# Fuzzes the deck reader and model builder with libFuzzer (tests/fuzz/fuzz_deck.cpp): builds the
# harness in the sanitizer build (scripts/sanitizer-build.sh: clang-14, AddressSanitizer and
# UndefinedBehaviorSanitizer, build-asan/), seeds it with the thesis, example, verification and
# malformed decks and fuzzes for SECONDS (default 60; scripts/test.sh runs it). Any crash,
# sanitizer report, untranslated exception, error without FILE:LINE or input slower than one
# second fails the script and leaves the input in $build/fuzz-artifacts/ (turn it into a
# malformed deck, tests/decks/malformed/). The corpus grows in $build/fuzz-corpus/.
#
# usage: scripts/fuzz.sh [SECONDS]        e.g. FUZZ_ARGS="-runs=10000000" scripts/fuzz.sh 0
# A long local run: nice -n 19 scripts/fuzz.sh 0 with FUZZ_ARGS="-runs=N" (one worker).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
source scripts/sanitizer-build.sh
build="$(pwd)/$sanitizer_build"  # absolute: the harness works in a temporary directory
cmake --build "$build" --target fuzz_deck -j "$(nproc)"

# Seeds: every deck of the repository (a fresh copy, so a deleted deck does not linger) but the
# benchmark models of tests/decks/bench/: hertz_graded.inp builds 12,167 nodes through ~10⁵
# interpreted *DO commands, 1.9 s under the sanitizers, so it and its mutations only time out.
rm -rf "$build/fuzz-seeds"
mkdir -p "$build/fuzz-seeds" "$build/fuzz-corpus" "$build/fuzz-artifacts"
# Nor the 20-node brick stretched plastically in 50 finite-strain substeps (3.7 s under the
# sanitizers; explicit runs are bounded by the harness's element-cycle budget).
for deck in examples/*.inp tests/decks/*/*.inp tests/verification/*.inp; do
  case "$deck" in
    tests/decks/bench/*) continue ;;
    tests/verification/solid186_nlgeom_plastic_stretch.inp) continue ;;
  esac
  cp "$deck" "$build/fuzz-seeds/$(echo "$deck" | tr '/' '_')"
done

limits=(-timeout=1 -max_len=16384 -rss_limit_mb=2048 -print_final_stats=1
  -artifact_prefix="$build/fuzz-artifacts/")
if [ "$seconds" -gt 0 ]; then limits+=(-max_total_time="$seconds"); fi
# OpenMP: one thread (the harness's models are small; threads only add noise to coverage).
export OMP_NUM_THREADS=1
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$(pwd)/scripts/lsan-suppressions.txt"
# shellcheck disable=SC2086
# tests/fuzz/regressions/ holds the inputs past findings came from (each must now pass in time).
"$build/tests/fuzz/fuzz_deck" "${limits[@]}" ${FUZZ_ARGS:-} "$build/fuzz-corpus" "$build/fuzz-seeds" \
  "$(pwd)/tests/fuzz/regressions"
echo "fuzz: ok (no crash, no timeout)"
