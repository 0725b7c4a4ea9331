#include "patch_distance.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>

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

// The byte offsets in `image` of the pixels of a patch of radius r rotated by `angle_rad`.
void offsets_in(const FeatureImage& image, int r, float angle_rad, int* offsets) {
    const float c = std::cos(angle_rad);
    const float s = std::sin(angle_rad);
    const int pixel_stride = image.stride();
    const int row_stride = static_cast<int>(image.row_bytes());
    // One flat loop over the patch's pixels (it vectorizes; a loop per row of P would not).
    const PatchGrid& grid = kPatchGrids[r];
    for (int k = 0; k < (2 * r + 1) * (2 * r + 1); ++k) {
        const RotatedOffset o = rotate_offset(grid.dx[k], grid.dy[k], c, s);
        offsets[k] = o.dy * row_stride + o.dx * pixel_stride;
    }
}

}  // namespace

void rotated_offsets(const Level& L, float angle_rad, int* offsets) {
    offsets_in(L.source_features, L.radius, angle_rad, offsets);
}

void rotated_target_offsets(const Level& L, float angle_rad, int* offsets) {
    offsets_in(L.target_features, L.radius, -angle_rad, offsets);
}

void gather_target_patch(const Level& L, int tx, int ty, int step, std::uint8_t* block) {
    const int area = L.patch_size * L.patch_size;
    const int* offset = L.step_target_offsets.data() + static_cast<std::size_t>(step) * area;
    const std::uint8_t* centre = L.target_features.pixel(tx, ty);
    const auto F = static_cast<std::size_t>(L.feature_channels());
    // A fixed 16-byte copy is one vector move (as in rotated_interior_distance).
    for (int k = 0; k < area; ++k, block += F) std::memcpy(block, centre + offset[k], 16);
    std::memset(block, 0, kSsdSlack);  // read by ssd_rows past the last row, weighted 0
}

float turned_target_distance(const Level& L, const std::uint8_t* block, int sx, int sy,
                             float bound) {
    const int r = L.radius;
    const int row_bytes = L.patch_size * L.feature_channels();
    const FeatureImage& s = L.source_features;
    return ssd_rows(block, static_cast<std::size_t>(row_bytes), s.pixel(sx - r, sy - r),
                    s.row_bytes(), L.patch_size, row_bytes, SsdWeights{L.row_weight.data(), 0},
                    bound);
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
    if (const int step = L.table_step(angle); step >= 0) {
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

// `sum` plus the P pixel sums of a row of terms (kF per pixel), in general_distance's order: each
// pixel's channels in turn, then the pixels, each times its fall-off weight (nullptr: flat).
// One instantiation per channel count, so the additions are unrolled.
template <int kF>
float add_row_of(const float* terms, int P, const float* falloff, float sum) {
    for (int i = 0; i < P; ++i, terms += kF) {
        float px = 0.0f;
        for (int ch = 0; ch < kF; ++ch) px += terms[ch];
        sum += falloff != nullptr ? falloff[i] * px : px;
    }
    return sum;
}
using RowAdder = float (*)(const float*, int, const float*, float);
template <std::size_t... F>
constexpr std::array<RowAdder, sizeof...(F)> row_adders(std::index_sequence<F...>) {
    return {&add_row_of<static_cast<int>(F)>...};
}
// For 0..16 feature channels (the gathered path's limit).
constexpr auto kRowAdders = row_adders(std::make_index_sequence<17>());

// Every case of general_distance (clamped borders, rotation, weight maps, fall-off) with its
// arithmetic: each term w·d·d rounded as there, the terms added in its order (a pixel's channels,
// then the row's pixels) and the same exit after a row, so the value is general_distance<true>'s
// to the bit (the search chooses as it did with that loop). Faster because a row's terms come
// from one SIMD kernel over contiguous runs of bytes (ssd_terms): the target's and source's rows
// are read in place where no pixel of the row is clamped or rotated, else gathered first. Only
// the additions stay a serial chain. Returns false (nothing computed) when a row does not fit
// the blocks.
bool gathered_distance(const Level& L, int tx, int ty, int sx, int sy, float angle, float bound,
                       float& sum) {
    constexpr int kMaxRowBytes = 15 * 16;
    // Pixels (at most 16 channels) are gathered 16 bytes or floats at a time: a fixed-size copy
    // instead of a call; the images and weights have the slack, the next pixel overwrites the rest.
    constexpr std::size_t kCopy = 16;
    const int r = L.radius;
    const int P = L.patch_size;
    const int F = L.feature_channels();
    const int row_bytes = P * F;
    const bool weighted = !L.target_weights.empty();
    if (F >= static_cast<int>(kRowAdders.size()) || row_bytes > kMaxRowBytes ||
        (weighted && L.target_pixel_weight.empty())) {
        return false;
    }
    const bool rotate = angle != 0.0f;
    const float c = rotate ? std::cos(angle) : 1.0f;
    const float s = rotate ? std::sin(angle) : 0.0f;
    const bool falloff = !L.pixel_weight.empty();
    const auto nf = static_cast<std::size_t>(F);
    const bool target_runs = tx >= r && tx < L.tw - r;
    const bool source_runs = !rotate && sx >= r && sx < L.sw - r;
    // The blocks have ssd_terms' slack: zeros past the gathered row.
    alignas(64) std::uint8_t target_block[kMaxRowBytes + kSsdSlack + kCopy];
    alignas(64) std::uint8_t source_block[kMaxRowBytes + kSsdSlack + kCopy];
    alignas(64) float weight_block[kMaxRowBytes + kSsdSlack + kCopy];
    alignas(64) float terms[kMaxRowBytes + kSsdSlack];
    if (!target_runs) {
        std::memset(target_block + row_bytes, 0, kSsdSlack);
        if (weighted) std::memset(weight_block + row_bytes, 0, kSsdSlack * sizeof(float));
    }
    if (!source_runs) std::memset(source_block + row_bytes, 0, kSsdSlack);
    const RowAdder add_row = kRowAdders[static_cast<std::size_t>(F)];
    sum = 0.0f;
    for (int dy = -r; dy <= r; ++dy) {
        const int y = std::clamp(ty + dy, 0, L.th - 1);
        const std::uint8_t* t = target_block;
        const std::uint8_t* src = source_block;
        // Without weight maps a row's weights are the channel weights tiled over its pixels;
        // with them, channel_weight[c] * target_weights(c) per pixel, general_distance's product.
        const float* w = L.row_weight.data();
        if (target_runs) {
            t = L.target_features.pixel(tx - r, y);
            if (weighted) w = L.target_pixel_weight.data() + L.target_index(tx - r, y) * nf;
        } else {
            for (int dx = -r, i = 0; dx <= r; ++dx, ++i) {
                const int x = std::clamp(tx + dx, 0, L.tw - 1);
                const auto at = static_cast<std::size_t>(i) * nf;
                std::memcpy(target_block + at, L.target_features.pixel(x, y), kCopy);
                if (weighted) {
                    std::memcpy(weight_block + at,
                                L.target_pixel_weight.data() + L.target_index(x, y) * nf,
                                kCopy * sizeof(float));
                }
            }
            if (weighted) w = weight_block;
        }
        if (source_runs) {
            src = L.source_features.pixel(sx - r, std::clamp(sy + dy, 0, L.sh - 1));
        } else {
            for (int dx = -r, i = 0; dx <= r; ++dx, ++i) {
                const RotatedOffset o =
                    rotate ? rotate_offset(dx, dy, c, s) : RotatedOffset{dx, dy};
                std::memcpy(source_block + static_cast<std::size_t>(i) * nf,
                            L.source_features.pixel(std::clamp(sx + o.dx, 0, L.sw - 1),
                                                    std::clamp(sy + o.dy, 0, L.sh - 1)),
                            kCopy);
            }
        }
        ssd_terms(t, src, w, row_bytes, terms);
        const float* row_falloff = falloff ? L.pixel_weight.data() + (dy + r) * P : nullptr;
        sum = add_row(terms, P, row_falloff, sum);
        if (sum > bound) return true;
    }
    return true;
}

}  // namespace

float patch_distance_reference(const Level& L, int tx, int ty, int sx, int sy, float angle) {
    return general_distance<false>(L, tx, ty, sx, sy, angle, 0.0f);
}

float patch_distance_general(const Level& L, int tx, int ty, int sx, int sy, float angle,
                             float bound) {
    if (const int step = turned_target_step(L, tx, ty, sx, sy, angle); step >= 0) {
        alignas(64) std::uint8_t block[kTargetPatchBytes];
        gather_target_patch(L, tx, ty, step, block);
        return turned_target_distance(L, block, sx, sy, bound);
    }
    float sum = 0.0f;
    if (angle != 0.0f && L.target_weights.empty() && L.pixel_weight.empty() &&
        rotated_interior_distance(L, tx, ty, sx, sy, angle, bound, sum)) {
        return sum;
    }
    if (gathered_distance(L, tx, ty, sx, sy, angle, bound, sum)) return sum;
    return general_distance<true>(L, tx, ty, sx, sy, angle, bound);
}

}  // namespace exemplar::synth
