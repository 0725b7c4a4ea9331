#!/usr/bin/env bash
# README command 1: install what is missing, build, and run the main job on bundled data.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
mkdir -p out
./build/release/exemplar stylize --config examples/stylit/job.json --output out/stylit.png
