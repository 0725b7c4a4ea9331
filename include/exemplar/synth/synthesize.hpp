#pragma once
/// \file
/// Guided patch-based synthesis (image analogies A : A' :: B : B').
///
/// Given a style exemplar A' (`style`), pairs of guides (A_i on the style's grid, B_i on the
/// target grid), produce B' such that every target patch resembles a style patch whose guides
/// match the target's guides. Multi-scale EM (Kwatra et al. 2005, Wexler et al. 2007) with
/// PatchMatch (Barnes et al. 2009) and a selectable patch-usage strategy; see docs/architecture.md.

#include <functional>
#include <string>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/run_context.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/synth/nnf.hpp"
#include "exemplar/synth/options.hpp"

namespace exemplar {

/// One guide pair. `source` has the style's size, `target` the target size, equal channel counts.
struct GuidePair {
    std::string name;     ///< For messages (usually the file names).
    Image source;         ///< A_i.
    Image target;         ///< B_i.
    float weight = 1.0f;  ///< Weight of this guide's squared differences (≥ 0).
    /// Optional per-pixel multiplier of `weight` on the target grid (1 channel, ≥ 0).
    Image target_weight_map;
};

/// Everything a run reads. Optional images are empty when unused. Single-channel masks are
/// "inside" where > 0.5; labels are compared after rounding; orientations are angles in radians.
struct SynthesisInput {
    Image style;  ///< A'; any channels (alpha is just another channel).
    std::vector<float> style_channel_weights;  ///< Optional, one per style channel (default 1).
    std::vector<GuidePair> guides;  ///< A_i / B_i pairs; the target size comes from them.
    int target_width = 0;           ///< Needed only when there are no guides.
    int target_height = 0;
    Image target_mask;  ///< Synthesize only here; elsewhere keep `initial_target`.
    Image source_mask;  ///< Only patches entirely inside may be used.
    /// A target pixel takes only source patches of its label. Labels are compared after
    /// rounding to integers: pass integer values, not 8-bit label images normalized to 0..1
    /// (the CLI maps each distinct colour to one integer).
    Image source_labels;
    Image target_labels;
    Image source_orientation;  ///< Angle field on the style grid (both or neither).
    Image target_orientation;  ///< Angle field on the target grid.
    /// With orientations: 0 (default) rotates each patch by its exact angle; N (4..1024) rounds
    /// every rotation to the nearest multiple of 2π / N (off by at most 180° / N), so that each
    /// level precomputes the N rotated offset patterns instead of a cosine, a sine and the
    /// rounded offsets per patch distance (the way Brushables and LazyFluids pre-rotate their
    /// exemplars). The field's angles are the rounded ones.
    int orientation_steps = 0;
    /// With orientation_steps: a rotated patch pair is compared with the source patch as it
    /// stands and the target patch turned back by the step's angle (nearest pixel), instead of
    /// the target patch as it stands and the source patch turned: the same rotation sampled on
    /// the other grid, so both centres stay exact. Every candidate of a target pixel at the same
    /// step then shares one gathered target patch, and each compares it with a plain source
    /// patch (contiguous rows). Distances differ from the turned-source ones by the nearest-pixel
    /// rounding (docs/paint.md); matches, votes and usage are as before. Default false; true
    /// without orientation_steps is an error.
    bool rotate_target_patches = false;
    Image initial_target;  ///< Optional start (required with target_mask): style channels.
    Nnf initial_nnf;       ///< Optional start NNF on the target grid (finest level).
    /// Optional extra candidate fields on the target grid (e.g. ribbons, Bénard et al. 2013
    /// §4.1): downscaled like `initial_nnf`, each pixel tries its entries at the start of every
    /// level and again in every forward PatchMatch iteration (next to propagation and random
    /// search), keeping whichever costs least. Entries with x = -1 are "none". The reversed
    /// retrieval of the uniform and error-budget strategies does not try them (it searches from
    /// source to target); their forward passes do.
    std::vector<Nnf> candidate_nnfs;
};

/// Intermediate buffers of a run, for debugging and visualisation.
struct DebugFrame {
    int level = 0;
    int iteration = 0;
    const Nnf* nnf = nullptr;
    const Image* usage = nullptr;    ///< Per style pixel: number of target patches using it.
    const Image* current = nullptr;  ///< Current target estimate (style channels).
};
using DebugSink = std::function<void(const DebugFrame&)>;

/// Output of a run.
struct SynthesisResult {
    Image image;  ///< B', same channels as the style, target size.
    Nnf nnf;      ///< Final NNF (target grid).
    /// Patch size the final NNF was computed with (3 after a final 3x3 pass).
    int nnf_patch_size = 0;
    /// Footprint of the vote that made `image` (SynthesisOptions::final_vote_size, at most
    /// nnf_patch_size): apply_nnf with nnf_patch_size, vote_size and vote_seams reproduces the
    /// image.
    int vote_size = 0;
    /// Whether that vote blended seams (SynthesisOptions::final_vote_seams).
    bool vote_seams = false;
    /// The coherence variance of that vote's weights (SynthesisOptions::vote_coherence; 0 = none,
    /// or not a weighted vote): apply_nnf's vote_coherence.
    float vote_coherence = 0.0f;
    /// Per-pixel patch distance of the final NNF against the final image (1 channel; 0 where
    /// the pixel is not a patch centre).
    Image error;
    /// What SynthesisOptions::guide_pca did: guide channels before and after (equal when the
    /// guides were used as given) and the fraction of their weighted variance kept.
    struct GuideCompression {
        int channels_before = 0;
        int channels_after = 0;
        double explained_variance = 1.0;
    } guide_compression;
    /// With labels: the levels (0 = finest, 1 = the one before, ...) on which they were not
    /// enforced because some target label had no whole source patch there (a segment of the
    /// source narrower than a patch at that scale); every target pixel then took patches of any
    /// label on that level. Empty when the labels held everywhere or none were given.
    std::vector<int> unlabelled_levels;
};

/// Checks inputs (sizes, channel counts, masks, finite values) and options; returns the first
/// problem as a one-line message naming the input and what is wrong.
Status validate_input(const SynthesisInput& input, const SynthesisOptions& options);

/// Runs the synthesis. Deterministic for a given seed, independent of `context.threads`.
Result<SynthesisResult> synthesize(const SynthesisInput& input, const SynthesisOptions& options,
                                   const RunContext& context = {}, const DebugSink& debug = {});

/// The same, consuming the input: its full-resolution images are released once the finest
/// level has been built from them (the engine works on its own compact copies), so the peak
/// memory holds them or the finest level's working set, not both. Same result, bit for bit.
/// For callers that do not need the input afterwards (the CLI, stylit, animate).
Result<SynthesisResult> synthesize(SynthesisInput&& input, const SynthesisOptions& options,
                                   const RunContext& context = {}, const DebugSink& debug = {});

}  // namespace exemplar
