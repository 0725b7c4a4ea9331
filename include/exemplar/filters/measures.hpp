#pragma once
/// \file
/// Image measures used to judge results.

#include "exemplar/core/image.hpp"

namespace exemplar {

/// Texture detail: the mean squared forward difference (x and y) of the luminance
/// 0.299 R + 0.587 G + 0.114 B (the first channel of images with fewer than 3). Output divided
/// by exemplar gives the "texture kept" figure of the benchmarks (plain averaging of patches
/// washes out to ~0.6). 0 for images narrower or lower than 2 pixels.
///
/// With `region` (1 channel, the image's size): only the differences whose three pixels (x, y),
/// (x + 1, y) and (x, y + 1) are all inside (> 0.5) count, e.g. the filled hole of an inpainting
/// or the known part of its exemplar; 0 when none is.
double gradient_energy(const Image& image, const Image& region = {});

}  // namespace exemplar
