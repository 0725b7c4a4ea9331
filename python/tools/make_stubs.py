"""Writes exemplar/__init__.pyi from the built module's option table:

    PYTHONPATH=build/release/python /usr/bin/python3 python/tools/make_stubs.py

Run it after changing an option; tests/test_api.py fails while the stubs are out of date."""

import pathlib

from exemplar import _signatures

path = pathlib.Path(__file__).resolve().parents[1] / "exemplar" / "__init__.pyi"
path.write_text(_signatures.stubs())
print(path)
