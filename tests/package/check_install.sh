#!/usr/bin/env bash
# Installs a build of exemplar into a temporary prefix and builds two programs against it, as a
# user's project would: tests/package/consumer with find_package(exemplar CONFIG), and the same
# source with pkg-config and g++ alone. Each must run and stylize an image.
#   check_install.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
source=$2
work=$(mktemp -d /tmp/exemplar-package.XXXXXX)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix

cmake --install "$build" --prefix "$prefix" > "$work/install.log"
test -f "$prefix/include/exemplar/synth/synthesize.hpp"
test -x "$prefix/bin/exemplar"
# The installed command finds its plugins in lib/exemplar/: OpenCV (flow), Embree (render),
# OpenEXR (the .exr), libtiff and Cairo (the sketch preview).
(
  unset EXEMPLAR_PLUGIN_DIR
  "$prefix/bin/exemplar" --version > /dev/null
  "$prefix/bin/exemplar" flow --from "$source/tests/data/flow/synthetic-img0.png" \
    --to "$source/tests/data/flow/synthetic-img1.png" -o "$work/flow.flo" -q
  "$prefix/bin/exemplar" render --scene sphere-on-table --width 16 --height 12 --spp 1 \
    -o "$work/sphere.exr" -q
  "$prefix/bin/exemplar" beautify "$source/examples/sketch/house.svg" -o "$work/house.svg" \
    --preview "$work/house.png" -q
  test -s "$work/flow.flo" && test -s "$work/sphere.exr" && test -s "$work/house.png"
)
# A manual page per verb, generated from the parser (apps/cli/man_main.cpp); man renders the
# stylize page with its flags as typed.
for page in exemplar exemplar-stylize exemplar-stylit exemplar-stylit-sheet exemplar-animate; do
  head -n 1 "$prefix/share/man/man1/$page.1" | grep -q '^\.TH '
done
if command -v man > /dev/null; then
  MANWIDTH=100 man -l "$prefix/share/man/man1/exemplar-stylize.1" 2> /dev/null |
    grep -q -- '--patch-size'
fi

# CMake package.
cmake -S "$source/tests/package/consumer" -B "$work/cmake" -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/cmake" > "$work/build.log"
"$work/cmake/consumer" "$work/cmake.png"

# pkg-config module (relocatable: found through PKG_CONFIG_PATH under any prefix).
pc_dir=$(dirname "$(find "$prefix" -name exemplar.pc)")
flags=$(PKG_CONFIG_PATH=$pc_dir pkg-config --cflags --libs exemplar)
libdir=$(PKG_CONFIG_PATH=$pc_dir pkg-config --variable=libdir exemplar)
# shellcheck disable=SC2086
g++ "$source/tests/package/consumer/main.cpp" $flags -Wl,-rpath,"$libdir" -o "$work/pc"
"$work/pc" "$work/pc.png"

# The Python package (when built: EXEMPLAR_PYTHON), in Debian's dist-packages under the prefix:
# it imports from there, not from the build tree, and runs.
if grep -q '^EXEMPLAR_PYTHON:BOOL=ON' "$build/CMakeCache.txt"; then
  python=$(sed -n 's/^EXEMPLAR_PYTHON_EXECUTABLE:FILEPATH=//p' "$build/CMakeCache.txt")
  site=$prefix/lib/python3/dist-packages
  test -f "$site/exemplar/__init__.pyi" && test -f "$site/exemplar/py.typed"
  (cd "$work" && PYTHONPATH=$site "$python" -c '
import pathlib, sys
import numpy as np
import exemplar
assert pathlib.Path(exemplar.__file__).parent == pathlib.Path(sys.argv[1]).resolve(), exemplar.__file__
style = (np.arange(20 * 24 * 3) % 251).astype(np.uint8).reshape(20, 24, 3)
result = exemplar.stylize(style, size=(30, 26), patch_size=3)
assert result.image.shape == (26, 30, 3) and result.image.dtype == np.uint8
' "$site/exemplar")
  echo "package: import exemplar works from $site"
fi
echo "package: CMake and pkg-config consumers built and ran against $prefix"
