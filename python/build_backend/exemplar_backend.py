"""A PEP 517 build backend for `pip install .` without a package index.

pip's default backend (setuptools) would have to be fetched into the isolated build environment;
this one needs only the standard library, cmake and a C++ compiler (scripts/install-deps.sh).
build_wheel configures the project with CMake (Release, no tests or benchmarks, the Python module
for the interpreter running pip), builds the target `exemplar_python` and zips the package folder
it lays out (build/python/exemplar/) into a wheel. The extension links the library statically, so
the wheel holds everything but the Debian libraries it uses.

A configured build folder can be reused (no rebuild of the library, as the tests do):
    EXEMPLAR_BUILD_DIR=build/release python3 -m pip install --no-index .
or `--config-settings build-dir=build/release`. Otherwise the build runs in a temporary folder
(CMAKE_BUILD_PARALLEL_LEVEL sets the jobs; default 2).
"""

import base64
import hashlib
import os
import pathlib
import re
import shutil
import subprocess
import sys
import sysconfig
import tarfile
import tempfile
import zipfile

_SOURCE = pathlib.Path(__file__).resolve().parents[2]
_NAME = "exemplar"
_SUMMARY = ("Example-based stylization: guided patch-based synthesis (StyLit) with numpy arrays")


def _version():
    text = (_SOURCE / "CMakeLists.txt").read_text()
    return re.search(r"project\(exemplar VERSION ([0-9.]+)", text).group(1)


def _metadata():
    return (f"Metadata-Version: 2.1\nName: {_NAME}\nVersion: {_version()}\n"
            f"Summary: {_SUMMARY}\nRequires-Python: >=3.9\nRequires-Dist: numpy\n"
            "\nSee docs/python.md in the source tree.\n")


def _tag():
    # The interpreter running pip is the one the module is built for.
    impl = f"cp{sys.version_info.major}{sys.version_info.minor}"
    platform = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return f"{impl}-{impl}-{platform}"


def _build_package(config_settings):
    """Builds the module; returns the build folder, whether it is a temporary one, and the
    package folder (build/python/exemplar)."""
    if shutil.which("cmake") is None:
        raise RuntimeError("exemplar: building the wheel needs cmake (scripts/install-deps.sh)")
    settings = config_settings or {}
    reuse = settings.get("build-dir") or os.environ.get("EXEMPLAR_BUILD_DIR")
    temporary = not reuse
    if reuse:
        build = pathlib.Path(reuse)
        if not build.is_absolute():
            build = _SOURCE / build
        if not (build / "CMakeCache.txt").exists():
            raise RuntimeError(f"exemplar: {build} is not a configured build folder")
    else:
        build = pathlib.Path(tempfile.mkdtemp(prefix="exemplar-wheel-"))
    try:
        if temporary:
            subprocess.run(["cmake", "-S", str(_SOURCE), "-B", str(build),
                            "-DCMAKE_BUILD_TYPE=Release", "-DEXEMPLAR_BUILD_TESTS=OFF",
                            "-DEXEMPLAR_BUILD_BENCH=OFF", "-DEXEMPLAR_PYTHON=ON",
                            f"-DEXEMPLAR_PYTHON_EXECUTABLE={sys.executable}"],
                           check=True, stdout=sys.stderr)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", "2")
        subprocess.run(["cmake", "--build", str(build), "--target", "exemplar_python", "-j",
                        jobs], check=True, stdout=sys.stderr)
    except BaseException:
        if temporary:
            shutil.rmtree(build, ignore_errors=True)
        raise
    return build, temporary, build / "python" / _NAME


def _record_line(name, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{name},sha256={digest},{len(data)}"


def get_requires_for_build_wheel(config_settings=None):
    return []


def get_requires_for_build_sdist(config_settings=None):
    return []


def prepare_metadata_for_build_wheel(metadata_directory, config_settings=None):
    """The dist-info folder without building (pip asks for it before the wheel)."""
    info = pathlib.Path(metadata_directory) / f"{_NAME}-{_version()}.dist-info"
    info.mkdir(parents=True, exist_ok=True)
    (info / "METADATA").write_text(_metadata())
    (info / "WHEEL").write_text(_wheel_text())
    return info.name


def _wheel_text():
    return (f"Wheel-Version: 1.0\nGenerator: exemplar_backend\nRoot-Is-Purelib: false\n"
            f"Tag: {_tag()}\n")


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    build, temporary, package = _build_package(config_settings)
    try:
        return _zip_wheel(wheel_directory, package)
    finally:
        if temporary:  # a whole build of the library: do not leave it in /tmp
            shutil.rmtree(build, ignore_errors=True)


def _zip_wheel(wheel_directory, package):
    suffix = sysconfig.get_config_var("EXT_SUFFIX")
    if not (package / f"_exemplar{suffix}").exists():
        raise RuntimeError(f"exemplar: the build made no _exemplar{suffix} in {package} (built "
                           "for another Python? set EXEMPLAR_PYTHON_EXECUTABLE)")
    files = {}
    for path in sorted(package.iterdir()):
        if path.suffix in (".py", ".pyi", ".typed") or path.name == f"_exemplar{suffix}":
            files[f"{_NAME}/{path.name}"] = path.read_bytes()
    info = f"{_NAME}-{_version()}.dist-info"
    files[f"{info}/METADATA"] = _metadata().encode()
    files[f"{info}/WHEEL"] = _wheel_text().encode()
    files[f"{info}/top_level.txt"] = f"{_NAME}\n".encode()
    record = [_record_line(name, data) for name, data in files.items()] + [f"{info}/RECORD,,"]
    files[f"{info}/RECORD"] = ("\n".join(record) + "\n").encode()
    wheel = f"{_NAME}-{_version()}-{_tag()}.whl"
    with zipfile.ZipFile(pathlib.Path(wheel_directory) / wheel, "w", zipfile.ZIP_DEFLATED) as z:
        for name, data in files.items():
            info_entry = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
            mode = 0o755 if name.endswith(".so") else 0o644
            info_entry.external_attr = (0o100000 | mode) << 16
            z.writestr(info_entry, data, zipfile.ZIP_DEFLATED)
    return wheel


def build_sdist(sdist_directory, config_settings=None):
    """The tracked source files (git ls-files) with PKG-INFO, as exemplar-VERSION.tar.gz."""
    listed = subprocess.run(["git", "ls-files", "-z"], cwd=_SOURCE, check=True,
                            capture_output=True).stdout.decode().split("\0")
    base = f"{_NAME}-{_version()}"
    name = f"{base}.tar.gz"
    with tempfile.TemporaryDirectory() as scratch:
        info = pathlib.Path(scratch) / "PKG-INFO"
        info.write_text(_metadata())
        with tarfile.open(pathlib.Path(sdist_directory) / name, "w:gz") as tar:
            tar.add(info, f"{base}/PKG-INFO")
            for file in filter(None, listed):
                tar.add(_SOURCE / file, f"{base}/{file}", recursive=False)
    return name
