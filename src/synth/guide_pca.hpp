#pragma once
// Guide compression: the guide pairs' channels, each scaled by sqrt(weight), replaced by their
// principal components (one basis fitted on source and target pixels together). Squared
// distances between pixels in the components equal the weighted sum of the guides' squared
// distances up to the variance left out, so the compressed guide gets weight 1 and the patch
// distance reads fewer bytes per pixel: the StyLit example's 12 guide channels keep 99.93% of
// their variance in 6 components (docs/PERFORMANCE.md). Opt-in (SynthesisOptions::guide_pca).
// Internal to the synth module.

#include <optional>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/synth/synthesize.hpp"

namespace exemplar::synth {

struct CompressedGuides {
    Image source;  ///< `kept` channels on the style grid.
    Image target;  ///< `kept` channels on the target grid.
    int channels_before = 0;
    int kept = 0;
    double explained_variance = 1.0;  ///< Fraction of the weighted guide variance kept.
};

/// The fewest principal components that keep `keep_variance` (0..1] of the weighted variance
/// of `guides`; nullopt when that would not drop a channel, when keep_variance <= 0 (off), or
/// when a guide has a per-pixel weight map (weights that differ per guide and pixel do not
/// survive a mix of the channels). Deterministic for any thread count.
std::optional<CompressedGuides> compress_guides(const std::vector<GuidePair>& guides,
                                                double keep_variance, int threads);

}  // namespace exemplar::synth
