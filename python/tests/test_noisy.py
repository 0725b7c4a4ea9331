"""exemplar.noisy_frame: the bytes of `exemplar noisy` for a frame, and the library's messages."""

import subprocess

import numpy as np
import pytest

import exemplar
from conftest import gradient, pattern


def test_noisy_frames_are_the_clis(cli, tmp_path):
    medium = pattern(40, 44, 3, 0.3)
    references = {n: pattern(32, 36, 3, 1.0 + 0.2 * n) for n in (3, 4)}
    exemplar.save_image(medium, str(tmp_path / "medium.png"))
    (tmp_path / "ref").mkdir()
    for n, image in references.items():
        exemplar.save_image(image, str(tmp_path / f"ref/{n:04d}.png"))
    subprocess.run([cli, "noisy", "--exemplar", str(tmp_path / "medium.png"), "--frames",
                    str(tmp_path / "ref/%04d.png"), "--first", "3", "--last", "4", "--noise",
                    "2.5", "--seed", "9", "--patch-size", "5", "-o",
                    str(tmp_path / "out/%04d.png"), "-j", "2", "-q"], check=True)
    frames = {}
    for n in (3, 4):
        frames[n] = exemplar.noisy_frame(medium, references[n], frame=n, noise=2.5, seed=9,
                                         patch_size=5, threads=2)
        assert frames[n].shape == (32, 36, 3) and frames[n].dtype == np.uint8
        expected = np.round(exemplar.load_image(str(tmp_path / f"out/{n:04d}.png")) * 255)
        np.testing.assert_array_equal(frames[n], expected)
    # Frame i depends on (seed, i): the same reference as another frame number differs.
    other = exemplar.noisy_frame(medium, references[3], frame=4, noise=2.5, seed=9, patch_size=5)
    assert not np.array_equal(other, frames[3])


def test_noisy_options_come_from_the_table():
    parameters = exemplar.noisy_frame.__signature__.parameters
    for name in ("noise", "level_ratio", "patch_size", "em_iterations", "search_iterations",
                 "warm_search_iterations", "warm_em_iterations",
                 "lattice_spacing", "min_offset", "max_offset", "seed", "filter", "frame"):
        assert name in parameters
    assert parameters["patch_size"].default == 7
    assert "Color Me Noisy" in exemplar.noisy_frame.__doc__


def test_noisy_refuses_what_the_library_refuses():
    medium, reference = pattern(40, 44, 3, 0.3), pattern(32, 36, 3, 1.0)
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^noise: is required"):
        exemplar.noisy_frame(medium, reference)
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^noise: -1 is invalid"):
        exemplar.noisy_frame(medium, reference, noise=-1)
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^patch-size: 4 is invalid"):
        exemplar.noisy_frame(medium, reference, noise=2, patch_size=4)
    with pytest.raises(exemplar.InvalidArgumentError, match="^filter"):
        exemplar.noisy_frame(medium, reference, noise=2, filter="gauss")
    with pytest.raises(exemplar.InvalidArgumentError, match="^noise_map: is 8x8"):
        exemplar.noisy_frame(medium, reference, noise=2,
                             noise_map=np.zeros((8, 8), np.float32))
    with pytest.raises(TypeError, match="unexpected keyword argument 'nosie'"):
        exemplar.noisy_frame(medium, reference, noise=2, nosie=3)


def test_noisy_frame_reports_progress_and_cancels():
    medium, reference = pattern(40, 44, 3, 0.3), gradient(32, 36, 3)
    with pytest.raises(exemplar.Cancelled):
        exemplar.noisy_frame(medium, reference, noise=3, progress=lambda p: False)
    calls = []
    exemplar.noisy_frame(medium, reference, noise=3, progress=calls.append)
    assert calls and calls[-1].fraction == pytest.approx(1.0)


def test_noisy_source_map_chooses_the_medium_as_the_cli_does(cli, tmp_path):
    dark = (0.1 + 0.3 * pattern(40, 44, 3, 0.3) / 255).astype(np.float32)
    bright = (0.6 + 0.3 * pattern(40, 44, 3, 0.7) / 255).astype(np.float32)
    reference = pattern(32, 36, 3, 1.0)
    source_map = np.zeros((32, 36), np.uint8)
    source_map[:, 18:] = 1
    for name, image in (("dark", dark), ("bright", bright)):
        exemplar.save_image(image, str(tmp_path / f"{name}.png"))
    (tmp_path / "ref").mkdir()
    exemplar.save_image(reference, str(tmp_path / "ref/0000.png"))
    exemplar.save_image(source_map[:, :, None].astype(np.float32) / 255, str(tmp_path / "map.png"))
    subprocess.run([cli, "noisy", "--exemplar", str(tmp_path / "dark.png"), "--exemplar",
                    str(tmp_path / "bright.png"), "--source-map", str(tmp_path / "map.png"),
                    "--frames", str(tmp_path / "ref/%04d.png"), "--first", "0", "--last", "0",
                    "--noise", "2", "--patch-size", "5", "-o", str(tmp_path / "out%d.png"), "-q"],
                   check=True)
    media = [exemplar.load_image(str(tmp_path / f"{name}.png")) for name in ("dark", "bright")]
    frame = exemplar.noisy_frame(media, exemplar.load_image(str(tmp_path / "ref/0000.png")),
                                 noise=2, patch_size=5, source_map=source_map)
    expected = exemplar.load_image(str(tmp_path / "out0.png"))
    np.testing.assert_allclose(frame, expected, atol=0.51 / 255)
    # Away from the boundary each half holds its own medium only.
    assert frame[:, :16].max() < 0.5 and frame[:, 20:].min() > 0.5
    with pytest.raises(exemplar.InvalidArgumentError,
                       match=r"^source map: value 2 at \(0, 0\) has no source \(2 given: 0..1\)"):
        exemplar.noisy_frame(media, reference, noise=2, source_map=source_map + 2)
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^source map: is required"):
        exemplar.noisy_frame(media, reference, noise=2)
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^source_map: 0.500000 is not"):
        exemplar.noisy_frame(media, reference, noise=2, source_map=source_map + 0.5)
