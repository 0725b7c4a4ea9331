#include "patch_distance.hpp"

#include <algorithm>

#include "ssd.hpp"

namespace exemplar::synth {

namespace {

// General path: clamped target coordinates, rotation, weight maps and fall-off.
template <bool kEarlyExit>
float general_distance(const Level& L, int tx, int ty, int sx, int sy, float angle, float bound) {
    const int r = L.radius;
    const int F = L.feature_channels();
    const float c = std::cos(angle);
    const float s = std::sin(angle);
    const bool rotate = angle != 0.0f;
    const bool weighted = !L.target_weights.empty();
    const bool falloff = !L.pixel_weight.empty();
    float sum = 0.0f;
    int k = 0;
    for (int dy = -r; dy <= r; ++dy) {
        const int y = std::clamp(ty + dy, 0, L.th - 1);
        for (int dx = -r; dx <= r; ++dx, ++k) {
            const int x = std::clamp(tx + dx, 0, L.tw - 1);
            const RotatedOffset o = rotate ? rotate_offset(dx, dy, c, s) : RotatedOffset{dx, dy};
            const std::uint8_t* t = L.target_features.pixel(x, y);
            const std::uint8_t* src = L.source_features.pixel(sx + o.dx, sy + o.dy);
            const float* w = L.channel_weight.data();
            const float* map = weighted ? L.target_weights.pixel(x, y) : nullptr;
            float px = 0.0f;
            for (int ch = 0; ch < F; ++ch) {
                const auto d =
                    static_cast<float>(static_cast<int>(t[ch]) - static_cast<int>(src[ch]));
                px += (weighted ? map[ch] * w[ch] : w[ch]) * d * d;
            }
            sum += falloff ? L.pixel_weight[k] * px : px;
        }
        if (kEarlyExit && sum > bound) return sum;
    }
    return sum;
}

}  // namespace

float patch_distance_reference(const Level& L, int tx, int ty, int sx, int sy, float angle) {
    return general_distance<false>(L, tx, ty, sx, sy, angle, 0.0f);
}

float patch_distance(const Level& L, int tx, int ty, int sx, int sy, float angle, float bound) {
    const int r = L.radius;
    const bool interior = tx >= r && ty >= r && tx < L.tw - r && ty < L.th - r;
    if (!interior || angle != 0.0f || !L.pixel_weight.empty()) {
        return general_distance<true>(L, tx, ty, sx, sy, angle, bound);
    }
    // Fast path: each patch row is one contiguous run of P pixels in both feature images (and
    // in the per-pixel weights when guides have weight maps).
    const FeatureImage& t = L.target_features;
    const FeatureImage& s = L.source_features;
    const int F = t.stride();
    SsdWeights weights{L.row_weight.data(), 0};
    if (!L.target_pixel_weight.empty()) {
        const std::size_t row = static_cast<std::size_t>(L.tw) * static_cast<std::size_t>(F);
        weights = SsdWeights{L.target_pixel_weight.data() + static_cast<std::size_t>(ty - r) * row +
                                 static_cast<std::size_t>(tx - r) * static_cast<std::size_t>(F),
                             row};
    }
    return ssd_rows(t.pixel(tx - r, ty - r), t.row_bytes(), s.pixel(sx - r, sy - r), s.row_bytes(),
                    L.patch_size, L.patch_size * F, weights, bound);
}

}  // namespace exemplar::synth
