"""exemplar.render: the CLI's renders as arrays."""

import subprocess

import numpy as np
import pytest

import exemplar
from conftest import SOURCE_DIR

SMALL = dict(width=40, height=30, spp=4)


def test_the_buffers_are_the_clis_for_the_same_seed(cli, tmp_path):
    subprocess.run([cli, "render", "--scene", "sphere-on-table", "--width", "40", "--height",
                    "30", "--spp", "4", "--seed", "3", "--format", "exr", "-j", "2", "-q",
                    "-o", str(tmp_path / "out")], check=True)
    buffers = exemplar.render("sphere-on-table", seed=3, threads=1, **SMALL)
    files = sorted(path.stem for path in (tmp_path / "out").glob("*.exr"))
    assert files == sorted(buffers)
    for name, image in buffers.items():
        assert image.dtype == np.float32 and image.shape[:2] == (30, 40), name
        np.testing.assert_array_equal(image, exemplar.load_image(str(tmp_path / "out" /
                                                                     f"{name}.exr")), name)
    assert buffers["fullgi"].shape == (30, 40, 3) and buffers["depth"].shape == (30, 40, 1)
    assert len(np.unique(buffers["object_id"])) >= 2  # the sphere and the table


def test_the_seed_matters_and_the_thread_count_does_not():
    one = exemplar.render("sphere-on-table", threads=1, **SMALL)
    two = exemplar.render("sphere-on-table", threads=2, **SMALL)
    other = exemplar.render("sphere-on-table", seed=2, **SMALL)
    np.testing.assert_array_equal(one["fullgi"], two["fullgi"])
    assert not np.array_equal(one["fullgi"], other["fullgi"])


def test_an_animated_scene_renders_one_frame_with_its_motion():
    scene = str(SOURCE_DIR / "examples/render/spot-turntable.json")
    with pytest.raises(exemplar.InvalidArgumentError, match="^frame: required: .* is animated"):
        exemplar.render(scene, **SMALL)
    buffers = exemplar.render(scene, frame=2, **SMALL)
    assert buffers["forward_flow"].shape == (30, 40, 2)
    assert buffers["occlusion"].shape == (30, 40, 1)
    assert np.abs(buffers["forward_flow"]).max() > 0


def test_render_refuses_what_the_cli_refuses(tmp_path):
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^spp: 0 is invalid \(must be "):
        exemplar.render("sphere-on-table", spp=0)
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^width: 0 is invalid"):
        exemplar.render("sphere-on-table", width=0)
    with pytest.raises(exemplar.InvalidArgumentError,
                       match=r'^scene: scene "cube" is not a built-in scene \(built-in: '):
        exemplar.render("cube")
    with pytest.raises(exemplar.IoError, match="missing.json"):
        exemplar.render(str(tmp_path / "missing.json"))
    with pytest.raises(TypeError, match=r"^width: must be an int \(got float\)"):
        exemplar.render("sphere-on-table", width=40.0)
    with pytest.raises(TypeError, match="unexpected keyword argument 'samples'"):
        exemplar.render("sphere-on-table", samples=4)
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^frame: -1 is invalid"):
        exemplar.render("sphere-on-table", frame=-1)


def test_render_reports_progress_and_cancels():
    events = []
    exemplar.render("sphere-on-table", progress=events.append, **SMALL)
    assert events and events[-1].fraction == pytest.approx(1.0)
    assert [e.fraction for e in events] == sorted(e.fraction for e in events)
    with pytest.raises(exemplar.Cancelled):
        exemplar.render("sphere-on-table", progress=lambda event: False, **SMALL)
