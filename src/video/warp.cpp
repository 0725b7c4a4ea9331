// Backward warping along a flow field (the advection step of Bénard et al. 2013 §3.3 reads
// M_{t-1}(p - V⁻_t) the same way).

#include "exemplar/video/warp.hpp"

#include <algorithm>
#include <cmath>

#include "exemplar/core/parallel.hpp"

namespace exemplar::video {

bool sample_bilinear(const Image& image, float x, float y, int c, float& value) {
    const float w = static_cast<float>(image.width()), h = static_cast<float>(image.height());
    if (!(x >= -0.5f && x <= w - 0.5f && y >= -0.5f && y <= h - 0.5f)) return false;  // and NaN
    x = std::clamp(x, 0.0f, w - 1.0f);
    y = std::clamp(y, 0.0f, h - 1.0f);
    const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
    const int x1 = std::min(x0 + 1, image.width() - 1), y1 = std::min(y0 + 1, image.height() - 1);
    const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
    const float top = image.at(x0, y0, c) + fx * (image.at(x1, y0, c) - image.at(x0, y0, c));
    const float bottom = image.at(x0, y1, c) + fx * (image.at(x1, y1, c) - image.at(x0, y1, c));
    value = top + fy * (bottom - top);
    return true;
}

Result<WarpResult> backward_warp(const Image& source, const Image& flow, int threads) {
    if (source.empty()) return invalid_argument("warp: the source image is empty");
    if (flow.empty() || flow.channels() != 2) {
        return invalid_argument("warp: the flow needs 2 channels (u, v), got " +
                                std::to_string(flow.channels()));
    }
    WarpResult result{Image(flow.width(), flow.height(), source.channels()),
                      Image(flow.width(), flow.height(), 1)};
    result.image.set_channel_names(source.channel_names());
    result.valid.set_channel_names({"valid"});
    parallel_for(0, flow.height(), threads, [&](int y) {
        for (int x = 0; x < flow.width(); ++x) {
            const float sx = static_cast<float>(x) + flow.at(x, y, 0);
            const float sy = static_cast<float>(y) + flow.at(x, y, 1);
            float* out = result.image.pixel(x, y);
            bool inside = true;
            for (int c = 0; c < source.channels() && inside; ++c) {
                inside = sample_bilinear(source, sx, sy, c, out[c]);
            }
            if (!inside) std::fill_n(out, source.channels(), 0.0f);
            result.valid.at(x, y, 0) = inside ? 1.0f : 0.0f;
        }
    });
    return result;
}

}  // namespace exemplar::video
