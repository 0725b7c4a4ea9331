#!/usr/bin/env bash
# README command 2: install what is missing, build, check formatting, run the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
bash scripts/check-format.sh
ctest --preset release --output-on-failure -j2
