#include "rotated_copies.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>

#include "exemplar/core/parallel.hpp"

namespace exemplar::synth {

RotatedOffset copy_source_pixel(const RotatedCopy& copy, int qx, int qy, int sw, int sh) {
    const RotatedOffset p =
        rotate_offset(qx - copy.origin_x, qy - copy.origin_y, copy.cos, copy.sin);
    return {std::clamp(p.dx, 0, sw - 1), std::clamp(p.dy, 0, sh - 1)};
}

void build_rotated_copies(Level& L, int threads) {
    const int n = L.orientation_steps;
    const int F = L.feature_channels();
    // Every source centre's patch (radius r) lies inside its copy, with one pixel to spare.
    const int margin = L.radius + 1;
    L.step_copies.assign(static_cast<std::size_t>(n), RotatedCopy{});
    for (int k = 1; k < n; ++k) {
        RotatedCopy& copy = L.step_copies[static_cast<std::size_t>(k)];
        const float angle = L.step_angle[static_cast<std::size_t>(k)];
        copy.cos = std::cos(angle);
        copy.sin = std::sin(angle);
        // The rounding is monotone in each coordinate, so the extremes lie at the corners.
        int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
        bool first = true;
        for (const int cy : {0, L.sh - 1}) {
            for (const int cx : {0, L.sw - 1}) {
                const RotatedOffset q = rotate_offset(cx, cy, copy.cos, -copy.sin);
                x0 = first ? q.dx : std::min(x0, q.dx);
                x1 = first ? q.dx : std::max(x1, q.dx);
                y0 = first ? q.dy : std::min(y0, q.dy);
                y1 = first ? q.dy : std::max(y1, q.dy);
                first = false;
            }
        }
        copy.origin_x = margin - x0;
        copy.origin_y = margin - y0;
        copy.features = FeatureImage(x1 - x0 + 1 + 2 * margin, y1 - y0 + 1 + 2 * margin, F);
        parallel_for(0, copy.features.height(), threads, [&](int qy) {
            for (int qx = 0; qx < copy.features.width(); ++qx) {
                const RotatedOffset p = copy_source_pixel(copy, qx, qy, L.sw, L.sh);
                std::memcpy(copy.features.pixel(qx, qy), L.source_features.pixel(p.dx, p.dy),
                            static_cast<std::size_t>(F));
            }
        });
    }
}

float copy_distance(const Level& L, int tx, int ty, int sx, int sy, int step, float bound) {
    const RotatedCopy& copy = L.step_copies[static_cast<std::size_t>(step)];
    const RotatedOffset q = copy_position(copy, sx, sy);
    const int r = L.radius;
    const FeatureImage& t = L.target_features;
    const FeatureImage& s = copy.features;
    return ssd_rows(t.pixel(tx - r, ty - r), t.row_bytes(), s.pixel(q.dx - r, q.dy - r),
                    s.row_bytes(), L.patch_size, L.patch_size * L.feature_channels(),
                    SsdWeights{L.row_weight.data(), 0}, bound);
}

float copy_distance_reference(const Level& L, int tx, int ty, int sx, int sy, int step) {
    const RotatedCopy& copy = L.step_copies[static_cast<std::size_t>(step)];
    const RotatedOffset q = copy_position(copy, sx, sy);
    const int r = L.radius;
    const int F = L.feature_channels();
    float sum = 0.0f;
    for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
            const RotatedOffset p = copy_source_pixel(copy, q.dx + dx, q.dy + dy, L.sw, L.sh);
            const std::uint8_t* a = L.target_features.pixel(tx + dx, ty + dy);
            const std::uint8_t* b = L.source_features.pixel(p.dx, p.dy);
            for (int c = 0; c < F; ++c) {
                const auto d = static_cast<float>(static_cast<int>(a[c]) - static_cast<int>(b[c]));
                sum += L.channel_weight[static_cast<std::size_t>(c)] * d * d;
            }
        }
    }
    return sum;
}

}  // namespace exemplar::synth
