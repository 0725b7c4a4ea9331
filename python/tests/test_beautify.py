"""exemplar.beautify: the CLI's beautification, report and suggestions as Python objects."""

import json
import subprocess

import numpy as np
import pytest

import exemplar
from conftest import SOURCE_DIR

HOUSE = str(SOURCE_DIR / "examples/sketch/house.svg")


@pytest.mark.parametrize("fit", [0.0, 1.0])
def test_the_result_is_the_clis(cli, tmp_path, fit):
    out, report, suggestions = (tmp_path / "clean.svg", tmp_path / "report.json",
                                tmp_path / "suggestions.json")
    subprocess.run([cli, "beautify", HOUSE, "-o", str(out), "--report", str(report),
                    "--suggestions", str(suggestions), "--fit", str(fit), "--max-suggestions",
                    "5", "-q"], check=True)
    result = exemplar.beautify(HOUSE, fit=fit, max_suggestions=5)
    assert result.svg == out.read_text()
    expected = json.loads(report.read_text())
    assert result.strokes == expected["per_stroke"]
    assert result.relation_counts == expected["relation_counts"]
    assert result.suggestions == json.loads(suggestions.read_text())["suggestions"]
    assert len(result.paths) == expected["strokes"] == 14


def test_svg_text_is_the_file():
    with open(HOUSE) as file:
        text = file.read()
    assert exemplar.beautify(text).svg == exemplar.beautify(HOUSE).svg


def test_polylines_are_strokes():
    wobbly = np.array([[0, 0], [50, 1.5], [100, 0]])
    below = np.array([[0, 40], [100, 41]], dtype=np.float32)
    result = exemplar.beautify([wobbly, below])
    assert [stroke["kind"] for stroke in result.strokes] == ["line", "line"]
    assert result.relation_counts["parallel"] == 1
    rules = {relation["rule"] for relation in result.strokes[1]["relations"]}
    assert {"line", "parallel", "equal-length"} <= rules
    assert [s["rank"] for s in result.suggestions] == list(range(1, len(result.suggestions) + 1))


def test_beautify_refuses_what_the_cli_refuses():
    with pytest.raises(exemplar.InvalidArgumentError,
                       match=r"^max_suggestions: 0 is invalid \(must be 1..100\)$"):
        exemplar.beautify(HOUSE, max_suggestions=0)
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^fit: -1.000000 is invalid"):
        exemplar.beautify(HOUSE, fit=-1)
    with pytest.raises(exemplar.InvalidArgumentError, match="^drawing: the drawing has no strokes"):
        exemplar.beautify('<svg xmlns="http://www.w3.org/2000/svg"></svg>')
    with pytest.raises(exemplar.InvalidArgumentError, match="^drawing: not valid XML"):
        exemplar.beautify("<svg")
    with pytest.raises(exemplar.IoError, match="missing.svg"):
        exemplar.beautify("missing.svg")
    with pytest.raises(exemplar.InvalidArgumentError,
                       match=r"^drawing: stroke 0 is degenerate \(a single point\)$"):
        exemplar.beautify([np.zeros((3, 2))])
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^drawing\[1\]: must be an Nx2"):
        exemplar.beautify([np.ones((3, 2)).cumsum(0), np.zeros((3, 3))])
    with pytest.raises(exemplar.InvalidArgumentError, match=r"^drawing\[0\]: contains NaN"):
        exemplar.beautify([np.array([[0, 0], [np.nan, 1]])])
    with pytest.raises(TypeError, match="^drawing: must be SVG text"):
        exemplar.beautify(5)
    with pytest.raises(TypeError, match="unexpected keyword argument 'threads'"):
        exemplar.beautify(HOUSE, threads=1)
