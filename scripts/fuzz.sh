#!/usr/bin/env bash
# Fuzzes the deck reader and model builder with libFuzzer (tests/fuzz/fuzz_deck.cpp): builds the
# harness with clang-14, AddressSanitizer and UndefinedBehaviorSanitizer in build-fuzz/ (the
# library only, no tests), seeds it with the thesis, example, verification and malformed decks
# and fuzzes for SECONDS (default 60; scripts/test.sh runs it when RUN_FUZZ=1). Any crash,
# sanitizer report, untranslated exception, error without FILE:LINE or input slower than one
# second fails the script and leaves the input in build-fuzz/artifacts/ (turn it into a
# malformed deck, tests/decks/malformed/).
#
# usage: scripts/fuzz.sh [SECONDS]        e.g. FUZZ_ARGS="-runs=10000000" scripts/fuzz.sh 0
# A long local run: nice -n 19 scripts/fuzz.sh 0 with FUZZ_ARGS="-runs=N" (one worker).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
build=build-fuzz
# clang-14 with compiler-rt (libFuzzer, sanitizers) and its OpenMP runtime build the harness.
# They are installed here on demand, not by scripts/install-deps.sh: fuzzing is opt-in, so the
# CI's install time does not carry them (gcc's own sanitizers serve scripts/test-sanitizers.sh).
if ! command -v clang++-14 >/dev/null 2>&1 || ! dpkg -s libclang-rt-14-dev >/dev/null 2>&1 ||
  ! dpkg -s libomp-14-dev >/dev/null 2>&1; then
  sudo_cmd=""
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo_cmd apt-get update
  $sudo_cmd apt-get install -y --no-install-recommends clang-14 libclang-rt-14-dev libomp-14-dev
fi
sanitize="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined"
launcher=()
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
  -DCMAKE_CXX_FLAGS="$sanitize -fno-omit-frame-pointer" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DIMPACTFE_BUILD_TESTS=OFF -DIMPACTFE_BUILD_BENCH=OFF -DIMPACTFE_BUILD_FUZZERS=ON \
  "${launcher[@]}" >/dev/null
cmake --build "$build" --target fuzz_deck -j "$(nproc)"

# Seeds: every deck of the repository (a fresh copy, so a deleted deck does not linger).
rm -rf "$build/seeds"
mkdir -p "$build/seeds" "$build/corpus" "$build/artifacts"
for deck in examples/*.inp tests/decks/*/*.inp tests/verification/*.inp; do
  cp "$deck" "$build/seeds/$(echo "$deck" | tr '/' '_')"
done

limits=(-timeout=1 -max_len=16384 -rss_limit_mb=2048 -print_final_stats=1
  -artifact_prefix="$build/artifacts/")
if [ "$seconds" -gt 0 ]; then limits+=(-max_total_time="$seconds"); fi
# OpenMP: one thread (the harness's models are small; threads only add noise to coverage).
export OMP_NUM_THREADS=1
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# shellcheck disable=SC2086
"$build/tests/fuzz/fuzz_deck" "${limits[@]}" ${FUZZ_ARGS:-} "$build/corpus" "$build/seeds"
echo "fuzz: ok (no crash, no timeout)"
