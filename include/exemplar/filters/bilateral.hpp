#pragma once
/// \file
/// The bilateral filter (Tomasi and Manduchi 1998), as used by Durand and Dorsey (2002) to split
/// an image into a base layer (the filtered image: large-scale variation with its edges kept)
/// and a detail layer (image − base).

#include "exemplar/core/image.hpp"

namespace exemplar {

/// Bilateral filter: every output pixel is the average of the pixels within 2·`sigma_space_px`
/// (a square window, clamped at the borders), weighted by a spatial Gaussian of σ =
/// `sigma_space_px` times a range Gaussian of σ = `sigma_range` on the Euclidean distance of the
/// pixels' values over all channels (so colour edges are kept, channels stay coupled).
/// `sigma_space_px` ≤ 0 or `sigma_range` ≤ 0 returns the input. Both must be finite (checked).
/// Deterministic for any `threads` (0 = all cores, 1 = inline). Cost: (4σ + 1)² per pixel.
Image bilateral_filter(const Image& image, float sigma_space_px, float sigma_range,
                       int threads = 0);

}  // namespace exemplar
