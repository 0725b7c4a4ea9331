#!/usr/bin/env bash
# Configures and builds the release preset (build/release): every target, or the targets given
# (`bash scripts/build.sh exemplar` builds the command alone).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset release > /dev/null
if (($# > 0)); then
  cmake --build --preset release --target "$@"
else
  cmake --build --preset release
fi
