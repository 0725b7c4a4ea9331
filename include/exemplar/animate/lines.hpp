#pragma once
/// \file
/// The distance-transform input of Bénard et al. 2013's line term g_dt (eq. 9): the distance
/// from each pixel to the nearest line pixel, bounded by d_max, so that line drawings of the
/// frames and of the style input guide the synthesis toward the style's strokes without a
/// vector representation of the lines.

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"

namespace exemplar::animate {

/// Distance to the nearest line pixel (channel 0 < 0.5: dark lines on a light background), in
/// pixels (Euclidean, OpenCV's exact distance transform), bounded by `max_distance_px` and
/// divided by it: 1 channel "line_distance" in [0, 1], 0 on the lines, 1 from d_max on.
/// Without any line pixel the result is 1 everywhere. InvalidArgument for an empty image or a
/// non-positive bound.
Result<Image> line_distance(const Image& lines, float max_distance_px);

}  // namespace exemplar::animate
