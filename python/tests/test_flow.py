"""exemplar.flow: the CLI's optical flow, backward flow and occlusion mask as arrays."""

import subprocess

import numpy as np
import pytest

import exemplar
from conftest import SOURCE_DIR

FRAMES = [str(SOURCE_DIR / f"tests/data/flow/synthetic-img{i}.png") for i in (0, 1)]


def test_the_flows_are_the_clis(cli, tmp_path):
    forward, backward, occlusion = (str(tmp_path / name)
                                    for name in ("fwd.exr", "bwd.exr", "occ.exr"))
    subprocess.run([cli, "flow", "--from", FRAMES[0], "--to", FRAMES[1], "-o", forward,
                    "--backward", backward, "--occlusion", occlusion, "--preset", "fast",
                    "--epsilon", "4", "-q"], check=True)
    frames = [exemplar.load_image(path) for path in FRAMES]
    result = exemplar.flow(*frames, backward=True, occlusion=True, preset="fast", epsilon=4)
    assert sorted(result) == ["backward", "forward", "occlusion"]
    assert result["forward"].shape == (192, 256, 2) and result["forward"].dtype == np.float32
    np.testing.assert_array_equal(result["forward"], exemplar.load_image(forward))
    np.testing.assert_array_equal(result["backward"], exemplar.load_image(backward))
    np.testing.assert_array_equal(result["occlusion"], exemplar.load_image(occlusion)[..., 0])
    assert 0 < result["occlusion"].mean() < 0.5


def test_only_the_forward_flow_unless_asked():
    frames = [exemplar.load_image(path) for path in FRAMES]
    assert list(exemplar.flow(*frames, preset="ultrafast")) == ["forward"]


def test_flow_refuses_what_the_cli_refuses():
    frames = [exemplar.load_image(path) for path in FRAMES]
    with pytest.raises(exemplar.InvalidArgumentError, match="^epsilon: 0.000000 is invalid"):
        exemplar.flow(*frames, epsilon=0)
    with pytest.raises(exemplar.InvalidArgumentError, match="^preset: "):
        exemplar.flow(*frames, preset="slow")
    with pytest.raises(exemplar.InvalidArgumentError,
                       match="^from_frame is 256x192 but to_frame is 255x192$"):
        exemplar.flow(frames[0], np.ascontiguousarray(frames[1][:, 1:]))
    with pytest.raises(TypeError, match="^occlusion: must be a bool$"):
        exemplar.flow(*frames, occlusion="yes")
