#pragma once
/// \file
/// Resampling and image pyramids.

#include <vector>

#include "exemplar/core/image.hpp"

namespace exemplar {

/// Reconstruction filter for resampling.
enum class ResampleFilter {
    Box,       ///< Area average when shrinking, nearest-like when enlarging.
    Gaussian,  ///< Gaussian (sigma 0.5 output pixel per unit scale), smooth, no ringing.
    Lanczos3,  ///< Sharp, windowed sinc with 3 lobes (may ring slightly).
    Nearest,   ///< Point sampling (for labels, masks and indices).
};

/// Resizes to `width` x `height` with a separable filter scaled to the reduction factor.
/// Borders clamp. All channels are filtered independently. `threads`: 0 = all, 1 = inline.
Image resize(const Image& image, int width, int height, ResampleFilter filter,
             int threads = 0);

/// Blurs with a separable Gaussian of standard deviation `sigma_px` (clamped borders).
Image gaussian_blur(const Image& image, float sigma_px, int threads = 0);

/// Size of pyramid level `level` (0 = full resolution) for a given ratio (0 < ratio < 1):
/// max(1, round(size * ratio^level)).
int pyramid_level_size(int size, float ratio, int level);

/// Gaussian pyramid: level 0 is `image`, level i has size pyramid_level_size(.., ratio, i),
/// obtained by Gaussian-prefiltered resampling of the full-resolution image. `levels` ≥ 1.
/// ratio 0.5 is the classic octave pyramid; 0.85 gives the fine pyramids some papers use.
std::vector<Image> gaussian_pyramid(const Image& image, int levels, float ratio,
                                    ResampleFilter filter = ResampleFilter::Gaussian,
                                    int threads = 0);

}  // namespace exemplar
