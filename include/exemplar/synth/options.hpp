#pragma once
/// \file
/// Options of one synthesis run. Every numeric option is described once in
/// `synthesis_option_specs()` (name, doc, unit, range, default); validation, the CLI flags, the
/// JSON job keys and the docs are generated from that table.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "exemplar/core/status.hpp"

namespace exemplar {

/// How often a source patch may be used in the target.
enum class UsageStrategy {
    /// Plain nearest neighbours (Kwatra et al. 2005); tends to wash out.
    None,
    /// Every source patch used K or K+1 times (Jamriška et al. 2015, LazyFluids §5.4.1).
    Uniform,
    /// Reversed retrieval limited by an error budget (Fišer et al. 2016, StyLit §8.3.3).
    ErrorBudget,
    /// Penalty on repeatedly used source patches (Kaspar et al. 2015; Bénard et al. 2013 g_h).
    OccurrencePenalty,
};

/// How overlapping patches are combined into a pixel (the M-step).
enum class VoteMode {
    /// Plain average (Wexler et al. 2007; StyLit).
    Average,
    /// Average weighted by 1 / (0.01 + e / ē), e the patch's distance and ē the mean distance
    /// of the iteration: good matches dominate, which keeps strokes sharp (like ebsynth's
    /// weighted vote, but independent of the value range).
    Weighted,
};

/// "average", "weighted".
std::string_view to_string(VoteMode mode);
/// Parses the names of to_string; error names the accepted values.
Result<VoteMode> parse_vote_mode(std::string_view name);

/// The quality dial: presets of the search effort (EM and PatchMatch iterations per level) for
/// users who do not want to tune the search. Each preset is the defaults with the few options of
/// quality_changes() changed, so a change of a default carries over to every preset it does not
/// set. Measurements of each in docs/PERFORMANCE.md ("Quality presets").
enum class Quality {
    /// Previews: fewer EM iterations on the two finest levels and fewer PatchMatch iterations
    /// per warm search; about 2x faster than Default, a little less texture and a little
    /// further from the exemplar.
    Fast,
    /// The defaults of SynthesisOptions.
    Default,
    /// Finals: many more EM iterations on the coarse levels (they are cheap and set the
    /// layout) and more on the two finest; closer to the exemplar and more of its texture,
    /// about 1.7x the time of Default.
    Best,
};

/// "fast", "default", "best".
std::string_view to_string(Quality quality);
/// Parses the names of to_string; error names the accepted values
/// (`quality: 'superb' is invalid (must be one of fast, default, best)`).
Result<Quality> parse_quality(std::string_view name);

/// One option a quality preset sets: its name in synthesis_option_specs() and its value.
struct QualityChange {
    std::string_view option;
    double value = 0.0;
};

/// The options `quality` sets on top of the defaults, in the order of synthesis_option_specs()
/// (none for Default): the one description of the presets, which SynthesisOptions::preset
/// applies and `exemplar stylize --help-all` and docs/cli.md list.
std::span<const QualityChange> quality_changes(Quality quality);

/// "none", "uniform", "error-budget", "occurrence".
std::string_view to_string(UsageStrategy strategy);
/// Parses the names of to_string; error names the accepted values.
Result<UsageStrategy> parse_usage_strategy(std::string_view name);

/// All options of a run. Defaults follow StyLit §8.3.4 (patch 5, ratio 2, 6 EM and 6 PatchMatch
/// iterations) unless a comment says otherwise. See synthesis_option_specs() for ranges.
struct SynthesisOptions {
    int patch_size = 5;          ///< Patch width in pixels, odd.
    int levels = 0;              ///< Pyramid levels; 0 = automatic (coarsest side ≥ 5 patches).
    float pyramid_ratio = 0.5f;  ///< Size ratio between consecutive levels (StyLit: 1/2).
    int em_iterations = 6;       ///< Search+vote iterations per level (coarser levels).
    /// Search+vote iterations on the finest level; 0 = em_iterations. Our deviation from
    /// StyLit's 6: the finest level starts from the upsampled solution of the level before and
    /// converges in a few iterations, while it costs as much as all coarser levels together
    /// (measurements in docs/PERFORMANCE.md).
    int finest_em_iterations = 2;
    /// Search+vote iterations on the level before the finest (unless that is the coarsest,
    /// which starts from scratch); 0 = em_iterations. Our deviation from StyLit's 6: that level
    /// also starts from an upsampled solution, and 4 iterations give the finest level as good a
    /// start (closer exemplar patches, slightly less gradient energy) for 2/3 of the cost
    /// (measurements in docs/PERFORMANCE.md).
    int second_finest_em_iterations = 4;
    int search_iterations = 6;  ///< PatchMatch iterations per NNF search from a cold start.
    /// Largest random-search window (pixels) of the finest level's PatchMatch searches; 0 = the
    /// whole image (StyLit). The finest level starts from a close field (the coarser level's,
    /// upsampled), so its wide windows rarely win but miss the caches; a few pixels make its
    /// searches about a third cheaper (the `fast` preset; docs/PERFORMANCE.md).
    int finest_search_radius = 0;
    /// PatchMatch iterations when the search starts from a field that is already close: the
    /// previous EM iteration's (every EM iteration after a level's first), or the previous
    /// round's (reversed-retrieval rounds). StyLit uses 6 throughout; with the warm starts of
    /// the reversed field 2 keep the texture (measurements in docs/PERFORMANCE.md).
    int warm_search_iterations = 2;
    /// PatchMatch iterations of the first reversed-retrieval round of each EM iteration on the
    /// finest level, which starts from a close field (the previous iteration's, or the coarser
    /// level's upsampled); 0 = warm_search_iterations. One is enough there (on coarser levels
    /// it loses texture); measurements in docs/PERFORMANCE.md. The error budget's finest level
    /// runs no reversed rounds unless budget_polish_iterations is 0.
    int finest_first_round_iterations = 1;
    float style_weight = 1.0f;      ///< Weight of the style (A'/B') term relative to guides.
    float falloff_sigma_px = 0.0f;  ///< Gaussian fall-off of pixel weights in a patch; 0 = flat.
    UsageStrategy usage = UsageStrategy::ErrorBudget;
    VoteMode vote = VoteMode::Weighted;
    /// Weighted vote: each patch's weight is also multiplied by its coherence, the number of
    /// patches around it that map their pixels where it does (Lukáč et al. 2015, Brushables
    /// eq. 6.8: a Gaussian of the mapping discrepancy with this variance, in px²; the paper
    /// uses 2). Coherent pieces of the exemplar then outvote the stray patches between them.
    /// 0 = off (default: it also outvotes thin structures made of many small pieces, such as
    /// the strokes of the animation's line term; measurements in docs/PERFORMANCE.md).
    float vote_coherence = 0.0f;
    /// Colour-histogram weight of the vote (Kopf et al. 2007; Brushables eq. 7, w_h): every
    /// candidate value is weighed by 1 / (1 + k Σ_c max(0, H_target,c − H_source,c)) at its
    /// own value, with k this strength and H the per-channel histograms (32 bins over the
    /// source's range, as densities: 1 = uniform) of the style and of the current target. Values
    /// the target already holds more of than the exemplar lose weight, so rare colours of the
    /// exemplar (highlights, dark accents) are not averaged away. 0 = off (default).
    float vote_histogram = 0.0f;
    /// Extra EM iterations with 3x3 patches after the finest level (ebsynth's "extrapass3x3").
    /// 0 = off (default): final_vote_size keeps the fine grain at a fraction of the cost.
    int final_pass_iterations = 0;
    /// The run's last vote averages only the central final_vote_size x final_vote_size pixels
    /// of each patch: 9 overlapping patches per pixel instead of 25 for 5x5 patches, so the
    /// exemplar's fine grain is not averaged away. 0 (or the patch size) = the whole patch.
    /// Replaces the slower 3x3 pass as the default (measurements in docs/PERFORMANCE.md).
    int final_vote_size = 3;
    /// 1: where the patches of the last vote's footprint disagree on a pixel's source (a seam
    /// between differently mapped pieces), that pixel takes the plain average of the whole
    /// patches over it instead, so seams blend as in ebsynth's vote while the pieces keep the
    /// narrow footprint's grain. Closer to the exemplar, a little less grain (facestyle's
    /// brushwork: 0.745 -> 0.715 of the exemplar's gradient energy); 0 = off (default; 1 in
    /// Quality::Best). No effect when the last vote takes whole patches.
    int final_vote_seams = 0;
    /// Error budget: stop reversed retrieval once this fraction of target patches is covered;
    /// the rest use forward nearest neighbours (StyLit: ~95%).
    float budget_coverage = 0.95f;
    /// Guide channels (each scaled by sqrt(weight)) are replaced by the fewest principal
    /// components that keep this fraction of their variance, fitted on source and target
    /// together; fewer channels make every patch distance cheaper. 0 = off (default: the
    /// components are coded in 8 bits over their range, which loses the exact coding of 8-bit
    /// guides; see docs/algorithms.md). Not applied when a guide has a per-pixel weight map.
    float guide_pca = 0.0f;
    /// Error budget: propagation-only PatchMatch sweeps after the assignment. The budget
    /// assigns targets one by one, so neighbours often take unrelated sources: a mosaic of
    /// small pieces whose seams no exemplar patch contains. In the sweeps every stray match
    /// (one continuing the source region of fewer than two of its four neighbours) takes a
    /// neighbour's shifted match where that is closer; matches inside coherent regions stay.
    /// Closer to the exemplar and more of its grain kept; 0 = off (StyLit as published).
    /// Measurements in docs/PERFORMANCE.md.
    int coherence_sweeps = 2;
    /// Coherent pieces: sweeps of iterated conditional modes after every search (and before its
    /// vote) on the levels above the finest, up to piece_levels, on a Markov random field over
    /// the matches with a Potts term on their offsets (synth::grow_pieces): each target takes,
    /// of its own match and the shifted matches of its neighbours within the vote's footprint,
    /// the one of least patch distance + lambda x (those neighbours it does not continue), with
    /// lambda = piece_weight x the field's mean patch distance. The searches keep whichever of
    /// many similar patches is marginally closest, so neighbours take unrelated sources: a
    /// mosaic of small pieces whose seams no exemplar patch contains. The sweeps merge them into
    /// larger pieces (Image Analogies' coherence, Ashikhmin's coherent candidates; Kwatra's
    /// graph-cut textures place seams by the same kind of energy). 0 = off (default; the `default`
    /// and `best` presets use 2; measurements in docs/performance-history.md, "Larger exemplar
    /// pieces").
    int piece_sweeps = 0;
    /// The same sweeps on the finest level (its searches' window: the last vote's footprint);
    /// 0 = none (default; the `default` and `best` presets use 1).
    int finest_piece_sweeps = 0;
    /// The Potts weight of piece_sweeps: the cost of one neighbour a match does not continue,
    /// relative to the field's mean patch distance.
    float piece_weight = 1.0f;
    /// Of each level above the finest, how many of the last EM iterations are followed by piece
    /// sweeps; 0 = every iteration (default; the `best` preset). The `default` preset sweeps
    /// after each level's last iteration only: every sweep also lets pieces grow across region
    /// edges the guides hardly mark (a painted shadow up a self-shadowed object), and one sweep
    /// per level keeps most of the gain.
    int piece_iterations = 0;
    /// How many of the finest levels run piece sweeps, the finest included (never the coarsest,
    /// whose field starts at random): 3 = the finest and the two before it.
    int piece_levels = 3;
    /// Uniform usage: sweeps after the assignment in which every stray match (as for
    /// coherence_sweeps) takes a neighbour's shifted source instead where that lowers the summed
    /// patch error, by moving to it if every source's count stays K or K + 1 (and K > 0, so no
    /// source goes out of use), or by swapping sources with a stray target that uses it: larger
    /// coherent pieces of the exemplar, the same counts. 0 = off (default: LazyFluids as
    /// published; exemplar fluid uses 2).
    int uniform_coherence_sweeps = 0;
    /// Error budget and uniform usage: the finest level runs this many EM iterations of plain
    /// nearest-neighbour search from the field the usage strategy laid out on the coarser
    /// levels, instead of finest_em_iterations iterations with the strategy. (With the uniform
    /// usage and a target much larger than the exemplar, the finest level's reversed rounds cost
    /// most of the run; paint::fill_area uses 2: docs/feature.md.) The coarser levels fix the
    /// layout (which exemplar region goes where); the budget on the finest level adds a mosaic of
    /// small pieces whose seams no exemplar patch contains, and the plain search moves those seams
    /// to where neighbouring pieces agree: closer to the exemplar (stylit's patch fidelity as
    /// ebsynth's) and cheaper, but the finest grain partly washes out again (facestyle keeps 4-7%
    /// less gradient energy) and highlights take fewer highlight patches. 0 = off (default: StyLit
    /// as published; the `best` preset uses it). Not in the 3x3 final pass. Measurements in
    /// docs/PERFORMANCE.md.
    int budget_polish_iterations = 0;
    /// Error budget and uniform usage: how many of the finest levels polish. The finest polishes
    /// when budget_polish_iterations > 0 (its iterations; else it keeps the usage); the others
    /// up to this count (never the coarsest, which starts from scratch) keep their EM
    /// iterations but search plain nearest neighbours from the upsampled field the usage laid
    /// out on the coarser levels. 1 (default) = the finest only; the `fast` preset polishes
    /// three levels (a third less CPU, as much texture), the `best` preset three with 7x7
    /// patches (polish_patch_size), the `default` preset the level before the finest only
    /// (docs/PERFORMANCE.md).
    int budget_polish_levels = 1;
    /// Error budget and uniform usage: patch width of the levels that polish (see
    /// budget_polish_levels), each where it fits (its sides at least the patch); odd, 0 =
    /// patch_size (default). Their plain nearest-neighbour search then matches wider patches
    /// against the pieces the usage laid out, so a piece continues into its neighbours over a
    /// wider band and the seams between pieces fall where wider strips of the exemplar agree:
    /// closer to the exemplar, as much texture, for the wider patches' CPU (the `best` preset
    /// uses 7; measurements in docs/PERFORMANCE.md). The finest level's NNF then has this patch
    /// size (SynthesisResult::nnf_patch_size).
    int polish_patch_size = 0;
    /// Error budget: maximal number of reversed-retrieval rounds per EM iteration.
    int budget_max_rounds = 32;
    /// Error budget: once fewer than this fraction of the target patches are still free, a
    /// round queries only the source patches that can plausibly take one of them (those next
    /// to a free target's current match, and those not used yet in this search) instead of all
    /// of them. 0 = every round queries every source; 1 (default) = every round after the first.
    float budget_focus = 1.0f;
    /// Occurrence penalty strength h_s (squared error per use above the threshold).
    float occurrence_strength = 0.05f;
    /// Occurrence penalty threshold h_τ in uses; 0 = automatic (2 × target/source area ratio).
    float occurrence_threshold = 0.0f;
    std::uint64_t seed = 1;  ///< Random seed; same seed → same output for any thread count.

    /// The options of a quality preset: the defaults above with quality_changes(quality) applied.
    /// The stylize verbs (stylize, stylit; CLI, studio, Python) start from
    /// preset(Quality::Default) when no quality is given; the defaults above are the plain
    /// engine the other verbs (fluid, paint, fill, ...) build on. Callers that also set options
    /// explicitly apply them after the preset, so explicit values win.
    static SynthesisOptions preset(Quality quality);
};

/// Whether the usage lays the field out with reversed retrieval (error budget, uniform), which
/// a polish can follow with plain nearest neighbours.
inline bool usage_lays_out(const SynthesisOptions& options) {
    return options.usage == UsageStrategy::ErrorBudget || options.usage == UsageStrategy::Uniform;
}

/// Whether the finest level searches plain nearest neighbours instead of the error budget
/// (SynthesisOptions::budget_polish_iterations).
inline bool budget_polish(const SynthesisOptions& options) {
    return usage_lays_out(options) && options.budget_polish_iterations > 0;
}

/// Whether the level `depth` steps above the finest (0 = finest) of a pyramid with `levels`
/// levels polishes (SynthesisOptions::budget_polish_levels): the finest when budget_polish, the
/// next ones up to budget_polish_levels but never the coarsest.
inline bool polishes_level(const SynthesisOptions& options, int depth, int levels) {
    if (depth == 0) return budget_polish(options);
    return usage_lays_out(options) && depth < options.budget_polish_levels && depth < levels - 1;
}

/// Patch width of the level `depth` steps above the finest (0 = finest) of a pyramid with
/// `levels` levels: polish_patch_size on a level that polishes (polishes_level) when set and
/// `fits` it, else patch_size.
inline int patch_size_of_level(const SynthesisOptions& options, int depth, int levels, bool fits) {
    if (options.polish_patch_size > 0 && fits && polishes_level(options, depth, levels)) {
        return options.polish_patch_size;
    }
    return options.patch_size;
}

/// EM iterations of the level `depth` steps above the finest (0 = finest) of a pyramid with
/// `levels` levels: finest_em_iterations on the finest (budget_polish_iterations when
/// budget_polish) and second_finest_em_iterations on the one before it if that is not the
/// coarsest (each when set), else em_iterations.
inline int em_iterations_of_level(const SynthesisOptions& options, int depth, int levels) {
    if (depth == 0 && budget_polish(options)) return options.budget_polish_iterations;
    if (depth == 0 && options.finest_em_iterations > 0) return options.finest_em_iterations;
    if (depth == 1 && levels > 2 && options.second_finest_em_iterations > 0) {
        return options.second_finest_em_iterations;
    }
    return options.em_iterations;
}

/// Sweeps of synth::grow_pieces after each search on the level `depth` steps above the finest
/// (0 = finest) of a pyramid with `levels` levels: finest_piece_sweeps on the finest,
/// piece_sweeps on the next ones up to piece_levels, none on the coarsest.
inline int piece_sweeps_of_level(const SynthesisOptions& options, int depth, int levels) {
    if (depth >= options.piece_levels || depth == levels - 1) return 0;
    return depth == 0 ? options.finest_piece_sweeps : options.piece_sweeps;
}
/// Description of one numeric option. `field` points into SynthesisOptions.
struct OptionSpec {
    std::string_view name;  ///< kebab-case name, used as --name and JSON key (with '_' too).
    std::string_view doc;   ///< Meaning and advice.
    std::string_view unit;  ///< "px", "iterations", "" ...
    double min = 0.0;       ///< Inclusive range.
    double max = 0.0;
    std::variant<int SynthesisOptions::*, float SynthesisOptions::*,
                 std::uint64_t SynthesisOptions::*>
        field;
};

/// The table of numeric options (usage strategy is separate: it is an enum).
std::span<const OptionSpec> synthesis_option_specs();

/// Reads an option's current value as a double.
double get_option(const SynthesisOptions& options, const OptionSpec& spec);
/// Sets an option; rejects values outside [min, max] or non-integral values for integer options
/// with a message like `patch-size: 4 is invalid (must be odd, 3..31)`.
Status set_option(SynthesisOptions& options, const OptionSpec& spec, double value);
/// Finds an option by name ('-' and '_' are interchangeable). nullptr if unknown.
const OptionSpec* find_option(std::string_view name);

/// Checks every option against its range and cross-option rules (odd patch size, ...).
Status validate(const SynthesisOptions& options);

}  // namespace exemplar
