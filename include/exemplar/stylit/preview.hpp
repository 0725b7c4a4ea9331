#pragma once
/// \file
/// StyLit's preview mode (§8.3.4): half resolution and the LPE buffers compressed by PCA, so
/// that the patch distance compares a few channels instead of twelve. (The paper's third
/// measure, integer textures, is the engine's business and not done here.)

#include <span>

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

/// One guide pair of make_preview's second form (not owned; must outlive the call).
struct PreviewGuide {
    const Image* source = nullptr;
    const Image* target = nullptr;
    float weight = 1.0f;
};

/// make_preview without a SynthesisInput: saves copying full-size images that are only halved.
/// Sizes are not checked here (validate_input on the result does).
Result<PreviewInput> make_preview(const Image& style, std::span<const PreviewGuide> guides,
                                  int components, int threads = 0);

/// EM iterations per coarser level of a preview at most (StyLit: 6).
inline constexpr int kPreviewEmIterations = 4;
/// Cold-start PatchMatch iterations of a preview at most (StyLit: 6).
inline constexpr int kPreviewSearchIterations = 4;

/// The engine options of a preview, derived from the full run's for speed: the error budget
/// becomes plain nearest neighbours (its reversed retrieval is about 2/3 of the preview's
/// time), EM and cold PatchMatch iterations are capped at kPreviewEmIterations
/// and kPreviewSearchIterations; everything else (patch size, vote, final 3x3 pass, seed,
/// other usage strategies) is kept. Quality vs the full result: docs/stylit.md#preview-834.
SynthesisOptions preview_synthesis_options(const SynthesisOptions& full);

/// How closely a preview resembles the full-quality result, compared at the preview's size.
struct PreviewSimilarity {
    /// Mean absolute difference of the colour channels (0..1 for images in 0..1) after both
    /// images are reduced by `blur_factor` (area average): do strokes and colours sit in the
    /// same places?
    double colour_difference = 0.0;
    /// Luminance gradient energy of the preview over that of the full result reduced to the
    /// preview's size (1 = as much texture; plain averaging washes out to ~0.6).
    double texture_ratio = 1.0;
};

/// Compares a preview with the full result (any size ≥ the preview's; reduced to it by area
/// average). `blur_factor` ≥ 1 is the extra reduction for the colour difference. The images
/// need the same channel count (InvalidArgument otherwise).
Result<PreviewSimilarity> compare_preview(const Image& preview, const Image& full,
                                          int blur_factor = 4, int threads = 0);

}  // namespace exemplar
