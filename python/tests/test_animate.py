"""exemplar.animate: the CLI's TCIA run on frames held as arrays."""

import json
import subprocess

import numpy as np
import pytest

import exemplar
from conftest import SOURCE_DIR, gradient, pattern

EXAMPLE = SOURCE_DIR / "examples/animate"


def test_the_frames_are_the_clis(cli, tmp_path):
    job = {"frames": str(EXAMPLE / "frames/%04d.png"), "first": 0, "last": 2,
           "flows": "estimate", "style": {"input": str(EXAMPLE / "style_input.png"),
                                          "output": str(EXAMPLE / "style_output.png")},
           "output": str(tmp_path / "out/%04d.png")}
    (tmp_path / "job.json").write_text(json.dumps(job))
    subprocess.run([cli, "animate", str(tmp_path / "job.json"), "-q", "-j", "2"], check=True)

    frames = [exemplar.load_image(str(EXAMPLE / f"frames/{i:04d}.png")) for i in range(3)]
    style_output = np.round(exemplar.load_image(str(EXAMPLE / "style_output.png")) * 255)
    out = exemplar.animate(exemplar.load_image(str(EXAMPLE / "style_input.png")),
                           style_output.astype(np.uint8), frames, threads=1)
    assert len(out) == 3
    for i, frame in enumerate(out):
        assert frame.dtype == np.uint8 and frame.shape == (108, 192, 3)
        from_cli = np.round(exemplar.load_image(str(tmp_path / f"out/{i:04d}.png")) * 255)
        np.testing.assert_array_equal(frame, from_cli.astype(np.uint8))


@pytest.fixture
def clip():
    """A 3-frame static clip (given zero motion) of 32x32 frames and its style pair."""
    style_input, style_output = gradient(40, 44), pattern(40, 44, 3, 0.0)
    frames = [gradient(32, 32) for _ in range(3)]
    still = np.zeros((32, 32, 2), np.float32)
    return style_input, style_output, frames, [(still, still)] * 2


def test_a_painted_keyframe_is_reproduced_exactly(clip):
    style_input, style_output, frames, flows = clip
    key = pattern(32, 32, 3, 2.0)
    out = exemplar.animate(style_input, style_output, frames, flows=flows,
                           keyframes=[(1, key)], levels=2)
    np.testing.assert_array_equal(out[1], key)
    # A partial key: only its painted half is copied.
    mask = np.zeros((32, 32), np.float32)
    mask[:, :16] = 1
    out = exemplar.animate(style_input, style_output, frames, flows=flows,
                           keyframes=[(0, key, mask)], levels=2)
    np.testing.assert_array_equal(out[0][:, :16], key[:, :16])


def test_animate_options_are_honoured(clip):
    style_input, style_output, frames, flows = clip
    plain = exemplar.animate(style_input, style_output, frames, flows=flows, levels=2)
    again = exemplar.animate(style_input, style_output, frames, flows=flows, levels=2, threads=1)
    seeded = exemplar.animate(style_input, style_output, frames, flows=flows, levels=2, seed=5)
    for a, b in zip(plain, again):
        np.testing.assert_array_equal(a, b)
    assert any(not np.array_equal(a, b) for a, b in zip(plain, seeded))


def test_animate_refuses_what_the_cli_refuses(clip):
    style_input, style_output, frames, flows = clip
    with pytest.raises(exemplar.InvalidArgumentError,
                       match=r"^flows: 1 pairs for 3 frames \(must be one per consecutive"):
        exemplar.animate(style_input, style_output, frames, flows=flows[:1])
    with pytest.raises(exemplar.InvalidArgumentError, match="^levels: 0 is invalid"):
        exemplar.animate(style_input, style_output, frames, flows=flows, levels=0)
    with pytest.raises(exemplar.InvalidArgumentError, match="^patch-size: 4 is invalid"):
        exemplar.animate(style_input, style_output, frames, patch_size=4)
    with pytest.raises(exemplar.InvalidArgumentError, match="keyframe"):
        exemplar.animate(style_input, style_output, frames, flows=flows,
                         keyframes=[(7, pattern(32, 32, 3, 1.0))])
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^frames\[1\]: dtype float64"):
        exemplar.animate(style_input, style_output, [frames[0], frames[1].astype(float)])
    with pytest.raises(TypeError, match="^frames: must be a sequence of arrays"):
        exemplar.animate(style_input, style_output, frames[0])
    with pytest.raises(TypeError, match="unexpected keyword argument 'vote'"):
        exemplar.animate(style_input, style_output, frames, vote="average")
    with pytest.raises(ValueError, match="preset"):
        exemplar.animate(style_input, style_output, frames, flow_preset="slow")


def test_animate_reports_progress_and_cancels(clip):
    style_input, style_output, frames, flows = clip
    events = []
    exemplar.animate(style_input, style_output, frames, flows=flows, levels=2,
                     progress=events.append)
    assert {event.stage for event in events} >= {"forward", "backward"}
    assert [e.fraction for e in events] == sorted(e.fraction for e in events)
    with pytest.raises(exemplar.Cancelled):
        exemplar.animate(style_input, style_output, frames, flows=flows,
                         progress=lambda event: False)


def test_the_signature_shows_animations_own_defaults():
    import inspect
    parameters = inspect.signature(exemplar.animate).parameters
    assert parameters["usage"].default == "occurrence"
    assert parameters["em_iterations"].default == 3
    assert parameters["levels"].default == 4 and parameters["levels"].annotation == "int"
    assert "vote" not in parameters


def test_the_signatures_defaults_are_the_defaults(clip):
    import inspect
    style_input, style_output, frames, flows = clip
    defaults = {name: p.default for name, p in inspect.signature(exemplar.animate).parameters.items()
                if p.kind == inspect.Parameter.KEYWORD_ONLY and name != "flows"}
    plain = exemplar.animate(style_input, style_output, frames, flows=flows)
    spelled_out = exemplar.animate(style_input, style_output, frames, flows=flows, **defaults)
    for a, b in zip(plain, spelled_out):
        np.testing.assert_array_equal(a, b)
