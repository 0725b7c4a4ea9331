#!/usr/bin/env bash
# Builds the .deb of a build of exemplar (cpack -G DEB) and checks it without installing it:
# its Depends (from dpkg-shlibdeps) name the Debian packages of the libraries it links, it holds
# the command, the library, the headers and the CMake/pkg-config files under /usr, and the
# command inside runs.
#   check_deb.sh BUILD_DIR
set -euo pipefail
build=$1
work=$(mktemp -d /tmp/exemplar-deb.XXXXXX)
trap 'rm -rf "$work"' EXIT

(cd "$build" && cpack -G DEB -B "$work" > "$work/cpack.log" 2>&1) || {
  cat "$work/cpack.log" >&2
  exit 1
}
deb=$(ls "$work"/exemplar_*_amd64.deb 2> /dev/null || ls "$work"/exemplar_*.deb)
depends=$(dpkg-deb --field "$deb" Depends)
for package in libpng16-16 libjpeg62-turbo libtiff6 libopenexr-3-1-30 libtbb12 libstdc++6; do
  if [[ $depends != *"$package"* ]]; then
    echo "check_deb: Depends lacks $package: $depends" >&2
    exit 1
  fi
done
if [[ $depends == *openimageio* ]]; then
  echo "check_deb: Depends still names OpenImageIO: $depends" >&2
  exit 1
fi
contents=$(dpkg-deb --contents "$deb")
for file in ./usr/bin/exemplar ./usr/lib/libexemplar.so ./usr/include/exemplar/synth/synthesize.hpp \
  ./usr/lib/cmake/exemplar/exemplarConfig.cmake ./usr/lib/pkgconfig/exemplar.pc \
  ./usr/lib/exemplar/libexemplar_video_mp4.so ./usr/lib/exemplar/libexemplar_opencv.so \
  ./usr/lib/exemplar/libexemplar_render_embree.so ./usr/lib/exemplar/libexemplar_cairo.so \
  ./usr/lib/exemplar/libexemplar_openexr.so ./usr/lib/exemplar/libexemplar_tiff.so \
  ./usr/lib/exemplar/libexemplar_http.so \
  ./usr/share/man/man1/exemplar-stylize.1; do
  if ! grep -qF " $file" <<< "$contents"; then
    echo "check_deb: $deb has no $file" >&2
    exit 1
  fi
done
# apt accepts the package and resolves its Depends (simulated: nothing is installed).
if command -v apt-get > /dev/null; then
  apt-get install -s "$deb" > "$work/apt.log" 2>&1 || {
    cat "$work/apt.log" >&2
    exit 1
  }
fi
# The Python package, when built (EXEMPLAR_PYTHON): in Debian's dist-packages, with numpy and
# the Python it was built for among the Depends.
if grep -q '^EXEMPLAR_PYTHON:BOOL=ON' "$build/CMakeCache.txt"; then
  for file in ./usr/lib/python3/dist-packages/exemplar/__init__.py \
    ./usr/lib/python3/dist-packages/exemplar/__init__.pyi; do
    if ! grep -qF " $file" <<< "$contents"; then
      echo "check_deb: $deb has no $file" >&2
      exit 1
    fi
  done
  if ! grep -q ' ./usr/lib/python3/dist-packages/exemplar/_exemplar\.cpython-.*\.so' <<< "$contents"; then
    echo "check_deb: $deb has no Python extension module" >&2
    exit 1
  fi
  for package in python3-numpy "python3 (>= "; do
    if [[ $depends != *"$package"* ]]; then
      echo "check_deb: Depends lacks $package: $depends" >&2
      exit 1
    fi
  done
fi
dpkg-deb -x "$deb" "$work/root"
"$work/root/usr/bin/exemplar" --version
echo "deb: $(basename "$deb"), Depends: $depends"
