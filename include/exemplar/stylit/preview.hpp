#pragma once
/// \file
/// StyLit's preview mode (§8.3.4): half resolution and the LPE buffers compressed by PCA, so
/// that the patch distance compares a few channels instead of twelve. (The paper's third
/// measure, integer textures, is the engine's business and not done here.)

#include "exemplar/core/status.hpp"
#include "exemplar/synth/synthesize.hpp"

namespace exemplar {

/// A preview input and what the compression kept.
struct PreviewInput {
    SynthesisInput input;             ///< Half-size style and one PCA guide (weight 1).
    int channels_before = 0;          ///< Guide channels of the full input.
    int channels_after = 0;           ///< Principal components kept.
    double explained_variance = 1.0;  ///< Fraction of the weighted guide variance they keep.
};

/// Halves the style and every guide (area average; odd sizes round up), then projects the
/// stacked guide channels, each scaled by sqrt(weight), on their first `components` principal
/// components (fitted on source and target pixels together, so both share one basis). Squared
/// distances in the kept components approximate the weighted sum of the guides' squared
/// distances, so the single guide gets weight 1. `components` is clamped to the channel count;
/// it must be ≥ 1 and the input must have at least one guide (InvalidArgument otherwise).
/// Masks, labels and initial images are not supported in preview (InvalidArgument).
Result<PreviewInput> make_preview(const SynthesisInput& full, int components, int threads = 0);

}  // namespace exemplar
