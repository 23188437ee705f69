#!/usr/bin/env bash
# Runs the whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer: the sanitizer
# build (scripts/sanitizer-build.sh: clang-14 -O2, build-asan/, shared with scripts/fuzz.sh),
# then ctest there. A sanitizer report exits with status 86, which no test expects (the
# malformed and verification decks expect 0, 1 or 2), so a report always fails its test.
# Tests left out are listed in EXCLUDE with the reason.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/sanitizer-build.sh
cmake --build "$sanitizer_build" -j "$(nproc)"

export ASAN_OPTIONS="detect_leaks=1:exitcode=86:abort_on_error=0:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:exitcode=86"
# HDF5's own lost free-list blocks (scripts/lsan-suppressions.txt says why).
export LSAN_OPTIONS="suppressions=$(pwd)/scripts/lsan-suppressions.txt"
# EXCLUDE: ctest regular expression of the tests left out, with the reason:
# - python.test_terminal and python.test_explicit_dynamics: 370 of the suite's 1650 CPU seconds
#   under the sanitizers (6 min on 2 cores), dozens of CLI runs of decks that the C++ unit,
#   verification and malformed-deck tests already run under the sanitizers; they check the
#   terminal text and the Python reader, and run in the Release suite.
EXCLUDE="${EXCLUDE-^python\.(test_terminal|test_explicit_dynamics)$}"
# Tests that start Open MPI (the MUMPS module) run without LeakSanitizer: Open MPI's components,
# loaded with dlopen and closed at MPI_Finalize, keep allocations until exit, and their stacks
# lose the module names, so no suppression can match them. Address and UB checks stay on.
MPI_TESTS='^(mpi\.|MumpsSolver\.)'
args=(--test-dir "$sanitizer_build" --output-on-failure -j "$(nproc)")
exclude="$MPI_TESTS"
if [ -n "$EXCLUDE" ]; then exclude="$exclude|$EXCLUDE"; fi
ctest "${args[@]}" -E "$exclude"
mpi_args=(-R "$MPI_TESTS")
if [ -n "$EXCLUDE" ]; then mpi_args+=(-E "$EXCLUDE"); fi
# The MUMPS comparisons run on 2 ranks only (IMPACTFE_MPI_RANKS): the sanitizers look for memory
# errors, which one distributed run exercises; the Release suite checks 1, 2 and 4 ranks. Each
# rank count is two runs of the model, minutes under the sanitizers.
IMPACTFE_MPI_RANKS=2 ASAN_OPTIONS="${ASAN_OPTIONS/detect_leaks=1/detect_leaks=0}" ctest "${args[@]}" "${mpi_args[@]}"
echo "sanitizers: ok"
