#!/usr/bin/env bash
# Makes the image files tests/io/image_formats_test.cpp reads: one small picture in the layouts
# other tools write (tiled, planar, compressed, ASCII, data windows, extra channels), made with
# OpenImageIO 2.4's oiiotool (Debian bookworm, `openimageio-tools`), which many pipelines use.
# Not run by the build or the tests: the files are committed. Run from this folder.
set -euo pipefail
src=../../../examples/stylit/source_style.png
# reference: a 24x16 crop of the bundled StyLit painting, 8-bit RGB
oiiotool "$src" --cut 24x16+300+200 -d uint8 -o reference.png
oiiotool reference.png -d uint16 -o rgb16.png
oiiotool reference.png -d uint8 --tile 16 16 --compression lzw -o tiled_lzw.tif
oiiotool reference.png -d uint16 --planarconfig separate -o planar16.tif
oiiotool reference.png --ch R,G,B,A=0.5,E=0.25 -d float -o extra_float.tif
oiiotool reference.png --ch R -d uint8 -o grey.tif
oiiotool reference.png -d half --tile 16 16 --compression piz -o tiled_piz.exr
oiiotool reference.png -d float --origin +5+3 --fullsize 40x30+0+0 -o window.exr
oiiotool reference.png -d uint8 --attrib pnm:binary 0 -o ascii.ppm
oiiotool reference.png -d uint8 --ch R --attrib pnm:binary 0 -o ascii.pgm
oiiotool reference.png -d uint8 --ch R -o grey.jpg
