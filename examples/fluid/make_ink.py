#!/usr/bin/env python3
"""Makes ink.png, the RGBA exemplar of this example, from an ink-in-water photo.

Source: EmbarkStudios/texture-synthesis, imgs/multiexample/2.jpg (400x400, MIT or Apache-2.0).
The photo has no alpha, so alpha comes from the background (LazyFluids needs an RGBA exemplar):
the background colour is the median of the darkest 5% of pixels, and alpha ramps from 0 to 1 as
a pixel's RGB distance to it goes from 0.08 to 0.35. The result is halved (2x2 box average of
premultiplied colour) to 200x200. Needs python3-numpy and python3-pil.

    python3 examples/fluid/make_ink.py PATH/TO/2.jpg examples/fluid/ink.png
"""
import sys

import numpy as np
from PIL import Image

photo = np.asarray(Image.open(sys.argv[1]).convert("RGB")).astype(np.float64) / 255
luminance = photo.mean(axis=2)
background = np.median(photo[luminance < np.quantile(luminance, 0.05)], axis=0)
distance = np.sqrt(((photo - background) ** 2).sum(axis=2))
alpha = np.clip((distance - 0.08) / (0.35 - 0.08), 0, 1)

h, w = alpha.shape
premultiplied = photo * alpha[..., None]
box = lambda a: a.reshape(h // 2, 2, w // 2, 2, *a.shape[2:]).mean(axis=(1, 3))
alpha_half = box(alpha)
colour_half = box(premultiplied) / np.maximum(alpha_half, 1e-6)[..., None]
rgba = np.dstack([np.clip(colour_half, 0, 1), alpha_half])
Image.fromarray((rgba * 255 + 0.5).astype(np.uint8), "RGBA").save(sys.argv[2])
