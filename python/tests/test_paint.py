"""exemplar.directions and exemplar.paint: the bytes of `exemplar directions` and
`exemplar paint`, and the library's messages as exceptions."""

import json
import subprocess

import numpy as np
import pytest

import exemplar
from conftest import pattern

STROKES = [
    {"points": [[6, 30], [20, 14], [40, 10], [56, 24]], "width": 14},
    {"points": [[10, 40], [50, 40]], "width": 10},
    {"points": [[20, 20], [40, 36]], "width": 12, "comb": True},
]


def blob(size=36):
    """An RGBA uint8 exemplar: striped texture inside a soft-edged disc."""
    rgb = pattern(size, size, 3, 0.7)
    y, x = np.mgrid[0:size, 0:size].astype(np.float64)
    r = np.hypot(x - size / 2, y - size / 2) / (size / 2)
    alpha = np.round(np.clip((1.0 - r) * 4, 0, 1) * 255).astype(np.uint8)
    return np.ascontiguousarray(np.concatenate([rgb, alpha[..., None]], axis=-1))


def test_directions_are_the_clis(cli, tmp_path):
    exemplar.save_image(blob(), str(tmp_path / "blob.png"))
    subprocess.run([cli, "directions", str(tmp_path / "blob.png"), "-o",
                    str(tmp_path / "dir.exr"), "--radius", "6", "--iterations", "2", "-q"],
                   check=True)
    angles = exemplar.directions(blob(), radius=6, iterations=2)
    assert angles.shape == (36, 36) and angles.dtype == np.float32
    expected = exemplar.load_image(str(tmp_path / "dir.exr"))[..., 0]
    # The CLI's EXR holds half samples: the same angles rounded to float16.
    np.testing.assert_array_equal(angles.astype(np.float16).astype(np.float32), expected)
    assert np.abs(angles).max() > 0.1 and np.abs(angles).max() <= np.pi + 1e-6


def test_paint_is_the_clis(cli, tmp_path):
    exemplar.save_image(blob(), str(tmp_path / "blob.png"))
    (tmp_path / "strokes.json").write_text(json.dumps(STROKES))
    subprocess.run([cli, "paint", "--source", str(tmp_path / "blob.png"), "--strokes",
                    str(tmp_path / "strokes.json"), "--width", "64", "--height", "52",
                    "--seed", "3", "--edge-extent", "8", "-o", str(tmp_path / "out.png"),
                    "--threads", "2", "-q"], check=True)
    strokes = [dict(s, points=np.array(s["points"], np.float64)) for s in STROKES]
    result = exemplar.paint(blob(), strokes, width=64, height=52, seed=3, edge_extent=8,
                            threads=2)
    assert result.shape == (52, 64, 4) and result.dtype == np.uint8
    expected = np.round(exemplar.load_image(str(tmp_path / "out.png")) * 255)
    np.testing.assert_array_equal(result, expected)
    assert result[..., 3].max() == 255 and result[0, 63, 3] == 0  # painted, and not everywhere


def test_paint_labels_are_the_clis(cli, tmp_path):
    """Two segments: ids 1 and 2 in Python, colours red and blue in the CLI's label image."""
    rgb = pattern(24, 32, 3, 0.7)
    rgb[:, 16:, 2] = 255 - rgb[:, 16:, 2]
    ids = np.ones((24, 32), np.uint8)
    ids[:, 16:] = 2
    colours = np.zeros((24, 32, 3), np.uint8)
    colours[ids == 1] = (255, 0, 0)
    colours[ids == 2] = (0, 0, 255)
    exemplar.save_image(rgb, str(tmp_path / "two.png"))
    exemplar.save_image(colours, str(tmp_path / "segments.png"))
    strokes = [{"points": [[4, 10], [60, 10]], "width": 12, "label": "#0000ff"},
               {"points": [[4, 30], [60, 30]], "width": 12, "label": "#ff0000"}]
    (tmp_path / "strokes.json").write_text(json.dumps(strokes))
    subprocess.run([cli, "paint", "--source", str(tmp_path / "two.png"), "--source-labels",
                    str(tmp_path / "segments.png"), "--strokes", str(tmp_path / "strokes.json"),
                    "--width", "64", "--height", "40", "-o", str(tmp_path / "out.png"),
                    "--threads", "2", "-q"], check=True)
    for stroke, label in zip(strokes, (2, 1)):
        stroke["label"] = label
    result = exemplar.paint(rgb, strokes, source_labels=ids, width=64, height=40, threads=2)
    expected = np.round(exemplar.load_image(str(tmp_path / "out.png")) * 255)
    np.testing.assert_array_equal(result, expected)
    with pytest.raises(exemplar.InvalidArgumentError, match="label 3 is painted"):
        exemplar.paint(rgb, [dict(strokes[0], label=3)], source_labels=ids, width=64, height=40)
    with pytest.raises(exemplar.InvalidArgumentError, match="^source_labels: 0.500000 is not"):
        exemplar.paint(rgb, strokes, source_labels=ids * 0.5, width=64, height=40)


def test_paint_refuses_what_the_library_refuses():
    with pytest.raises(exemplar.InvalidArgumentError, match="^radius"):
        exemplar.directions(blob(), radius=0)
    with pytest.raises(exemplar.InvalidArgumentError, match="^width/height: 0x0 is invalid"):
        exemplar.paint(blob(), STROKES)
    with pytest.raises(exemplar.InvalidArgumentError, match="^patch-size"):
        exemplar.paint(blob(), STROKES, width=64, height=52, patch_size=4)
    with pytest.raises(exemplar.InvalidArgumentError, match="strokes\\[0\\]: points must be Nx2"):
        exemplar.paint(blob(), [{"points": [1, 2, 3]}], width=64, height=52)
    with pytest.raises(exemplar.InvalidArgumentError, match="width"):
        exemplar.paint(blob(), [{"points": [[1, 2]], "width": -3}], width=64, height=52)
    with pytest.raises(TypeError, match="unknown key 'colour'"):
        exemplar.paint(blob(), [{"points": [[1, 2]], "colour": 1}], width=64, height=52)
    with pytest.raises(TypeError, match="unexpected keyword argument 'radius'"):
        exemplar.paint(blob(), STROKES, width=64, height=52, radius=3)


def test_paint_reports_progress_and_cancels():
    with pytest.raises(exemplar.Cancelled):
        exemplar.paint(blob(), STROKES, width=64, height=52, progress=lambda p: False)
    calls = []
    exemplar.paint(blob(), STROKES, width=64, height=52, progress=calls.append)
    assert calls
