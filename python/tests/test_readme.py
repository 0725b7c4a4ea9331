"""The Python example of the README (and of docs/python.md) runs as written."""

import re

import numpy as np

import exemplar
from conftest import SOURCE_DIR


def python_blocks(path):
    return re.findall(r"```python\n(.*?)```", (SOURCE_DIR / path).read_text(), re.S)


def test_the_readme_example_runs_as_written(tmp_path, monkeypatch):
    example = python_blocks("README.md")[0]
    assert len(example.strip().splitlines()) == 5
    assert python_blocks("docs/python.md")[0] == example
    # From a folder that looks like the repository's root, so that the output lands in tmp_path.
    (tmp_path / "examples").symlink_to(SOURCE_DIR / "examples")
    monkeypatch.chdir(tmp_path)
    exec(compile(example, "README.md", "exec"), {})
    image = exemplar.load_image(str(tmp_path / "stylized.png"))
    painting = exemplar.load_image(str(SOURCE_DIR / "examples/stylit/source_style.png"))
    # The preview: half the target render's size, the painting's colours.
    assert image.shape == (228, 300, 3)
    assert np.abs(image.mean(axis=(0, 1)) - painting.mean(axis=(0, 1))).max() < 0.1
