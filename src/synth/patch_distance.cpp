#include "patch_distance.hpp"

#include <algorithm>

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
            const std::uint8_t* src = L.source_features.pixel(std::clamp(sx + o.dx, 0, L.sw - 1),
                                                              std::clamp(sy + o.dy, 0, L.sh - 1));
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

float patch_distance_general(const Level& L, int tx, int ty, int sx, int sy, float angle,
                             float bound) {
    return general_distance<true>(L, tx, ty, sx, sy, angle, bound);
}

}  // namespace exemplar::synth
