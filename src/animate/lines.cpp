// Bounded distance transform of line drawings (Bénard et al. 2013 §3.2, g_dt) with OpenCV.

#include "exemplar/animate/lines.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

namespace exemplar::animate {

Result<Image> line_distance(const Image& lines, float max_distance_px) {
    if (lines.empty()) return invalid_argument("lines: image is empty");
    if (!(std::isfinite(max_distance_px) && max_distance_px > 0.0f)) {
        return invalid_argument("line-max-distance: " + std::to_string(max_distance_px) +
                                " is invalid (must be > 0 px)");
    }
    // distanceTransform measures the distance to the nearest zero pixel: lines become 0.
    cv::Mat binary(lines.height(), lines.width(), CV_8UC1);
    for (int y = 0; y < lines.height(); ++y) {
        auto* row = binary.ptr<std::uint8_t>(y);
        for (int x = 0; x < lines.width(); ++x) row[x] = lines.at(x, y, 0) < 0.5f ? 0 : 255;
    }
    Image out(lines.width(), lines.height(), 1, 1.0f);
    out.set_channel_names({"line_distance"});
    if (cv::countNonZero(binary) == static_cast<int>(binary.total())) return out;  // no line
    cv::Mat distance;
    cv::distanceTransform(binary, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
    for (int y = 0; y < lines.height(); ++y) {
        const float* row = distance.ptr<float>(y);
        for (int x = 0; x < lines.width(); ++x) {
            out.at(x, y, 0) = std::min(row[x], max_distance_px) / max_distance_px;
        }
    }
    return out;
}

}  // namespace exemplar::animate
