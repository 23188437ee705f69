#!/usr/bin/env bash
# Configures the sanitizer build shared by scripts/test-sanitizers.sh (the whole test suite under
# AddressSanitizer + UndefinedBehaviorSanitizer) and scripts/fuzz.sh (the libFuzzer harness):
# clang-14 with -fsanitize=fuzzer-no-link,address,undefined in one build directory
# (SANITIZER_BUILD_DIR, default build-asan/; benchmarks off), so that CI compiles the library
# once for both. The fuzzer-no-link coverage instrumentation costs the tests little; without
# the fuzzer's main it only counts. -O2 (not -O1): Eigen's fixed-size kernels left out of line
# made the co-rotational tests 80x slower than Release; line tables only keep the binaries
# small. Library templates are not coverage-instrumented (scripts/fuzz-coverage-ignorelist.txt).
# SANITIZERS (default "address,undefined") picks the runtime checks: a long fuzzing run may use
# "undefined" alone in its own SANITIZER_BUILD_DIR, several times faster (docs/reliability.md).
# Sourced, not run: sets $sanitizer_build.
set -euo pipefail
sanitizer_build="${SANITIZER_BUILD_DIR:-build-asan}"
if ! command -v clang++-14 >/dev/null 2>&1; then
  echo "clang++-14 is missing: run scripts/install-deps.sh" >&2
  exit 1
fi
sanitize="-fsanitize=fuzzer-no-link,${SANITIZERS:-address,undefined} -fno-sanitize-recover=undefined"
sanitize+=" -fsanitize-coverage-ignorelist=$(pwd)/scripts/fuzz-coverage-ignorelist.txt"
launcher=()
if command -v ccache >/dev/null 2>&1; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S . -B "$sanitizer_build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
  -DCMAKE_CXX_FLAGS="$sanitize -fno-omit-frame-pointer" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only" \
  -DIMPACTFE_BUILD_TESTS=ON -DIMPACTFE_BUILD_BENCH=OFF -DIMPACTFE_BUILD_FUZZERS=ON \
  "${launcher[@]}" >/dev/null
