#!/usr/bin/env bash
# Fails if any C++ file differs from clang-format's output.
set -euo pipefail
cd "$(dirname "$0")/.."
files=$(git ls-files '*.cpp' '*.hpp' 2>/dev/null || find include src apps tests bench python -name '*.[ch]pp')
if [[ -z "$files" ]]; then exit 0; fi
if ! clang-format --dry-run --Werror $files; then
  echo "exemplar: run 'clang-format -i' on the files above" >&2
  exit 1
fi
