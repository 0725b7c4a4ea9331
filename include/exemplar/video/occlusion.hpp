#pragma once
/// \file
/// Occlusion and disocclusion from the forward-backward consistency of two flow fields
/// (the occlusion function χ of Bénard et al. 2013 §3.1).
///
/// With forward flow f (frame t → t+1, on t's grid) and backward flow b (t+1 → t, on t+1's
/// grid), a pixel x of frame t is consistent when following f and then b returns to x:
///     |f(x) + b(x + f(x))|² < ε,
/// with b read by bilinear interpolation. Bénard's χ⁺(x, t) is 1 exactly for consistent pixels
/// (in his notation V⁺_t = f and V⁻_{t+1} = −b). Swapping the arguments (b as "forward", f as
/// "backward") gives the test for frame t+1 against t, i.e. χ⁻(·, t+1).

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"

namespace exemplar::video {

/// Options of `occlusion_mask`.
struct OcclusionOptions {
    /// ε of Bénard et al. §3.1: the largest squared round-trip distance, in px², that still
    /// counts as consistent. Default 2 (the paper's value: about 1.4 px, the rounding of
    /// rasterized velocities); must be finite and > 0. Estimated flow is less precise than
    /// rendered velocities; values of 4..10 suit DIS flow.
    float tolerance_sq_px = 2.0f;
};

/// The occlusion mask of frame t: 1 channel "occluded", 1 where the consistency test fails
/// (the point is occluded in frame t+1, or leaves the frame: x + f(x) outside the image, see
/// `warp.hpp`), 0 where it passes; i.e. 1 − χ. Non-finite flow values (Middlebury's unknown
/// flow is huge but finite and fails the test too) count as occluded.
/// InvalidArgument if either field is not a non-empty 2-channel image, or the sizes differ.
Result<Image> occlusion_mask(const Image& forward, const Image& backward,
                             const OcclusionOptions& options = {}, int threads = 0);

/// Fraction of pixels whose mask value is > 0.5 (statistics and tests).
double occluded_fraction(const Image& mask);

}  // namespace exemplar::video
