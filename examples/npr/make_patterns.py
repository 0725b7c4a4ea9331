"""Makes the example patterns of `exemplar npr` (docs/npr.md, "Patterns"):

- stipple.png: a stipple screen, the distance to the nearest of Poisson-disc points (dart
  throwing on the torus, minimum distance 6 px) divided by 6, clamped to 1: thresholding it at
  t gives round dots that grow with t (tests/npr/npr_patterns.hpp makes the same kind);
- halftone.png: a clustered-dot halftone screen, 0.5 + 0.25 (cos x + cos y), period 8 px;
- hatch.png: hatching composed from real crayon strokes, the GIMPressionist scans crayon01,
  crayon02 and crayon04 (white strokes on black, 230-260 x 40-50 px): each placed many times,
  scaled to 70-130 x 4.5 px, turned by up to 3 degrees, in rows 8 px apart with random offsets,
  wrapped around (tileable), ink composited as 1 - (1 - a)(1 - b); dark strokes on white.

Usage: python3 make_patterns.py BRUSH_DIR OUT_DIR
BRUSH_DIR holds the scans (Debian gimp-data: /usr/share/gimp/2.0/gimpressionist/Brushes).
Needs numpy and exemplar (PYTHONPATH=build/release/python). Deterministic (seeded).
"""
import pathlib
import sys

import numpy as np

import exemplar


def stipple(size=128, spacing=6.0, seed=7):
    rng = np.random.default_rng(seed)
    dots = []
    n = float(size)
    for _ in range(int(30 * n * n / spacing**2)):
        x, y = rng.random() * n, rng.random() * n
        near = False
        for dx, dy in dots:
            ex, ey = abs(x - dx), abs(y - dy)
            ex, ey = min(ex, n - ex), min(ey, n - ey)
            if ex * ex + ey * ey < spacing * spacing:
                near = True
                break
        if not near:
            dots.append((x, y))
    yy, xx = np.mgrid[0:size, 0:size] + 0.5
    image = np.ones((size, size))
    for dx, dy in dots:
        ex, ey = np.abs(xx - dx), np.abs(yy - dy)
        ex, ey = np.minimum(ex, n - ex), np.minimum(ey, n - ey)
        image = np.minimum(image, np.sqrt(ex * ex + ey * ey) / spacing)
    return image


def halftone(size=128, period=8):
    y, x = np.mgrid[0:size, 0:size] * (2 * np.pi / period)
    return 0.5 + 0.25 * (np.cos(x) + np.cos(y))


def bilinear(image, x, y):
    """image sampled at float coordinates (0 outside)."""
    h, w = image.shape
    x0, y0 = np.floor(x).astype(int), np.floor(y).astype(int)
    fx, fy = x - x0, y - y0
    out = np.zeros_like(x)
    for dy, wy in ((0, 1 - fy), (1, fy)):
        for dx, wx in ((0, 1 - fx), (1, fx)):
            xi, yi = x0 + dx, y0 + dy
            inside = (xi >= 0) & (yi >= 0) & (xi < w) & (yi < h)
            out += np.where(inside, image[np.clip(yi, 0, h - 1), np.clip(xi, 0, w - 1)], 0) * wx * wy
    return out


def hatch(strokes, size=256, period=8, thickness=4.5, seed=3):
    rng = np.random.default_rng(seed)
    ink = np.zeros((size, size))
    for row in range(size // period):
        x = rng.random() * size
        for _ in range(8):  # strokes along the row, overlapping
            stroke = strokes[rng.integers(len(strokes))]
            sh, sw = stroke.shape
            length = 70 + 60 * rng.random()
            angle = np.radians(rng.uniform(-3, 3))
            cy = row * period + period / 2 + rng.uniform(-1, 1)
            cx = x + length / 2
            x += length * rng.uniform(0.55, 0.9)
            # The stroke's box in the image, wrapped around
            reach = int(length / 2 + thickness) + 2
            ys, xs = np.mgrid[-reach:reach + 1, -reach:reach + 1]
            px, py = xs + np.floor(cx) + 0.5 - cx, ys + np.floor(cy) + 0.5 - cy
            # Into the stroke's frame: along (u) and across (v)
            u = np.cos(angle) * px + np.sin(angle) * py
            v = -np.sin(angle) * px + np.cos(angle) * py
            a = bilinear(stroke, (u / length + 0.5) * sw - 0.5, (v / thickness + 0.5) * sh - 0.5)
            rows = (ys + int(np.floor(cy))) % size
            cols = (xs + int(np.floor(cx))) % size
            ink[rows, cols] = 1 - (1 - ink[rows, cols]) * (1 - a)
    return 1 - ink


def main():
    brushes, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    out.mkdir(parents=True, exist_ok=True)
    strokes = [exemplar.load_image(str(brushes / f"{name}.pgm"))[..., 0].astype(np.float64)
               for name in ("crayon01", "crayon02", "crayon04")]
    for name, image in (("stipple", stipple()), ("halftone", halftone()), ("hatch", hatch(strokes))):
        grey = np.round(np.clip(image, 0, 1) * 255).astype(np.uint8)[..., None]
        exemplar.save_image(grey, str(out / f"{name}.png"))
        print(out / f"{name}.png")


if __name__ == "__main__":
    main()
