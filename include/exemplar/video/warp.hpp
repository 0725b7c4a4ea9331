#pragma once
/// \file
/// Backward warping (advection) of an image along a flow field.
///
/// Sampling rule shared with the occlusion test: a position p is inside an image of size W x H
/// when -0.5 ≤ p.x ≤ W - 0.5 and -0.5 ≤ p.y ≤ H - 0.5 (within the footprint of the border
/// pixels); inside, values are bilinear between pixel centres with the coordinates clamped to
/// [0, W-1] x [0, H-1]. Written by hand rather than with cv::remap so that any channel count and
/// float data work without conversion and the validity rule is exactly the one χ uses.

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"

namespace exemplar::video {

/// Result of `backward_warp`.
struct WarpResult {
    Image image;  ///< Same channels and names as the source.
    Image valid;  ///< 1 channel "valid": 1 where the sample was inside the source, else 0.
};

/// out(x) = source(x + flow(x)): pulls each output pixel from where the flow points. With the
/// forward flow f of frame t → t+1 and source = frame t+1 this approximates frame t (on pixels
/// that are not occluded). The output has the flow's size; the source may differ in size.
/// Out-of-frame or non-finite samples give 0 in every channel and valid = 0.
/// InvalidArgument if the source is empty or the flow is not a non-empty 2-channel image.
Result<WarpResult> backward_warp(const Image& source, const Image& flow, int threads = 0);

/// Bilinear sample of channel `c` at (x, y) under the rule above; false (and `value` untouched)
/// if (x, y) is outside or not finite.
bool sample_bilinear(const Image& image, float x, float y, int c, float& value);

}  // namespace exemplar::video
