#pragma once
/// \file
/// Resampling and image pyramids.
///
/// Conventions: pixel centres are aligned (output pixel x of an axis resized from `in` to `out`
/// pixels samples input position (x + 0.5) * in / out - 0.5), borders are clamped (the edge
/// pixel repeats), every channel is filtered independently, and filter weights are normalized,
/// so a constant image stays constant. Results are deterministic and bit-identical for any
/// `threads` value (0 = all cores, 1 = inline on the caller). Invalid sizes or ratios are
/// programming errors and abort through EXEMPLAR_CHECK (callers validate user options first).

#include <vector>

#include "exemplar/core/image.hpp"

namespace exemplar {

/// Reconstruction filter for resampling. When shrinking by a factor f = in / out > 1, the
/// kernels below are widened by f (measured in input pixels) so that they prefilter.
enum class ResampleFilter {
    Box,       ///< Area average when shrinking (exact pixel-overlap weights, any ratio);
               ///< nearest pixel when enlarging.
    Gaussian,  ///< Gaussian (sigma 0.5 output pixel per unit scale, i.e. 0.5 * max(1, f) input
               ///< pixels, truncated at 3 sigma), smooth, no ringing.
    Lanczos3,  ///< Sharp, windowed sinc with 3 lobes (may ring slightly, values may leave the
               ///< input range near edges).
    Nearest,   ///< Point sampling (for labels, masks and indices): every output value is exactly
               ///< one input value, input pixel floor((x + 0.5) * in / out).
};

/// Resizes to `width` x `height` (each ≥ 1, checked) with a separable filter scaled to the
/// reduction factor. Borders clamp. All channels are filtered independently; channel names are
/// kept. An axis whose size does not change is copied unchanged, so resizing to the same size
/// returns the input exactly for every filter. An empty input returns an empty image.
/// `threads`: 0 = all, 1 = inline.
Image resize(const Image& image, int width, int height, ResampleFilter filter, int threads = 0);

/// Blurs with a separable Gaussian of standard deviation `sigma_px` (in pixels, truncated at
/// 3 sigma, clamped borders). `sigma_px` ≤ 0 returns the input unchanged; it must be finite
/// (checked). Cost grows linearly with sigma.
Image gaussian_blur(const Image& image, float sigma_px, int threads = 0);

/// Size of pyramid level `level` (0 = full resolution) for a given ratio (0 < ratio < 1):
/// max(1, round(size * ratio^level)), halves rounded away from zero. Requires size ≥ 1 and
/// level ≥ 0 (checked).
int pyramid_level_size(int size, float ratio, int level);

/// Gaussian pyramid: level 0 is `image`, level i has size pyramid_level_size(.., ratio, i),
/// obtained by Gaussian-prefiltered resampling of the full-resolution image. `levels` ≥ 1.
/// ratio 0.5 is the classic octave pyramid; 0.85 gives the fine pyramids some papers use.
/// `filter` chooses the resampling filter of every level (Nearest for label maps, Box for
/// masks). An empty image gives `levels` empty images. Invalid `levels` or `ratio` abort
/// (checked).
std::vector<Image> gaussian_pyramid(const Image& image, int levels, float ratio,
                                    ResampleFilter filter = ResampleFilter::Gaussian,
                                    int threads = 0);

}  // namespace exemplar
