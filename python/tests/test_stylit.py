"""exemplar.stylit: the StyLit guides built from light-path buffers, as arrays or as files."""

import numpy as np
import pytest

import exemplar
from conftest import gradient, pattern


@pytest.fixture
def renders():
    """A painting, and four buffers of an exemplar render and of a target render."""
    painting = pattern(24, 28, 3, 0.0)
    source = [pattern(24, 28, 3, phase) for phase in (1.0, 2.0, 3.0)] + [gradient(24, 28, 3)]
    target = [pattern(26, 30, 3, phase) for phase in (1.5, 2.5, 3.5)] + [gradient(26, 30, 3)]
    return painting, source, target


def test_stylit_is_stylize_with_the_buffers_as_guides(renders):
    painting, source, target = renders
    result = exemplar.stylit(painting, source, target, guidance_weight=2.0, seed=4)
    # mu = 2 shared by four buffers: weight 0.5 each.
    same = exemplar.stylize(painting, [(s, t, 0.5) for s, t in zip(source, target)], seed=4)
    assert result.image.shape == (26, 30, 3) and result.image.dtype == np.uint8
    np.testing.assert_array_equal(result.image, same.image)
    assert result.guide_channels == 12


def test_buffers_from_files_are_the_buffers_as_arrays(renders, tmp_path):
    painting, source, target = renders
    paths = {}
    for side, buffers in (("source", source), ("target", target)):
        paths[side] = []
        for i, image in enumerate(buffers):
            paths[side].append(str(tmp_path / f"{side}_{i}.png"))
            exemplar.save_image(image, paths[side][-1])
    from_files = exemplar.stylit(painting, paths["source"], paths["target"], usage="uniform")
    from_arrays = exemplar.stylit(painting, source, target, usage="uniform")
    np.testing.assert_array_equal(from_files.image, from_arrays.image)


def test_preview_runs_at_half_size_on_compressed_buffers(renders):
    painting, source, target = renders
    result = exemplar.stylit(painting, source, target, preview=True)
    assert result.image.shape == (13, 15, 3)
    assert result.guide_channels <= 5 and 0.0 < result.explained_variance <= 1.0


def test_stylit_refuses_what_the_cli_refuses(renders, tmp_path):
    painting, source, target = renders
    with pytest.raises(exemplar.InvalidArgumentError, match="guidance weight: "):
        exemplar.stylit(painting, source, target, guidance_weight=-1)
    with pytest.raises(exemplar.InvalidArgumentError):
        exemplar.stylit(painting, source, target[:3])
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^source\[1\] / target\[1\]: source guide is 27x24 but the style is 28x24$"):
        exemplar.stylit(painting, [source[0], np.ascontiguousarray(source[1][:, 1:])] +
                        source[2:], target)
    with pytest.raises(exemplar.IoError, match="no such file"):
        exemplar.stylit(painting, str(tmp_path / "missing.exr"), target)
    with pytest.raises(ValueError, match="^patch-size: 2 is invalid"):
        exemplar.stylit(painting, source, target, patch_size=2)
    with pytest.raises(TypeError, match="unexpected keyword argument 'guides'"):
        exemplar.stylit(painting, source, target, guides=[])
