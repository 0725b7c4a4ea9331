"""exemplar.npr_frame: the bytes of `exemplar npr` frame after frame, render()'s buffers taken as
they are, the library's messages, progress and cancellation."""

import json
import pathlib
import subprocess

import numpy as np
import pytest

import exemplar
from conftest import gradient, pattern

# A sphere moving right (as tests/npr/npr_cli_test.cpp renders it).
SCENE = {
    "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov_deg": 40},
    "sky": [0.8, 0.8, 0.8],
    "materials": [{"name": "m"}],
    "objects": [{"shape": "sphere", "material": "m", "subdivisions": 16,
                 "keyframes": [{"frame": 0, "translate": [0, 0, 0]},
                               {"frame": 10, "translate": [1, 0, 0]}]}],
}
WIDTH, HEIGHT = 48, 32


def screen(size=32, period=6):
    """A tileable dot screen, uint8 (thresholding it grows dots with the darkness)."""
    y, x = np.mgrid[0:size, 0:size].astype(np.float64) * (2 * np.pi / period)
    value = 0.5 + 0.25 * (np.cos(x) + np.cos(y)) + 0.1 * np.sin(x / 3 + 2 * y / 5)
    return np.round(np.clip(value, 0, 1) * 255).astype(np.uint8)[..., None]


def load_folder(folder: pathlib.Path):
    """A frame folder's buffers as the CLI reads them: EXR as float32 (linear), PNG as uint8."""
    buffers = {}
    for path in sorted(folder.iterdir()):
        if path.suffix == ".exr":
            buffers[path.stem] = exemplar.load_image(str(path))
        elif path.stem not in buffers:
            buffers[path.stem] = np.round(exemplar.load_image(str(path)) * 255).astype(np.uint8)
    return buffers


@pytest.fixture
def frames(cli, tmp_path):
    """Three frames rendered by `exemplar render --frames` (PNG folders) and the scene file."""
    (tmp_path / "scene.json").write_text(json.dumps(SCENE))
    subprocess.run([cli, "render", "--scene", str(tmp_path / "scene.json"), "--width",
                    str(WIDTH), "--height", str(HEIGHT), "--spp", "2", "-j", "2", "--frames",
                    "0-2", "-o", str(tmp_path / "R/frame_%04d"), "-q"], check=True)
    return tmp_path


@pytest.mark.parametrize("style, flags, keywords", [
    ("stipple", ["--tone", "fullgi"], {"tone": "fullgi"}),
    ("hatch", ["--seed", "4", "--coherence-weight", "0.5"], {"seed": 4, "coherence_weight": 0.5}),
    ("pattern", ["--no-lines"], {"lines": False}),
    ("stipple", ["--paper", "PAPER", "--erosion", "1.5"], {"paper": "PAPER", "erosion": 1.5}),
])
def test_npr_frames_are_the_clis(cli, frames, style, flags, keywords):
    exemplar.save_image(screen(), str(frames / "screen.png"))
    # The paper layer: a finer screen as the paper, a file for the CLI, an array for Python
    paper = screen(32, 3)
    exemplar.save_image(paper, str(frames / "paper.png"))
    flags = [str(frames / "paper.png") if f == "PAPER" else f for f in flags]
    keywords = {k: paper if isinstance(v, str) and v == "PAPER" else v
                for k, v in keywords.items()}
    subprocess.run([cli, "npr", "--pattern", str(frames / "screen.png"), "--frames",
                    str(frames / "R/frame_%04d"), "--first", "0", "--last", "2", "--style", style,
                    "--levels", "2", "--patch-size", "8", "-o", str(frames / "O/%04d.png"),
                    "-j", "2", "-q", *flags], check=True)
    state = None
    for n in range(3):
        image, state = exemplar.npr_frame(screen(), load_folder(frames / f"R/frame_{n:04d}"),
                                          previous=state, frame=n, style=style, levels=2,
                                          patch_size=8, threads=2, **keywords)
        assert image.shape == (HEIGHT, WIDTH, 1) and image.dtype == np.uint8
        expected = np.round(exemplar.load_image(str(frames / f"O/{n:04d}.png")) * 255)
        np.testing.assert_array_equal(image, expected, err_msg=f"frame {n}")
        assert state.frame == n and state.levels == 2
        assert [c.shape for c in state.coords] == [(HEIGHT, WIDTH, 2),
                                                   (HEIGHT // 2, WIDTH // 2, 2)]
    if style != "pattern" and "paper" not in keywords:  # the paper's grain shades the white
        assert set(np.unique(image)) == {0, 255}


def test_npr_frame_takes_renders_buffers(frames):
    """render()'s dict goes in as it is: float32 light buffers are linear and encoded first."""
    scene = str(frames / "scene.json")
    state, images = None, []
    for n in range(2):
        buffers = exemplar.render(scene, frame=n, width=WIDTH, height=HEIGHT, spp=2)
        image, state = exemplar.npr_frame(screen(), buffers, previous=state, frame=n, levels=2,
                                          patch_size=8)
        images.append(image)
        # The same tone encoded by hand (linear_tone=False) gives the same frame
        if n == 0:
            encoded = dict(buffers, direct_diffuse=_srgb(buffers["direct_diffuse"]))
            again, _ = exemplar.npr_frame(screen(), encoded, frame=0, levels=2, patch_size=8,
                                          linear_tone=False)
            np.testing.assert_array_equal(again, image)
    assert images[0].dtype == np.uint8 and not np.array_equal(images[0], images[1])


def _srgb(linear):
    c = np.clip(linear, 0, 1)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055).astype(np.float32)


def synthetic(width=WIDTH, height=HEIGHT):
    """Buffers of a frame without a renderer: a tone ramp, no lines, a 1 px motion."""
    flow = np.zeros((height, width, 2), np.float32)
    flow[..., 0] = -1
    return {"direct_diffuse": gradient(height, width),
            "lines": np.zeros((height, width), np.uint8), "backward_flow": flow,
            "disocclusion": np.zeros((height, width, 1), np.float32)}


def test_npr_options_come_from_the_table():
    parameters = exemplar.npr_frame.__signature__.parameters
    for name in ("levels", "patch_size", "coherence_weight", "motion_levels", "paper_grain",
                 "erosion", "style", "tone", "orientation", "lines", "tone_correction", "seed",
                 "frame", "previous", "linear_tone", "paper"):
        assert name in parameters
    assert parameters["patch_size"].default == 12 and parameters["levels"].default == 3
    assert "Range 1..6" in exemplar.npr_frame.__doc__


def test_npr_refuses_what_the_library_refuses():
    pat, buffers = pattern(48, 48, 1, 0.3), synthetic()
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^style: 'crosshatch' is invalid"):
        exemplar.npr_frame(pat, buffers, style="crosshatch")
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^levels: 9 is invalid"):
        exemplar.npr_frame(pat, buffers, levels=9)
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^tone: not used by style pattern"):
        exemplar.npr_frame(pat, buffers, style="pattern", tone="fullgi")
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^pattern: 16x16 is too small"):
        exemplar.npr_frame(pattern(16, 16, 1, 0.3), buffers)
    with pytest.raises(exemplar.InvalidArgumentError,
                       match=r"^buffers\['lines'\]: dtype float64 is not supported"):
        exemplar.npr_frame(pat, dict(buffers, lines=np.zeros((HEIGHT, WIDTH))))
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^buffers\['direct_diffuse'\]: has"):
        exemplar.npr_frame(pat, dict(buffers, direct_diffuse=np.zeros(WIDTH, np.uint8)))
    with pytest.raises(exemplar.InvalidArgumentError,
                       match=r"^buffer 'lines' is 49x32 but the frames are 48x32$"):
        exemplar.npr_frame(pat, dict(buffers, lines=np.zeros((HEIGHT, WIDTH + 1), np.uint8)))
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^missing buffer 'orientation'$"):
        exemplar.npr_frame(pat, buffers, style="hatch")
    _, state = exemplar.npr_frame(pat, buffers)
    flowless = {k: v for k, v in buffers.items() if k != "backward_flow"}
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^missing buffer 'backward_flow'$"):
        exemplar.npr_frame(pat, flowless, previous=state, frame=1)
    with pytest.raises(exemplar.InvalidArgumentError, match="differs from the previous frame's"):
        exemplar.npr_frame(pat, synthetic(WIDTH + 2), previous=state, frame=1)
    with pytest.raises(TypeError, match="previous: must be an exemplar.NprState"):
        exemplar.npr_frame(pat, buffers, previous=np.zeros((2, 2, 2), np.float32))
    with pytest.raises(TypeError, match="buffers: must be a dict"):
        exemplar.npr_frame(pat, [buffers["direct_diffuse"]])
    with pytest.raises(TypeError, match="lines: must be a bool"):
        exemplar.npr_frame(pat, buffers, lines=1)
    with pytest.raises(TypeError, match="linear_tone: must be a bool"):
        exemplar.npr_frame(pat, buffers, linear_tone=1)
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^erosion: needs paper=$"):
        exemplar.npr_frame(pat, buffers, erosion=3)
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^paper: pattern: 8x8 is too small"):
        exemplar.npr_frame(pat, buffers, paper=pattern(8, 8, 1, 0.3))
    with pytest.raises(TypeError, match="unexpected keyword argument 'levles'"):
        exemplar.npr_frame(pat, buffers, levles=2)


def test_npr_frame_reports_progress_and_cancels():
    pat, buffers = pattern(48, 48, 1, 0.3), synthetic()
    calls = []
    _, state = exemplar.npr_frame(pat, buffers, progress=calls.append)
    assert [c.stage for c in calls] == ["synthesis"] * 3
    assert calls[-1].fraction == pytest.approx(1.0)
    with pytest.raises(exemplar.Cancelled):
        exemplar.npr_frame(pat, buffers, previous=state, frame=1, progress=lambda p: False)
    token = exemplar.CancelToken()
    token.cancel()
    with pytest.raises(exemplar.Cancelled):
        exemplar.npr_frame(pat, buffers, cancel=token)
    # The state is untouched by the cancelled calls: the next frame still follows it
    image, _ = exemplar.npr_frame(pat, buffers, previous=state, frame=1)
    assert image.shape == (HEIGHT, WIDTH, 1)
