#!/usr/bin/env bash
# `pip install .` with no package index: pip builds a wheel with the in-tree backend
# (pyproject.toml, python/build_backend), reusing BUILD_DIR so that nothing is rebuilt. Checked
# twice, never touching the system: Debian's pip makes the wheel (its RECORD must list every file
# with its hash), and the pip of a temporary venv that sees Debian's packages (numpy) installs
# the source tree; the installed package imports from the venv and runs.
#   check_pip.sh BUILD_DIR SOURCE_DIR PYTHON
set -euo pipefail
build=$1
source=$2
python=$3
work=$(mktemp -d /tmp/exemplar-pip.XXXXXX)
trap 'rm -rf "$work"' EXIT

run_pip() {
  local pip=$1
  shift
  if ! (cd "$source" && EXEMPLAR_BUILD_DIR=$build $pip "$@" --no-index \
          --no-cache-dir --disable-pip-version-check . > "$work/pip.log" 2>&1); then
    cat "$work/pip.log"
    exit 1
  fi
}
run_pip "$python -m pip" wheel --no-deps --wheel-dir "$work/wheels"
"$python" -m venv --system-site-packages "$work/venv"
run_pip "$work/venv/bin/python -m pip" install

cd "$work"
"$python" - "$work/wheels"/exemplar-*.whl <<'PYTHON'
import base64, hashlib, sys, zipfile
with zipfile.ZipFile(sys.argv[1]) as wheel:
    names = set(wheel.namelist())
    record = [line.split(",") for line in wheel.read(next(n for n in names if n.endswith(
        ".dist-info/RECORD"))).decode().splitlines()]
    assert {name for name, _, _ in record} == names, (names, record)
    for name, digest, size in record:
        if digest:
            data = wheel.read(name)
            expected = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=")
            assert digest == "sha256=" + expected.decode() and int(size) == len(data), name
    for needed in ("exemplar/__init__.py", "exemplar/__init__.pyi", "exemplar/py.typed"):
        assert needed in names, needed
PYTHON
"$work/venv/bin/python" -c '
import pathlib, sys
import numpy as np
import exemplar
assert pathlib.Path(exemplar.__file__).parent == pathlib.Path(sys.argv[1]).resolve(), exemplar.__file__
style = (np.arange(20 * 24 * 3) % 251).astype(np.uint8).reshape(20, 24, 3)
assert exemplar.stylize(style, size=(30, 26), patch_size=3).image.shape == (26, 30, 3)
' "$("$work/venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["platlib"])')/exemplar"
echo "pip: built a wheel and installed the source tree into a venv without a package index"
