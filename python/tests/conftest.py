"""Shared inputs of the Python tests: tiny deterministic images made here (no files needed), and
the paths ctest passes (the built `exemplar` command, the source tree)."""

import os
import pathlib

import numpy as np
import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("EXEMPLAR_SOURCE_DIR",
                                         pathlib.Path(__file__).resolve().parents[2]))


def pattern(height, width, channels, phase):
    """A smooth, structured image in 0..255 (uint8): stripes and blobs, so that patches differ."""
    y, x = np.mgrid[0:height, 0:width].astype(np.float64)
    layers = []
    for c in range(channels):
        value = (np.sin(x / (2.0 + c) + phase) * np.cos(y / (3.0 + phase) - c) + 1.0) / 2.0
        value = 0.7 * value + 0.3 * ((x * (c + 1) + y * 3 + phase * 7) % 17) / 17.0
        layers.append(value)
    return np.ascontiguousarray(np.round(np.stack(layers, axis=-1) * 255).astype(np.uint8))


def gradient(height, width, channels=1):
    """A guide: a diagonal ramp with a bump, in 0..255 (uint8)."""
    y, x = np.mgrid[0:height, 0:width].astype(np.float64)
    ramp = (x / width + y / height) / 2.0 + 0.2 * np.exp(-((x - width / 2) ** 2 +
                                                          (y - height / 2) ** 2) / 40.0)
    ramp = np.clip(ramp, 0.0, 1.0)
    return np.ascontiguousarray(
        np.repeat(np.round(ramp * 255).astype(np.uint8)[..., None], channels, axis=-1))


@pytest.fixture
def pair():
    """(style, source guide, target guide), uint8: a 28x24 style, a 32x26 target."""
    return pattern(24, 28, 3, 0.0), gradient(24, 28), gradient(26, 32)[::-1].copy()


@pytest.fixture
def large():
    """Inputs for a run that lasts a while (about half a second on one thread)."""
    return pattern(96, 112, 3, 0.5), gradient(96, 112), gradient(120, 128)


@pytest.fixture
def cli():
    """The built `exemplar` command (ctest passes it as EXEMPLAR_CLI)."""
    path = os.environ.get("EXEMPLAR_CLI")
    if not path:
        pytest.skip("EXEMPLAR_CLI is not set (ctest sets it to the built exemplar command)")
    return path
