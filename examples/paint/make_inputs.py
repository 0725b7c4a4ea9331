"""Makes the exemplars of examples/paint from the sources named in README.md (the project's
../shared/data folder; not needed to run the example, whose inputs are committed)."""
import sys

import numpy as np
from PIL import Image

DATA = sys.argv[1] if len(sys.argv) > 1 else "../../../shared/data/"

# A crayon stroke scan as an RGBA exemplar: crayon red, alpha = the scan's coverage.
scan = np.asarray(Image.open(DATA + "strokes/gimpressionist-brushes/crayon04.pgm").convert("L"))
scan = scan.astype(float) / 255
rgb = np.zeros(scan.shape + (3,))
rgb[...] = (0.78, 0.16, 0.12)
rgb *= (0.75 + 0.25 * scan)[..., None]
rgba = np.dstack([rgb, np.clip(scan * 1.15, 0, 1)])
Image.fromarray(np.round(rgba * 255).astype(np.uint8), "RGBA").save("crayon_red.png")

# A crop of The Starry Night's sky.
starry = Image.open(DATA + "style/neural-style/starry_night.jpg").convert("RGB")
starry.crop((300, 60, 560, 230)).save("starry_sky.png")
# Opaque: the whole crop is texture, no boundary (an all-white --source-mask says so).
Image.new("L", (260, 170), 255).save("starry_sky_mask.png")

# Two textures, bark (left) and leaves (right), tiled and cut along a wavy line; the
# segmentation in two colours, #804000 bark and #00a000 leaves.
bark = np.asarray(Image.open(DATA + "textures/gimp-patterns/bark.png").convert("RGB"))
leaves = np.asarray(Image.open(DATA + "textures/gimp-patterns/leaves.png").convert("RGB"))
W, H = 200, 150


def tile(t):
    return np.tile(t, (H // t.shape[0] + 1, W // t.shape[1] + 1, 1))[:H, :W]


y, x = np.mgrid[0:H, 0:W]
left = x < 92 + 10 * np.sin(y / 13.0)
Image.fromarray(np.where(left[..., None], tile(bark), tile(leaves)).astype(np.uint8)).save(
    "bark_leaves.png")
segments = np.zeros((H, W, 3), np.uint8)
segments[left] = (128, 64, 0)
segments[~left] = (0, 160, 0)
Image.fromarray(segments).save("bark_leaves_segments.png")
# Without the segmentation the whole exemplar is one opaque texture: an all-white mask.
Image.new("L", (W, H), 255).save("bark_leaves_mask.png")
