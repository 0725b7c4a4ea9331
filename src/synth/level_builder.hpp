#pragma once
// Builds the per-level data of a run (pyramids of all inputs, feature images, validity maps).
// Internal to the synth module.

#include <cstdint>
#include <vector>

#include "exemplar/synth/synthesize.hpp"
#include "level.hpp"

namespace exemplar::synth {

/// Target size of a run: from the guides, else the initial target, else the given size.
void target_size(const SynthesisInput& input, int& width, int& height);

/// Per pixel of a w x h source: 1 where the square footprint of radius `footprint_radius` lies
/// inside the image and, if `mask` is not empty, entirely inside the mask (> 0.5).
std::vector<std::uint8_t> source_validity(int w, int h, int footprint_radius, const Image& mask);

/// Automatic level count: the coarsest level keeps at least 5 patches across the smaller side of
/// both the style and the target (StyLit: 6 levels for one megapixel at ratio 1/2).
int automatic_levels(int min_side, int patch_size, float ratio);

/// Largest level count for which every level still has room for one patch (rotated patches need
/// a larger footprint).
int max_levels(int min_side, int patch_size, float ratio, bool rotated);

/// A guide pair as the levels use it: the input's (no copy) when all its channels are kept, else
/// the kept channels (copied), or principal components; `weights` per kept channel.
struct ReducedGuide {
    const GuidePair* whole = nullptr;
    Image own_source, own_target;
    const Image* weight_map = nullptr;  ///< The input's (possibly empty) map.
    std::vector<float> weights;
    const Image& source() const { return whole != nullptr ? whole->source : own_source; }
    const Image& target() const { return whole != nullptr ? whole->target : own_target; }
};

/// The inputs of every level, level 0 = coarsest: each level is resampled from the full-resolution
/// inputs when it is built.
class LevelBuilder {
public:
    LevelBuilder(const SynthesisInput& input, const SynthesisOptions& options, int levels,
                 int threads);
    // The reduced guides point into the input and into this object.
    LevelBuilder(const LevelBuilder&) = delete;
    LevelBuilder& operator=(const LevelBuilder&) = delete;

    int levels() const { return levels_; }
    int target_width() const { return tw_; }
    int target_height() const { return th_; }
    /// What guide compression did (options.guide_pca).
    const SynthesisResult::GuideCompression& guide_compression() const { return compression_; }

    /// Everything of level `index` except the style part of target_features (set it with
    /// set_target_style once B' is known), for patches of `patch_size` (default: the options').
    Level build(int index, int patch_size = 0) const;

    /// Frees the reduced guides this builder made; from here on neither it nor the input may be
    /// used to build a level (the input's owner may release it too).
    void release_inputs();

private:
    int depth(int index) const { return levels_ - 1 - index; }

    const SynthesisInput& input_;
    const SynthesisOptions& options_;
    int levels_;
    int threads_;
    int tw_, th_;
    // The guides the levels use (the input's without channels that cannot change a distance,
    // or their principal components) and their weights per channel.
    std::vector<ReducedGuide> guides_;
    Image no_map_;  // the weight map of compressed guides: none
    bool released_ = false;
    SynthesisResult::GuideCompression compression_;
};

/// Copies B' (style channels) into the style part of the level's target features, over rows on
/// up to `threads` threads (each row writes only its own pixels: the same bytes for any count).
void set_target_style(Level& level, const Image& style, int threads = 1);

}  // namespace exemplar::synth
