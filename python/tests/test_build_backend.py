"""The in-tree PEP 517 backend (python/build_backend) behind `pip install .`: metadata without a
build, no temporary build folder left behind, an sdist of the tracked files. The wheel itself is
built and installed by tests/package/check_pip.sh (ctest Package.PipInstallWithoutIndex)."""

import importlib.util
import re
import subprocess
import tarfile

import pytest

from conftest import SOURCE_DIR


@pytest.fixture
def backend():
    path = SOURCE_DIR / "python/build_backend/exemplar_backend.py"
    spec = importlib.util.spec_from_file_location("exemplar_backend", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def project_version():
    text = (SOURCE_DIR / "CMakeLists.txt").read_text()
    return re.search(r"project\(exemplar VERSION ([0-9.]+)", text).group(1)


def test_pip_gets_the_metadata_without_a_build(backend, tmp_path):
    assert backend.get_requires_for_build_wheel() == []
    name = backend.prepare_metadata_for_build_wheel(str(tmp_path))
    assert name == f"exemplar-{project_version()}.dist-info"
    metadata = (tmp_path / name / "METADATA").read_text()
    assert "Name: exemplar\n" in metadata and f"Version: {project_version()}\n" in metadata
    assert "Requires-Dist: numpy" in metadata
    assert re.search(r"Tag: cp3\d+-cp3\d+-linux_", (tmp_path / name / "WHEEL").read_text())


def test_a_failed_build_leaves_no_temporary_folder(backend, tmp_path, monkeypatch):
    scratch = tmp_path / "exemplar-wheel-x"
    scratch.mkdir()
    monkeypatch.delenv("EXEMPLAR_BUILD_DIR", raising=False)
    monkeypatch.setattr(backend.tempfile, "mkdtemp", lambda prefix: str(scratch))

    def fail(command, **kwargs):
        raise subprocess.CalledProcessError(1, command)

    monkeypatch.setattr(backend.subprocess, "run", fail)
    with pytest.raises(subprocess.CalledProcessError):
        backend.build_wheel(str(tmp_path))
    assert not scratch.exists()


def test_a_reused_folder_must_be_configured(backend, tmp_path):
    with pytest.raises(RuntimeError, match="is not a configured build folder"):
        backend.build_wheel(str(tmp_path), {"build-dir": str(tmp_path)})


def test_the_sdist_holds_the_tracked_files(backend, tmp_path):
    if not (SOURCE_DIR / ".git").exists():
        pytest.skip("the source tree is not a git checkout")
    name = backend.build_sdist(str(tmp_path))
    base = f"exemplar-{project_version()}"
    assert name == f"{base}.tar.gz"
    with tarfile.open(tmp_path / name) as tar:
        names = set(tar.getnames())
    for needed in ("PKG-INFO", "pyproject.toml", "CMakeLists.txt", "python/exemplar/__init__.py",
                   "python/build_backend/exemplar_backend.py", "src/synth/synthesize.cpp"):
        assert f"{base}/{needed}" in names, needed
    assert not any("/build/" in n for n in names)
