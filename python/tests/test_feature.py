"""exemplar.brush and exemplar.fill: the bytes of `exemplar brush` and `exemplar fill`, and the
library's messages as exceptions."""

import json
import subprocess

import numpy as np
import pytest

import exemplar
from conftest import pattern

FEATURE = {"points": [[4, 22], [30, 26], [58, 22]], "width": 12}
PATHS = [
    {"points": [[6, 20], [30, 10], [66, 24]], "width": 10},
    {"points": [[10, 44], [40, 36], [70, 46]], "width": 14},
]


def palette():
    """An RGB uint8 palette with a line feature: a dark band across a striped texture."""
    image = pattern(48, 64, 3, 0.3)
    image[20:27] //= 4
    return np.ascontiguousarray(image)


def region(height, width, box):
    """A white-on-black region image (HxW uint8), white inside the box (x0, y0, x1, y1)."""
    out = np.zeros((height, width), np.uint8)
    x0, y0, x1, y1 = box
    out[y0:y1, x0:x1] = 255
    return out


def png(array):
    return np.round(exemplar.load_image(array) * 255)


def test_brush_is_the_clis(cli, tmp_path):
    exemplar.save_image(palette(), str(tmp_path / "palette.png"))
    canvas = pattern(56, 80, 3, 1.1)
    exemplar.save_image(canvas, str(tmp_path / "canvas.png"))
    (tmp_path / "feature.json").write_text(json.dumps([FEATURE]))
    (tmp_path / "paths.json").write_text(json.dumps(PATHS))
    base = [cli, "brush", "--palette", str(tmp_path / "palette.png"), "--feature",
            str(tmp_path / "feature.json"), "--path", str(tmp_path / "paths.json"), "--seed", "3",
            "--sample-spacing", "1.5", "--threads", "2", "-q"]
    subprocess.run(base + ["--width", "80", "--height", "56", "-o", str(tmp_path / "a.png")],
                   check=True)
    subprocess.run(base + ["--canvas", str(tmp_path / "canvas.png"), "--no-snap", "--walk",
                           "looping", "--brush-width", "9", "-o", str(tmp_path / "b.png")],
                   check=True)
    paths = [dict(p, points=np.array(p["points"], np.float64)) for p in PATHS]
    a = exemplar.brush(palette(), FEATURE, paths, width=80, height=56, seed=3,
                       sample_spacing=1.5, threads=2)
    assert a.shape == (56, 80, 4) and a.dtype == np.uint8
    np.testing.assert_array_equal(a, png(str(tmp_path / "a.png")))
    assert a[..., 3].max() == 255 and a[0, 0, 3] == 0  # painted, and not everywhere
    b = exemplar.brush(palette(), FEATURE, PATHS, canvas=canvas, snap=False, walk="looping",
                       brush_width=9, seed=3, sample_spacing=1.5, threads=2)
    np.testing.assert_array_equal(b, png(str(tmp_path / "b.png")))
    assert not np.array_equal(a[..., :3], b[..., :3])


def test_brush_refuses_what_the_library_refuses():
    with pytest.raises(exemplar.InvalidArgumentError, match="^paths: none given"):
        exemplar.brush(palette(), FEATURE, [], width=80, height=56)
    with pytest.raises(TypeError, match="^feature: needs 'points'"):
        exemplar.brush(palette(), {"width": 12}, PATHS, width=80, height=56)
    with pytest.raises(exemplar.InvalidArgumentError, match="^sample-spacing"):
        exemplar.brush(palette(), FEATURE, PATHS, width=80, height=56, sample_spacing=0)
    with pytest.raises(exemplar.InvalidArgumentError, match="walk"):
        exemplar.brush(palette(), FEATURE, PATHS, width=80, height=56, walk="spiral")
    with pytest.raises(TypeError, match="unexpected keyword argument 'usage'"):
        exemplar.brush(palette(), FEATURE, PATHS, width=80, height=56, usage="none")


def test_fill_is_the_clis(cli, tmp_path):
    source = region(48, 64, (8, 4, 40, 30))
    target = region(40, 52, (10, 8, 34, 30))
    canvas = pattern(40, 52, 3, 2.0)
    for name, image in [("palette", palette()), ("source", source), ("target", target),
                        ("canvas", canvas)]:
        exemplar.save_image(image if image.ndim == 3 else image[..., None],
                            str(tmp_path / f"{name}.png"))
    base = [cli, "fill", "--palette", str(tmp_path / "palette.png"), "--source-region",
            str(tmp_path / "source.png"), "--target-region", str(tmp_path / "target.png"),
            "--seed", "5", "--rotations", "3", "--threads", "2", "-q"]
    subprocess.run(base + ["--canvas", str(tmp_path / "canvas.png"), "-o",
                           str(tmp_path / "a.png")], check=True)
    subprocess.run(base + ["--usage", "none", "-o", str(tmp_path / "b.png")], check=True)
    a = exemplar.fill(palette(), source, target, canvas=canvas, seed=5, rotations=3, threads=2)
    assert a.shape == (40, 52, 3) and a.dtype == np.uint8
    np.testing.assert_array_equal(a, png(str(tmp_path / "a.png")))
    np.testing.assert_array_equal(a[:8], canvas[:8])  # outside the region: the canvas's
    b = exemplar.fill(palette(), source, target, usage="none", seed=5, rotations=3, threads=2)
    assert b.shape == (40, 52, 4)
    np.testing.assert_array_equal(b, png(str(tmp_path / "b.png")))
    assert b[0, 0, 3] == 0 and b[20, 20, 3] == 255


def test_fill_refuses_what_the_library_refuses():
    source = region(48, 64, (8, 4, 40, 30))
    target = region(40, 52, (10, 8, 34, 30))
    with pytest.raises(exemplar.InvalidArgumentError, match="^source region: is 64x40"):
        exemplar.fill(palette(), source[:40], target)
    with pytest.raises(exemplar.InvalidArgumentError, match="^patch-size: 4 is invalid"):
        exemplar.fill(palette(), source, target, patch_size=4)
    with pytest.raises(exemplar.InvalidArgumentError, match="^palette: has 2 channels"):
        exemplar.fill(np.ascontiguousarray(palette()[..., :2]), source, target)
    with pytest.raises(exemplar.Cancelled):
        exemplar.fill(palette(), source, target, progress=lambda p: False)


DRAWING = """<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 60 40">
  <rect x="10" y="8" width="40" height="24" fill="#0000ff"/>
  <g fill="none" stroke="black" stroke-width="5">
    <path d="M4 20 C20 6 40 34 56 20"/>
  </g>
</svg>"""


def style_palette(tmp_path, fills='{"#0000ff": "paper"}'):
    """A style palette file beside palette.png: one line and one area feature."""
    exemplar.save_image(palette(), str(tmp_path / "palette.png"))
    (tmp_path / "style.json").write_text(
        '{"palette": "palette.png", '
        '"line_features": {"band": {"path": [[4, 23], [58, 23]], "width": 10}}, '
        '"area_features": {"paper": {"polygon": [[4, 30], [60, 30], [60, 46], [4, 46]]}}, '
        '"strokes": {"default": "band"}, "fills": ' + fills + '}')
    return str(tmp_path / "style.json")


def test_vectorize_style_is_the_clis(cli, tmp_path):
    (tmp_path / "drawing.svg").write_text(DRAWING)
    style = style_palette(tmp_path)
    subprocess.run([cli, "vectorize-style", str(tmp_path / "drawing.svg"), "--palette", style,
                    "--width", "90", "--seed", "4", "--rotations", "3", "--threads", "2", "-q",
                    "-o", str(tmp_path / "a.png")], check=True)
    a = exemplar.vectorize_style(str(tmp_path / "drawing.svg"), style, width=90, seed=4,
                                 rotations=3, threads=2)
    assert a.shape == (60, 90, 4) and a.dtype == np.uint8
    np.testing.assert_array_equal(a, png(str(tmp_path / "a.png")))
    assert a[30, 45, 3] == 255 and a[2, 2, 3] == 0  # the shape and stroke, no background


def test_vectorize_style_refuses_what_the_library_refuses(tmp_path):
    (tmp_path / "drawing.svg").write_text(DRAWING)
    (tmp_path / "empty.svg").write_text('<svg xmlns="http://www.w3.org/2000/svg"/>')
    with pytest.raises(exemplar.InvalidArgumentError, match="^drawing: holds no path"):
        exemplar.vectorize_style(str(tmp_path / "empty.svg"), style_palette(tmp_path))
    with pytest.raises(exemplar.InvalidArgumentError, match='names area feature "sky"'):
        exemplar.vectorize_style(str(tmp_path / "drawing.svg"),
                                 style_palette(tmp_path, '{"#0000ff": "sky"}'))
    with pytest.raises(exemplar.InvalidArgumentError, match="^rotations: 0 is invalid"):
        exemplar.vectorize_style(str(tmp_path / "drawing.svg"), style_palette(tmp_path),
                                 rotations=0)
