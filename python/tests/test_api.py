"""The Python API is generated from the library's option table: signatures, docstrings, stubs,
and the same options as the CLI."""

import inspect
import pathlib
import subprocess

import numpy as np

import exemplar
from conftest import pattern
from exemplar import _exemplar, _signatures

PACKAGE = pathlib.Path(__file__).resolve().parents[1] / "exemplar"


def test_every_option_of_the_table_is_a_keyword_with_its_default():
    specs = exemplar.option_specs()
    assert len(specs) > 15
    # stylize and stylit start from the default quality preset: its values are the defaults
    # shown, the table's elsewhere.
    preset = dict(_exemplar._stylize_defaults())
    assert preset["vote_coherence"] == 2 and preset["finest_em_iterations"] == 1
    for verb in (exemplar.stylize, exemplar.stylit):
        parameters = inspect.signature(verb).parameters
        for spec in specs:
            parameter = parameters[spec["name"]]
            assert parameter.kind == inspect.Parameter.KEYWORD_ONLY
            assert parameter.default == preset[spec["name"]]
            assert " ".join(spec["doc"].split()) in " ".join(verb.__doc__.split())
    patch = next(spec for spec in specs if spec["name"] == "patch_size")
    assert (patch["type"], patch["min"], patch["max"], patch["default"]) == ("int", 3, 31, 5)
    coverage = next(spec for spec in specs if spec["name"] == "budget_coverage")
    assert coverage["default"] == 0.95


def test_every_keyword_of_the_signature_is_accepted_with_its_default(pair):
    # Each documented keyword reaches the extension, and its documented default is the one
    # the run uses (spelling every default out changes nothing).
    style, source, target = pair
    plain = exemplar.stylize(style, [(source, target)])
    defaults = {name: p.default for name, p in inspect.signature(exemplar.stylize).parameters.items()
                if p.kind == inspect.Parameter.KEYWORD_ONLY}
    np.testing.assert_array_equal(exemplar.stylize(style, [(source, target)], **defaults).image,
                                  plain.image)
    buffers = [pattern(24, 28, 3, phase) for phase in (1.0, 2.0)]
    targets = [pattern(26, 32, 3, phase) for phase in (1.5, 2.5)]
    defaults = {name: p.default for name, p in inspect.signature(exemplar.stylit).parameters.items()
                if p.kind == inspect.Parameter.KEYWORD_ONLY}
    np.testing.assert_array_equal(
        exemplar.stylit(style, buffers, targets, **defaults).image,
        exemplar.stylit(style, buffers, targets).image)


def test_the_options_are_the_clis_flags(cli):
    help_text = subprocess.run([cli, "stylize", "--help-all"], check=True, capture_output=True,
                               text=True).stdout
    for spec in exemplar.option_specs():
        assert "--" + spec["name"].replace("_", "-") in help_text


def test_the_stubs_are_up_to_date():
    assert (PACKAGE / "__init__.pyi").read_text() == _signatures.stubs(), (
        "python/exemplar/__init__.pyi is out of date: run python/tools/make_stubs.py")
    assert (PACKAGE / "py.typed").exists()
    compile((PACKAGE / "__init__.pyi").read_text(), "__init__.pyi", "exec")


def test_the_stubs_name_what_the_package_exports():
    stub = (PACKAGE / "__init__.pyi").read_text()
    for name in exemplar.__all__:
        assert f"def {name}(" in stub or f"class {name}" in stub or f"{name}:" in stub, name


def test_load_and_save_round_trip(tmp_path):
    image = np.arange(5 * 7 * 3, dtype=np.uint8).reshape(5, 7, 3)
    exemplar.save_image(image, str(tmp_path / "a.png"))
    loaded = exemplar.load_image(str(tmp_path / "a.png"))
    assert loaded.dtype == np.float32 and loaded.shape == (5, 7, 3)
    np.testing.assert_array_equal(np.round(loaded * 255).astype(np.uint8), image)
    values = np.linspace(-2, 3, 5 * 7 * 2, dtype=np.float32).reshape(5, 7, 2)
    exemplar.save_image(values, str(tmp_path / "b.tif"))
    np.testing.assert_array_equal(exemplar.load_image(str(tmp_path / "b.tif")), np.clip(
        np.round(values * 65535) / 65535, 0, 1).astype(np.float32))
