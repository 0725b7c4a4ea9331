#include "patch_distance.hpp"

#include <algorithm>

namespace exemplar::synth {

namespace {

// Sum of squared differences of n contiguous floats, in eight independent lanes so the compiler
// can vectorize it without reassociating a single accumulator.
inline float ssd_span(const float* a, const float* b, int n) {
    float acc[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    int i = 0;
    for (; i + 8 <= n; i += 8) {
        for (int k = 0; k < 8; ++k) {
            const float d = a[i + k] - b[i + k];
            acc[k] += d * d;
        }
    }
    float tail = 0.0f;
    for (; i < n; ++i) {
        const float d = a[i] - b[i];
        tail += d * d;
    }
    return ((acc[0] + acc[4]) + (acc[1] + acc[5])) + ((acc[2] + acc[6]) + (acc[3] + acc[7])) + tail;
}

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
            const float* t = L.target_features.pixel(x, y);
            const float* src = L.source_features.pixel(sx + o.dx, sy + o.dy);
            float px = 0.0f;
            if (weighted) {
                const float* w = L.target_weights.pixel(x, y);
                for (int ch = 0; ch < F; ++ch) {
                    const float d = t[ch] - src[ch];
                    px += w[ch] * d * d;
                }
            } else {
                for (int ch = 0; ch < F; ++ch) {
                    const float d = t[ch] - src[ch];
                    px += d * d;
                }
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
    if (!interior || angle != 0.0f || !L.target_weights.empty() || !L.pixel_weight.empty()) {
        return general_distance<true>(L, tx, ty, sx, sy, angle, bound);
    }
    // Fast path: each patch row is one contiguous run of P*F floats in both images.
    const int F = L.feature_channels();
    const int n = L.patch_size * F;
    const std::size_t t_stride = static_cast<std::size_t>(L.tw) * static_cast<std::size_t>(F);
    const std::size_t s_stride = static_cast<std::size_t>(L.sw) * static_cast<std::size_t>(F);
    const float* t = L.target_features.pixel(tx - r, ty - r);
    const float* s = L.source_features.pixel(sx - r, sy - r);
    float sum = 0.0f;
    for (int row = 0; row < L.patch_size; ++row, t += t_stride, s += s_stride) {
        sum += ssd_span(t, s, n);
        if (sum > bound) return sum;
    }
    return sum;
}

}  // namespace exemplar::synth
