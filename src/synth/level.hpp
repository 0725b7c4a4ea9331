#pragma once
// One pyramid level of a synthesis run, in the form the kernels use: 8-bit feature images with
// per-channel weights (features.hpp), validity of source patch centres, labels, orientations
// and the target's active/fixed pixels. Internal to the synth module.

#include <cmath>
#include <cstdint>
#include <vector>

#include "exemplar/core/image.hpp"
#include "features.hpp"

namespace exemplar::synth {

struct Level {
    int index = 0;  ///< 0 = coarsest.
    /// Largest random-search window of the searches on this level; 0 = the whole database
    /// (SynthesisOptions::finest_search_radius on the finest level).
    int search_radius = 0;
    int patch_size = 5;
    int radius = 2;

    // Source (style grid).
    int sw = 0, sh = 0;
    Image source_style;                      ///< A', unscaled style channels (what voting copies).
    FeatureImage source_features;            ///< F channels: A' then the guides A_i.
    std::vector<std::uint8_t> source_valid;  ///< Patch centre usable (in bounds, mask).
    /// Label group of each source pixel (index into valid_by_group); empty when labels are unused.
    std::vector<int> source_label;
    std::vector<float> source_angle;  ///< Empty when orientation is unused.
    /// SynthesisInput::orientation_steps (0 = exact angles). With N steps, angle_for returns
    /// step_angle[k] for the nearest step k, and step_offsets[k * P² + i] is the byte offset in
    /// source_features of the i-th pixel (row-major) of a patch rotated by step_angle[k].
    int orientation_steps = 0;
    std::vector<float> step_angle;  ///< Per step k: 2πk / N as an angle in (−π, π].
    std::vector<int> step_offsets;
    /// Per step k, the rotated one-pixel moves of the search's propagation: rotate_offset of
    /// (1, 0), (-1, 0), (0, 1) and (0, -1) by step_angle[k], as (dx, dy) pairs at 8k..8k+7.
    std::vector<int> step_moves;
    /// With SynthesisInput::rotate_target_patches: per step k, step_target_offsets[k * P² + i] is
    /// the byte offset in target_features of the i-th pixel (row-major) of a patch rotated by
    /// −step_angle[k]: the rotated patch distance then turns the target patch instead of the
    /// source patch (patch_distance.hpp). Empty otherwise.
    std::vector<int> step_target_offsets;

    // Target.
    int tw = 0, th = 0;
    FeatureImage target_features;  ///< F channels: B' (updated by voting) then the guides B_i.
    Image target_weights;          ///< Empty, or F channels of per-pixel weight multipliers.
    /// With target_weights: per target pixel, F floats channel_weight[c] * target_weights(c),
    /// the weights of the SIMD fast path (plus kSsdSlack zeros at the end).
    std::vector<float> target_pixel_weight;
    std::vector<int> target_label;  ///< Label group of each target pixel; empty if unused.
    std::vector<float> target_angle;
    std::vector<std::uint8_t> target_active;  ///< Patch centres being optimized.
    std::vector<std::uint8_t> target_fixed;   ///< Pixels kept from the initial target.
    Image fixed_style;  ///< Initial target (style channels) at this level; empty if none.

    int style_channels = 0;  ///< S: leading channels of the feature images that hold style.
    std::vector<ChannelQuantizer> quantizers;  ///< Per feature channel (F), both sides.
    /// Per feature channel (F): channel weight * step^2, so that the weighted SSD of the codes
    /// approximates the weighted SSD of the values.
    std::vector<float> channel_weight;
    /// channel_weight repeated for the patch_size pixels of a patch row (plus kSsdSlack zeros):
    /// the shared weights of the SIMD fast path.
    std::vector<float> row_weight;
    std::vector<float> pixel_weight;  ///< Patch fall-off weights (P*P), empty = flat.

    // Valid source centres (pixel indices) grouped by label; one group when labels are unused.
    std::vector<std::vector<int>> valid_by_group;

    int feature_channels() const { return source_features.channels(); }
    /// Whether the patch centred at source pixel `s` lies inside the source (no repeated border
    /// pixels): only such patches are the exemplar's own, which usage control distributes.
    bool source_inside(std::size_t s) const {
        const int x = static_cast<int>(s % static_cast<std::size_t>(sw));
        const int y = static_cast<int>(s / static_cast<std::size_t>(sw));
        return x >= radius && y >= radius && x < sw - radius && y < sh - radius;
    }
    /// The same for target pixel `t`: uniform usage assigns only such target patches; those
    /// over the border take nearest neighbours.
    bool target_inside(std::size_t t) const {
        const int x = static_cast<int>(t % static_cast<std::size_t>(tw));
        const int y = static_cast<int>(t / static_cast<std::size_t>(tw));
        return x >= radius && y >= radius && x < tw - radius && y < th - radius;
    }
    bool rotated() const { return !source_angle.empty(); }
    bool labelled() const { return !source_label.empty(); }
    std::size_t target_index(int x, int y) const {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(tw) +
               static_cast<std::size_t>(x);
    }
    std::size_t source_index(int x, int y) const {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(sw) +
               static_cast<std::size_t>(x);
    }
    /// Group (index into valid_by_group) a target pixel draws from.
    int target_group(std::size_t target_pixel) const {
        return labelled() ? target_label[target_pixel] : 0;
    }
    int source_group(std::size_t source_pixel) const {
        return labelled() ? source_label[source_pixel] : 0;
    }
    /// Whether source centre (sx, sy) may serve target pixel tq (validity and labels).
    bool compatible(std::size_t target_pixel, int sx, int sy) const {
        const std::size_t s = source_index(sx, sy);
        if (!source_valid[s]) return false;
        return !labelled() || source_label[s] == target_label[target_pixel];
    }
    /// Rotation from target to source coordinates for a pair (0 without orientation), rounded
    /// to the nearest step with orientation_steps.
    float angle_for(std::size_t target_pixel, int sx, int sy) const {
        return rotated() ? turned_angle(target_pixel, source_index(sx, sy)) : 0.0f;
    }
    /// angle_for with the source centre as a pixel index (the reversed retrieval's query).
    float angle_for_source(std::size_t target_pixel, std::size_t source_pixel) const {
        return rotated() ? turned_angle(target_pixel, source_pixel) : 0.0f;
    }
    /// angle_for's value on a rotated level.
    float turned_angle(std::size_t target_pixel, std::size_t source_pixel) const {
        const float angle = source_angle[source_pixel] - target_angle[target_pixel];
        return orientation_steps > 0 ? step_angle[static_cast<std::size_t>(step_of(angle))] : angle;
    }
    /// With orientation_steps: the step nearest to `angle` (radians, finite).
    int step_of(float angle) const {
        const int n = orientation_steps;
        float steps = angle * (static_cast<float>(n) / 6.28318531f);
        // Differences of angles in (−π, π] need no reduction; other inputs do.
        if (!(std::abs(steps) < static_cast<float>(n))) {
            steps = std::fmod(steps, static_cast<float>(n));
        }
        // Shifted positive (0..2n), so that truncation rounds half up; then into 0..n-1 without
        // branches or an integer division (the search calls this for every candidate).
        int k = static_cast<int>(steps + static_cast<float>(n) + 0.5f);
        k = k >= n ? k - n : k;
        return k >= n ? k - n : k;
    }
    /// The step whose tables hold `angle` (exactly one of step_angle), or -1: no orientation
    /// steps, or an angle that is not a step (then offsets are computed from it).
    int table_step(float angle) const {
        if (orientation_steps == 0) return -1;
        const int k = step_of(angle);
        return step_angle[static_cast<std::size_t>(k)] == angle ? k : -1;
    }
};

}  // namespace exemplar::synth
