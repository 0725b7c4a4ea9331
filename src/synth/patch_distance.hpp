#pragma once
// Patch distance: weighted sum of squared differences between a target patch and a (possibly
// rotated) source patch over all feature channels, computed on the 8-bit feature codes with the
// level's per-channel weights (features.hpp); per-pixel target weight maps and the Gaussian
// fall-off are applied here.
// Source samples at rotated offsets use the nearest pixel (Bénard et al. 2013 §3.2).

#include <cmath>
#include <limits>

#include "level.hpp"
#include "ssd.hpp"

namespace exemplar::synth {

/// Rounded rotation of an integer offset: (round(c dx - s dy), round(s dx + c dy)).
struct RotatedOffset {
    int dx, dy;
};
inline RotatedOffset rotate_offset(int dx, int dy, float c, float s) {
    // floor(v + 0.5) without std::floor, for which the baseline x86-64 target has no instruction
    // (a long inline sequence in the rotated patch distance's offset loop): the same integer for
    // every |v| < 2^31, and patch offsets are a few pixels.
    const auto round_half_up = [](float v) {
        const float u = v + 0.5f;
        const int i = static_cast<int>(u);
        return i - (u < static_cast<float>(i) ? 1 : 0);
    };
    return {round_half_up(c * static_cast<float>(dx) - s * static_cast<float>(dy)),
            round_half_up(s * static_cast<float>(dx) + c * static_cast<float>(dy))};
}

/// The byte offsets in L.source_features of the pixels (row-major) of a patch rotated by
/// `angle_rad`, relative to its centre: patch_size² entries; patches up to 15x15.
/// (Level::step_offsets holds them for each step of a level with orientation steps.)
void rotated_offsets(const Level& L, float angle_rad, int* offsets);

/// The same for the target patch turned back, by −angle_rad, as byte offsets in
/// L.target_features (Level::step_target_offsets holds them per step).
void rotated_target_offsets(const Level& L, float angle_rad, int* offsets);

/// Bytes of a gathered target patch (gather_target_patch) for patches up to 15x15 of at most
/// 16 channels, with ssd_rows' slack.
inline constexpr int kTargetPatchBytes = 15 * 15 * 16 + kSsdSlack + 16;

/// Whether the pair takes the turned-target distance (SynthesisInput::rotate_target_patches):
/// a level with step_target_offsets, no weight maps or fall-off, at most 16 channels, the turned
/// target patch inside the target and the source patch inside the source.
inline bool turns_target(const Level& L, int tx, int ty, int sx, int sy) {
    const int r = L.radius;
    // A turned offset is at most r·√2 rounded.
    const int margin = static_cast<int>(std::ceil(static_cast<float>(r) * 1.41422f));
    return !L.step_target_offsets.empty() && L.target_weights.empty() && L.pixel_weight.empty() &&
           L.feature_channels() <= 16 && tx >= margin && ty >= margin && tx < L.tw - margin &&
           ty < L.th - margin && sx >= r && sy >= r && sx < L.sw - r && sy < L.sh - r;
}

/// The orientation step whose turned target patch the pair at `angle` is compared by, or -1 for
/// patch_distance's other paths: an unrotated pair, one turns_target refuses, or an angle that is
/// not a step of the level's tables.
inline int turned_target_step(const Level& L, int tx, int ty, int sx, int sy, float angle) {
    return angle != 0.0f && turns_target(L, tx, ty, sx, sy) ? L.table_step(angle) : -1;
}

/// The target patch centred at (tx, ty) turned back by orientation step `step`, gathered
/// row-major into `block` (kTargetPatchBytes): what turned_target_distance compares.
void gather_target_patch(const Level& L, int tx, int ty, int step, std::uint8_t* block);

/// The distance of a gathered turned target patch and the plain source patch centred at
/// (sx, sy); stops as patch_distance does once the sum exceeds `bound`.
float turned_target_distance(const Level& L, const std::uint8_t* block, int sx, int sy,
                             float bound);

/// The simple reference: every pixel and channel, no early termination. Test oracle.
float patch_distance_reference(const Level& level, int tx, int ty, int sx, int sy, float angle_rad);

/// Every case of patch_distance (clamped borders, rotation, weight maps, fall-off). Bit for bit
/// the reference's value (its summation order; above `bound`, some value > bound), except rotated
/// patches inside both images without weight maps or fall-off (a SIMD gather: the reference's
/// value up to summation order).
float patch_distance_general(const Level& level, int tx, int ty, int sx, int sy, float angle_rad,
                             float bound);

/// The production kernel: same value as the reference (up to float summation order), but stops
/// as soon as the partial sum exceeds `bound` (then returns some value > bound). Inline: the
/// search calls it tens of millions of times, mostly on the fast path below.
inline float patch_distance(const Level& L, int tx, int ty, int sx, int sy, float angle_rad,
                            float bound = std::numeric_limits<float>::infinity()) {
    const int r = L.radius;
    const bool interior = tx >= r && ty >= r && tx < L.tw - r && ty < L.th - r && sx >= r &&
                          sy >= r && sx < L.sw - r && sy < L.sh - r;
    if (!interior || angle_rad != 0.0f || !L.pixel_weight.empty()) {
        return patch_distance_general(L, tx, ty, sx, sy, angle_rad, bound);
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
