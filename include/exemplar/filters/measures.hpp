#pragma once
/// \file
/// Image measures used to judge results.

#include "exemplar/core/image.hpp"

namespace exemplar {

/// Texture detail: the mean squared forward difference (x and y) of the luminance
/// 0.299 R + 0.587 G + 0.114 B (the first channel of images with fewer than 3). Output divided
/// by exemplar gives the "texture kept" figure of the benchmarks (plain averaging of patches
/// washes out to ~0.6). 0 for images narrower or lower than 2 pixels.
double gradient_energy(const Image& image);

}  // namespace exemplar
