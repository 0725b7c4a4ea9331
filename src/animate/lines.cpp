// Bounded distance transform of line drawings (Bénard et al. 2013 §3.2, g_dt) with OpenCV
// (through its plugin, src/plugin/opencv_kernels.hpp).

#include "exemplar/animate/lines.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "opencv_kernels.hpp"

namespace exemplar::animate {

Result<Image> line_distance(const Image& lines, float max_distance_px) {
    if (lines.empty()) return invalid_argument("lines: image is empty");
    if (!(std::isfinite(max_distance_px) && max_distance_px > 0.0f)) {
        return invalid_argument("line-max-distance: " + std::to_string(max_distance_px) +
                                " is invalid (must be > 0 px)");
    }
    // distanceTransform measures the distance to the nearest zero pixel: lines become 0.
    const int w = lines.width(), h = lines.height();
    std::vector<std::uint8_t> binary(static_cast<std::size_t>(w) * h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) binary[y * w + x] = lines.at(x, y, 0) < 0.5f ? 0 : 255;
    }
    Image out(w, h, 1, 1.0f);
    out.set_channel_names({"line_distance"});
    if (std::find(binary.begin(), binary.end(), 0) == binary.end()) return out;  // no line
    auto opencv = plugin::opencv::kernels();
    if (!opencv.ok()) return Status(opencv.status().code(), "lines: " + opencv.status().message());
    std::vector<float> distance(binary.size());
    (*opencv)->distance_to_zero(binary.data(), w, h, distance.data());
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            out.at(x, y, 0) = std::min(distance[y * w + x], max_distance_px) / max_distance_px;
        }
    }
    return out;
}

}  // namespace exemplar::animate
