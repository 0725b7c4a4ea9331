#include "patch_distance.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

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

// The pixel offsets (dx, dy) of a patch of radius 0..7 in row-major order.
struct PatchGrid {
    int dx[15 * 15];
    int dy[15 * 15];
};
constexpr auto kPatchGrids = [] {
    std::array<PatchGrid, 8> grids{};
    for (int r = 0; r < 8; ++r) {
        for (int dy = -r, k = 0; dy <= r; ++dy) {
            for (int dx = -r; dx <= r; ++dx, ++k) {
                grids[r].dx[k] = dx;
                grids[r].dy[k] = dy;
            }
        }
    }
    return grids;
}();

}  // namespace

void rotated_offsets(const Level& L, float angle_rad, int* offsets) {
    const float c = std::cos(angle_rad);
    const float s = std::sin(angle_rad);
    const int pixel_stride = L.source_features.stride();
    const int row_stride = static_cast<int>(L.source_features.row_bytes());
    // One flat loop over the patch's pixels (it vectorizes; a loop per row of P would not).
    const PatchGrid& grid = kPatchGrids[L.radius];
    for (int k = 0; k < L.patch_size * L.patch_size; ++k) {
        const RotatedOffset o = rotate_offset(grid.dx[k], grid.dy[k], c, s);
        offsets[k] = o.dy * row_stride + o.dx * pixel_stride;
    }
}

namespace {

// Rotated patches inside both images, flat and without weight maps (Brushables' direction
// field, oriented stylization): the rotated source patch is gathered into a contiguous block,
// whose rows then go through the same SIMD kernel as an unrotated patch (ssd_rows). The scalar
// loop of general_distance is latency-bound on its chain of additions (one per channel and
// pixel); this is the fast path's value (the reference's up to float summation order). Returns
// false (nothing computed) when the patch or its rotated source reaches over a border or does
// not fit the block.
bool rotated_interior_distance(const Level& L, int tx, int ty, int sx, int sy, float angle,
                               float bound, float& sum) {
    const int r = L.radius;
    const int P = L.patch_size;
    const int F = L.feature_channels();
    constexpr int kBlockBytes = 8192;
    constexpr int kMaxPixels = 15 * 15;
    const int row_bytes = P * F;
    if (P * row_bytes + 16 + kSsdSlack > kBlockBytes || P * P > kMaxPixels) return false;
    // A rotated offset is at most r·√2 rounded: with that margin no source pixel needs a check.
    const int margin = static_cast<int>(std::ceil(static_cast<float>(r) * 1.41422f));
    if (tx < r || ty < r || tx >= L.tw - r || ty >= L.th - r || sx < margin || sy < margin ||
        sx >= L.sw - margin || sy >= L.sh - margin) {
        return false;
    }
    // The offsets first (the level's table for a rounded angle), then the copies.
    int computed[kMaxPixels];
    const int* offset = computed;
    const int step = L.orientation_steps > 0 ? L.step_of(angle) : 0;
    if (L.orientation_steps > 0 && L.step_angle[static_cast<std::size_t>(step)] == angle) {
        offset = L.step_offsets.data() + static_cast<std::size_t>(step) * (P * P);
    } else {
        rotated_offsets(L, angle, computed);
    }
    const std::uint8_t* centre = L.source_features.pixel(sx, sy);
    alignas(64) std::uint8_t block[kBlockBytes];
    std::uint8_t* out = block;
    if (F <= 16) {
        // A fixed 16-byte copy is one vector move (the feature images have slack past their last
        // pixel, the block past its last row, and the next pixel overwrites the rest).
        for (int k = 0; k < P * P; ++k, out += F) std::memcpy(out, centre + offset[k], 16);
    } else {
        for (int k = 0; k < P * P; ++k, out += F) {
            std::memcpy(out, centre + offset[k], static_cast<std::size_t>(F));
        }
    }
    std::memset(out, 0, kSsdSlack);  // read by ssd_rows past the last row, weighted 0
    const FeatureImage& t = L.target_features;
    sum =
        ssd_rows(t.pixel(tx - r, ty - r), t.row_bytes(), block, static_cast<std::size_t>(row_bytes),
                 P, row_bytes, SsdWeights{L.row_weight.data(), 0}, bound);
    return true;
}

}  // namespace

float patch_distance_reference(const Level& L, int tx, int ty, int sx, int sy, float angle) {
    return general_distance<false>(L, tx, ty, sx, sy, angle, 0.0f);
}

float patch_distance_general(const Level& L, int tx, int ty, int sx, int sy, float angle,
                             float bound) {
    float sum = 0.0f;
    if (angle != 0.0f && L.target_weights.empty() && L.pixel_weight.empty() &&
        rotated_interior_distance(L, tx, ty, sx, sy, angle, bound, sum)) {
        return sum;
    }
    return general_distance<true>(L, tx, ty, sx, sy, angle, bound);
}

}  // namespace exemplar::synth
