#!/usr/bin/env bash
# Configures and builds the release preset (build/release): every target, or the targets given
# (`bash scripts/build.sh exemplar` builds the command alone).
# With ccache installed (scripts/install-deps.sh installs it), compilations are cached across
# build folders and clones on this machine: paths are hashed relative to the repository, so a
# fresh clone elsewhere (CI's copy in /tmp) reuses what an earlier build compiled.
set -euo pipefail
cd "$(dirname "$0")/.."
launcher=()
if command -v ccache > /dev/null; then
  export CCACHE_BASEDIR=$PWD CCACHE_NOHASHDIR=true
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
cmake --preset release "${launcher[@]}" > /dev/null
if (($# > 0)); then
  cmake --build --preset release --target "$@"
else
  cmake --build --preset release
fi
