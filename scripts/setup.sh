#!/usr/bin/env bash
# README command 1: install what is missing, build the command, and run the main job on bundled
# data, the last step of the StyLit workflow (docs/stylit.md): render the bundled target scene
# (the Spot mesh on the exemplar's table, under its light) with its light-path buffers, then
# transfer the bundled painting of the exemplar sphere onto it through the exemplar's buffers.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh exemplar
mkdir -p out
S=examples/stylit
echo "exemplar: rendering spot-on-table (600x456, 64 samples per pixel) into out/spot/" >&2
./build/release/exemplar render --scene spot-on-table --width 600 --height 456 --spp 64 \
  --output out/spot --quiet
echo "exemplar: stylizing it with $S/source_style.png" >&2
./build/release/exemplar stylit --exemplar $S/source_style.png \
  --source $S/source_fullgi.png $S/source_dirdif.png $S/source_dirspc.png $S/source_indirb.png \
  --target out/spot --output out/spot_stylized.png
