"""exemplar.fluid_frame and exemplar.fluid_simulate: the bytes of `exemplar fluid` and
`exemplar fluid simulate`, frame by frame, and the library's messages as exceptions."""

import subprocess

import numpy as np
import pytest

import exemplar


def read_flo(path):
    """A Middlebury .flo file as an HxWx2 float32 array."""
    data = np.fromfile(path, dtype="<f4")
    assert data[0] == np.float32(202021.25)
    width, height = np.frombuffer(data[1:3].tobytes(), dtype="<i4")
    return data[3:].reshape(height, width, 2)


def fire(size=20):
    """An RGBA uint8 exemplar: a soft disc of fluid with a colour ramp."""
    y, x = np.mgrid[0:size, 0:size].astype(np.float64)
    r = np.hypot(x - size / 2 + 0.5, y - size / 2 + 0.5) / (size / 2)
    alpha = np.clip(1.2 - r, 0.0, 1.0)
    red = 0.6 + 0.4 * np.sin(x / 2.0)
    green = 0.3 + 0.3 * np.cos(y / 3.0 + x / 5.0)
    blue = 0.1 + 0.1 * ((x + 2 * y) % 5) / 5
    rgba = np.stack([red, green, blue, alpha], axis=-1)
    return np.ascontiguousarray(np.round(np.clip(rgba, 0, 1) * 255).astype(np.uint8))


def simulate_with_cli(cli, folder, frames):
    subprocess.run([cli, "fluid", "simulate", "--scene", "plume", "--width", "32", "--height",
                    "32", "--frames", str(frames), "-o", str(folder), "-q"], check=True)
    alphas = [exemplar.load_image(str(folder / f"alpha/{n:04d}.png")) for n in range(frames)]
    motions = [read_flo(folder / f"motion/{n:04d}.flo") for n in range(frames)]
    return alphas, motions


def test_fluid_simulate_is_the_clis(cli, tmp_path):
    alphas, motions = simulate_with_cli(cli, tmp_path / "sim", 3)
    got_alphas, got_motions = exemplar.fluid_simulate(width=32, height=32, frames=3, threads=2)
    assert len(got_alphas) == len(got_motions) == 3
    for n in range(3):
        assert got_alphas[n].shape == (32, 32) and got_alphas[n].dtype == np.float32
        assert got_motions[n].shape == (32, 32, 2) and got_motions[n].dtype == np.float32
        # The CLI writes alpha as 8-bit PNG and motion as .flo (float32, exact).
        np.testing.assert_array_equal(np.round(np.clip(got_alphas[n], 0, 1) * 255),
                                      np.round(alphas[n][..., 0] * 255))
        np.testing.assert_array_equal(got_motions[n], motions[n])
    assert got_alphas[-1].max() > 0.2  # the plume is there


def test_fluid_frames_are_the_clis(cli, tmp_path):
    alphas, motions = simulate_with_cli(cli, tmp_path / "sim", 2)
    exemplar.save_image(fire(), str(tmp_path / "fire.png"))
    subprocess.run([cli, "fluid", "--exemplar", str(tmp_path / "fire.png"), "--alpha",
                    str(tmp_path / "sim/alpha/%04d.png"), "--motion",
                    str(tmp_path / "sim/motion/%04d.flo"), "--first", "0", "--last", "1",
                    "-o", str(tmp_path / "out/%04d.png"), "--blur-radius", "1.5",
                    "--seed", "7", "-j", "2", "-q"], check=True)
    cli_frames = [np.round(exemplar.load_image(str(tmp_path / f"out/{n:04d}.png")) * 255)
                  for n in range(2)]
    first = exemplar.fluid_frame(fire(), alphas[0][..., 0], blur_radius=1.5, seed=7, threads=2)
    assert first.shape == (32, 32, 4) and first.dtype == np.uint8
    np.testing.assert_array_equal(first, cli_frames[0])
    # The next frame continues from the previous output along the previous frame's motion.
    second = exemplar.fluid_frame(fire(), alphas[1], previous_output=first,
                                  previous_motion=motions[0], blur_radius=1.5, seed=7)
    np.testing.assert_array_equal(second, cli_frames[1])
    assert second[..., 3].max() > 0


def test_fluid_options_come_from_the_table():
    names = [p for p in exemplar.fluid_frame.__signature__.parameters]
    for name in ("patch_size", "temporal_weight", "boundary_weight", "alpha_weight",
                 "blur_radius", "boundary_low", "boundary_high", "motion_blur", "seed",
                 "usage", "rotations", "progress", "cancel"):
        assert name in names
    assert exemplar.fluid_frame.__signature__.parameters["patch_size"].default == 5
    assert "LazyFluids" in exemplar.fluid_frame.__doc__


def test_fluid_refuses_what_the_library_refuses():
    alpha = np.zeros((16, 16), np.float32)
    alpha[4:12, 4:12] = 1
    with pytest.raises(exemplar.InvalidArgumentError,
                       match=r"^temporal-weight: -1 is invalid \(must be 0..10\)$"):
        exemplar.fluid_frame(fire(), alpha, temporal_weight=-1)
    with pytest.raises(exemplar.InvalidArgumentError, match="^usage: 'lots' is invalid"):
        exemplar.fluid_frame(fire(), alpha, usage="lots")
    with pytest.raises(exemplar.InvalidArgumentError, match="exemplar"):
        exemplar.fluid_frame(np.zeros((16, 16, 3), np.uint8), alpha)  # not RGBA
    with pytest.raises(TypeError, match="unexpected keyword argument 'spead'"):
        exemplar.fluid_frame(fire(), alpha, spead=2)
    with pytest.raises(exemplar.InvalidArgumentError, match="^width"):
        exemplar.fluid_simulate(width=2, height=32, frames=1)


def test_fluid_frame_reports_progress_and_cancels():
    alpha = fire()[..., 3].astype(np.float32) / 255  # the exemplar's own segments
    with pytest.raises(exemplar.Cancelled):
        exemplar.fluid_frame(fire(), alpha, blur_radius=1.5, progress=lambda p: False)
    calls = []
    exemplar.fluid_frame(fire(), alpha, blur_radius=1.5, progress=calls.append)
    assert calls and 0 <= calls[-1].fraction <= 1


def test_fluid_simulate_reports_progress_and_cancels():
    events = []
    exemplar.fluid_simulate(width=16, height=16, frames=3,
                            progress=lambda p: events.append((p.stage, p.iteration)))
    assert events == [("simulate", 1), ("simulate", 2), ("simulate", 3)]
    token = exemplar.CancelToken()
    token.cancel()
    with pytest.raises(exemplar.Cancelled):
        exemplar.fluid_simulate(width=16, height=16, frames=3, cancel=token)
