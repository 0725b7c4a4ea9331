#!/bin/sh
# Makes the pictures of examples/paint (README.md) with the built command; run from anywhere:
#   sh examples/paint/run.sh [path/to/exemplar]
set -e
X=${1:-$(cd "$(dirname "$0")/../.." && pwd)/build/release/exemplar}
cd "$(dirname "$0")"
# A crayon stroke scan (RGBA: its ragged edge is the shape) painted along new strokes.
"$X" paint --source crayon_red.png --strokes crayon_strokes.json --width 640 --height 260 \
  -o crayon.png -q
# The Starry Night's sky along three strokes: the paper's plain EM, then uniform patch usage.
for usage in none uniform; do
  "$X" paint --source starry_sky.png --source-mask starry_sky_mask.png --strokes starry_strokes.json --width 640 --height 360 \
    --usage $usage -o starry_$usage.png --save-directions starry_directions.png -q
done
# Two textures and their segmentation; the SVG's stroke colours name the segments.
"$X" paint --source bark_leaves.png --source-labels bark_leaves_segments.png --strokes tree.svg \
  --width 400 --height 400 --usage uniform -o tree.png -q
"$X" paint --source bark_leaves.png --source-mask bark_leaves_mask.png --strokes tree.svg --width 400 --height 400 \
  --usage uniform -o tree_no_labels.png -q
