#pragma once
// Patch distance: weighted sum of squared differences between a target patch and a (possibly
// rotated) source patch over all feature channels, computed on the 8-bit feature codes with the
// level's per-channel weights (features.hpp); per-pixel target weight maps and the Gaussian
// fall-off are applied here.
// Source samples at rotated offsets use the nearest pixel (Bénard et al. 2013 §3.2).

#include <cmath>
#include <limits>

#include "level.hpp"

namespace exemplar::synth {

/// Rounded rotation of an integer offset: (round(c dx - s dy), round(s dx + c dy)).
struct RotatedOffset {
    int dx, dy;
};
inline RotatedOffset rotate_offset(int dx, int dy, float c, float s) {
    return {static_cast<int>(
                std::floor(c * static_cast<float>(dx) - s * static_cast<float>(dy) + 0.5f)),
            static_cast<int>(
                std::floor(s * static_cast<float>(dx) + c * static_cast<float>(dy) + 0.5f))};
}

/// The simple reference: every pixel and channel, no early termination. Test oracle.
float patch_distance_reference(const Level& level, int tx, int ty, int sx, int sy, float angle_rad);

/// The production kernel: same value as the reference (up to float summation order), but stops
/// as soon as the partial sum exceeds `bound` (then returns some value > bound).
float patch_distance(const Level& level, int tx, int ty, int sx, int sy, float angle_rad,
                     float bound = std::numeric_limits<float>::infinity());

}  // namespace exemplar::synth
