#!/usr/bin/env bash
# Fails when a C++ source differs from .clang-format.
set -euo pipefail
cd "$(dirname "$0")/.."
files=$(git ls-files '*.cpp' '*.h' 2>/dev/null || find src tests bench -name '*.cpp' -o -name '*.h')
[ -z "$files" ] && exit 0
clang-format --dry-run --Werror $files
echo "format check: ok"
