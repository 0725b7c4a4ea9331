#!/usr/bin/env bash
# Installs the Debian bookworm packages exemplar builds against, if any are missing.
# Safe to run repeatedly; needs root (or sudo) only when something is missing.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libpng-dev libjpeg-dev libtiff-dev libopenexr-dev  # image files
  libtbb-dev                             # threads
  libhwy-dev                             # SIMD with runtime dispatch
  libcli11-dev nlohmann-json3-dev        # CLI, job files
  libembree-dev libtinyobjloader-dev     # renderer: ray queries, OBJ meshes
  libfmt-dev libspdlog-dev
  libopencv-dev libeigen3-dev libcairo2-dev  # stylit: scan alignment, PCA, PDF sheet
  libtinyxml2-dev                        # sketch: SVG import
  libgtest-dev libbenchmark-dev          # tests and benchmarks
  libpoppler-cpp-dev zlib1g-dev          # tests: the PDF sheet read back
  clang-format ccache                   # formatting; compilations cached across clones
  python3-dev pybind11-dev python3-numpy  # the Python module (python/)
  python3-pytest python3-pip python3-venv   # its tests; pip install . without an index
  python3-distributed                    # exemplar.distributed: frames on a Dask cluster
  libcpp-httplib-dev                     # exemplar studio: the HTTP server
  chromium                               # exemplar studio: its browser test (tests/browser)
)
# The browser test's driver (playwright-core) comes from npm; Debian's nodejs and npm only where
# the machine has no Node.js of its own.
if ! command -v npm > /dev/null; then packages+=(nodejs npm); fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "exemplar: all build dependencies are installed"
else
  echo "exemplar: installing ${missing[*]}"
  SUDO=""
  if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# tests/browser: playwright-core at the version package-lock.json pins (it drives the system's
# chromium and downloads no browser); from npm's cache when it has it.
(cd "$(dirname "$0")/../tests/browser" &&
  npm ci --prefer-offline --no-audit --no-fund --loglevel=error)
