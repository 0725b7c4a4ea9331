#include "exemplar/synth/options.hpp"

#include <array>
#include <cmath>
#include <sstream>

#include "exemplar/core/check.hpp"
#include "exemplar/core/option_table.hpp"

namespace exemplar {

std::string_view to_string(UsageStrategy strategy) {
    switch (strategy) {
        case UsageStrategy::None: return "none";
        case UsageStrategy::Uniform: return "uniform";
        case UsageStrategy::ErrorBudget: return "error-budget";
        case UsageStrategy::OccurrencePenalty: return "occurrence";
    }
    return "?";
}

std::string_view to_string(VoteMode mode) {
    switch (mode) {
        case VoteMode::Average: return "average";
        case VoteMode::Weighted: return "weighted";
    }
    return "?";
}

Result<VoteMode> parse_vote_mode(std::string_view name) {
    for (auto m : {VoteMode::Average, VoteMode::Weighted}) {
        if (name == to_string(m)) return m;
    }
    std::string message = "vote: '";
    message.append(name);
    message.append("' is invalid (must be one of average, weighted)");
    return invalid_argument(std::move(message));
}

std::string_view to_string(Quality quality) {
    switch (quality) {
        case Quality::Fast: return "fast";
        case Quality::Default: return "default";
        case Quality::Best: return "best";
    }
    return "?";
}

Result<Quality> parse_quality(std::string_view name) {
    for (auto q : {Quality::Fast, Quality::Default, Quality::Best}) {
        if (name == to_string(q)) return q;
    }
    std::string message = "quality: '";
    message.append(name);
    message.append("' is invalid (must be one of fast, default, best)");
    return invalid_argument(std::move(message));
}

std::span<const QualityChange> quality_changes(Quality quality) {
    // Measured on bench_examples stylit and facestyle, seeds 1-3 (docs/PERFORMANCE.md, "Quality
    // presets"), and on all four examples for issue 15's 25x ebsynth ("fast for previews").
    // Fast: the finest levels iterate less and warm searches run once; the finest level's one
    // iteration is a plain nearest-neighbour polish of the budget's field (a third less CPU,
    // closer to the exemplar, as much texture but on facestyle). One reversed-retrieval round
    // per budget iteration (the rest falls back to forward nearest neighbours): 10-25% less CPU
    // and closer to the exemplar on every example. The level before the finest iterates once
    // and the coarse levels three times (instead of six): another 15-25% less CPU, for stylit
    // 15% further from the exemplar, texture still far above ebsynth's. The finest level's
    // search starts from the upsampled field: random-search windows of 8 px at most find as
    // much there (same fidelity and texture) for a quarter less of that level's CPU. The two
    // levels before the finest polish too (plain nearest neighbours from the layout the budget
    // made on the coarser levels): a third less CPU again, as much texture, closer on stylit
    // (polishing a fourth level gains nothing and loses texture). Best: the
    // coarse levels iterate much more, which is nearly free and brings the most fidelity, then the
    // two finest levels converge further. Its votes weigh coherence (coherent pieces outvote
    // strays while the EM converges): more texture and closer to the exemplar on all four
    // examples, for 5-10% more CPU (issue 15, "texbynum's fidelity"). The level before the finest
    // polishes too: 18-27% less CPU and closer on all four (texbynum 0.0536 -> 0.0502 over seeds
    // 1-3), 1-3% less texture on stylit and facestyle (issue 15, "default at half the CPU").
    // The three finest levels polish, with 7x7 patches: their seams fall where wider strips of the
    // exemplar agree, 10-19% closer on all five examples (texbynum 0.0502 -> 0.0448 over seeds
    // 1-3), as much texture (stylit -1%, texbynum +4%), for 5-16% more CPU (issue 15, "`best` 10%
    // closer than ebsynth on texbynum"). Its searches are followed by piece sweeps (two on the
    // levels above the finest, one on the finest): larger exemplar pieces, closer on all five
    // with 3-20% more texture, for 4-16% more CPU (issue 15, "Larger exemplar pieces"). Both
    // together: texbynum 0.0502 -> 0.0420 over seeds 1-3, 17% closer than ebsynth (issue 15,
    // "Merged presets and the quiet re-measure").
    // Default (what the stylize verbs run when no quality is given): the level before the finest
    // polishes (plain nearest neighbours from the budget's layout), the finest keeps one budget
    // iteration (it places the exemplar's rare patches, StyLit's highlights) and votes weigh
    // coherence: 40-45% less CPU, as close to the exemplar or closer and as much texture or more on
    // all four examples (issue 15, "default at half the CPU"). Piece sweeps after each level's
    // last search (two above the finest, one on it) and seams blended in the last vote: 15-22%
    // closer to the exemplar on all five examples with as much texture or more, for about 5% more
    // CPU (issue 15, "Larger exemplar pieces"; sweeping after every iteration, as `best` does,
    // loses RenderStylit's cow to the painted shadow).
    static constexpr std::array kDefault{
        QualityChange{"finest-em-iterations", 1}, QualityChange{"final-vote-seams", 1},
        QualityChange{"vote-coherence", 2},       QualityChange{"piece-sweeps", 2},
        QualityChange{"finest-piece-sweeps", 1},  QualityChange{"piece-iterations", 1},
        QualityChange{"budget-polish-levels", 2},
    };
    static constexpr std::array kFast{
        QualityChange{"budget-polish-iterations", 1},
        QualityChange{"finest-em-iterations", 1},
        QualityChange{"second-finest-em-iterations", 1},
        QualityChange{"warm-search-iterations", 1},
        QualityChange{"em-iterations", 3},
        QualityChange{"budget-max-rounds", 1},
        QualityChange{"finest-search-radius", 8},
        QualityChange{"budget-polish-levels", 3},
    };
    static constexpr std::array kBest{
        QualityChange{"em-iterations", 16},
        QualityChange{"finest-em-iterations", 3},
        QualityChange{"second-finest-em-iterations", 8},
        QualityChange{"budget-polish-iterations", 4},
        QualityChange{"final-vote-seams", 1},
        QualityChange{"vote-coherence", 2},
        QualityChange{"budget-polish-levels", 3},
        QualityChange{"polish-patch-size", 7},
        QualityChange{"piece-sweeps", 2},
        QualityChange{"finest-piece-sweeps", 1},
    };
    switch (quality) {
        case Quality::Fast: return kFast;
        case Quality::Default: return kDefault;
        case Quality::Best: return kBest;
    }
    return {};
}

SynthesisOptions SynthesisOptions::preset(Quality quality) {
    SynthesisOptions o;
    for (const QualityChange& change : quality_changes(quality)) {
        // A bug, not bad input: the presets' names and values are tested.
        const OptionSpec* spec = find_option(change.option);
        EXEMPLAR_CHECK(spec != nullptr);
        EXEMPLAR_CHECK(set_option(o, *spec, change.value).is_ok());
    }
    return o;
}

Result<UsageStrategy> parse_usage_strategy(std::string_view name) {
    for (auto s : {UsageStrategy::None, UsageStrategy::Uniform, UsageStrategy::ErrorBudget,
                   UsageStrategy::OccurrencePenalty}) {
        if (name == to_string(s)) return s;
    }
    std::string message = "usage: '";
    message.append(name);
    message.append("' is invalid (must be one of none, uniform, error-budget, occurrence)");
    return invalid_argument(std::move(message));
}

namespace {
using O = SynthesisOptions;
// The one description of every numeric option: CLI flags, JSON keys, validation and docs come
// from here.
const std::array<OptionSpec, 34> kSpecs{{
    {"patch-size", "Patch width; odd. Larger patches keep larger structures but blur detail.", "px",
     3, 31, &O::patch_size},
    {"levels", "Pyramid levels; 0 = automatic (coarsest level about 5 patches across).", "levels",
     0, 16, &O::levels},
    {"pyramid-ratio", "Size ratio between consecutive pyramid levels (StyLit: 0.5).", "", 0.3, 0.95,
     &O::pyramid_ratio},
    {"em-iterations", "Search+vote iterations per pyramid level but the finest (StyLit: 6).",
     "iterations", 1, 100, &O::em_iterations},
    {"finest-em-iterations",
     "Search+vote iterations on the finest level; 0 = em-iterations. It starts from the "
     "upsampled coarser solution and converges fast (StyLit: 6).",
     "iterations", 0, 100, &O::finest_em_iterations},
    {"second-finest-em-iterations",
     "Search+vote iterations on the level before the finest (not when it is the coarsest); "
     "0 = em-iterations. It starts from an upsampled solution too (StyLit: 6).",
     "iterations", 0, 100, &O::second_finest_em_iterations},
    {"search-iterations", "PatchMatch iterations per nearest-neighbour search (StyLit: 6).",
     "iterations", 1, 100, &O::search_iterations},
    {"finest-search-radius",
     "Largest random-search window of the finest level's searches, which start from a close "
     "field; 0 = the whole image (StyLit). A few pixels: about a third less search CPU there, "
     "nearly the same result.",
     "px", 0, 100000, &O::finest_search_radius},
    {"warm-search-iterations",
     "PatchMatch iterations when the search starts from a close field: the previous EM "
     "iteration's, or the previous reversed-retrieval round's (StyLit: 6; fewer is faster but "
     "keeps less of the exemplar's fine texture).",
     "iterations", 1, 100, &O::warm_search_iterations},
    {"finest-first-round-iterations",
     "Usage strategies: PatchMatch iterations of the first reversed-retrieval round on the "
     "finest level, which starts from a close field; 0 = warm-search-iterations.",
     "iterations", 0, 100, &O::finest_first_round_iterations},
    {"final-pass-iterations",
     "EM iterations with 3x3 patches after the finest level (ebsynth's extra pass); 0 = off.",
     "iterations", 0, 100, &O::final_pass_iterations},
    {"final-vote-size",
     "The last vote averages only the central NxN pixels of each patch, which keeps the "
     "exemplar's fine grain; odd, 0 = the whole patch.",
     "px", 0, 31, &O::final_vote_size},
    {"final-vote-seams",
     "1: where the patches of the last vote's footprint disagree on a pixel's source (a seam "
     "between pieces), the pixel takes the plain average of the whole patches instead: seams "
     "blend, pieces keep their grain; closer to the exemplar, a little less grain. 0 = off.",
     "", 0, 1, &O::final_vote_seams},
    {"vote-coherence",
     "Weighted vote: each patch also weighs by how many patches around it map consistently "
     "(a Gaussian of their discrepancy with this variance; Brushables: 2); coherent pieces of "
     "the exemplar outvote stray patches, but also thin strokes made of small pieces. 0 = off.",
     "px^2", 0, 100, &O::vote_coherence},
    {"vote-histogram",
     "Vote: each candidate value weighs 1 / (1 + k * excess), the excess being how much more of "
     "its value (per channel, 32 bins) the current target holds than the exemplar (Kopf et al. "
     "2007; Brushables' w_h); rare exemplar colours are then not averaged away. 0 = off.",
     "", 0, 100, &O::vote_histogram},
    {"style-weight", "Weight of the style term (B' vs A') relative to the guides.", "", 0, 1e6,
     &O::style_weight},
    {"falloff-sigma", "Gaussian fall-off of pixel weights inside a patch; 0 = all pixels equal.",
     "px", 0, 100, &O::falloff_sigma_px},
    {"guide-pca",
     "Guide channels are replaced by the fewest principal components that keep this fraction of "
     "their weighted variance (faster distances, approximate guides); 0 = off. Not with "
     "per-pixel guide weights.",
     "", 0, 1, &O::guide_pca},
    {"budget-coverage",
     "Error budget: fraction of target patches covered by reversed retrieval before the rest "
     "falls back to forward nearest neighbours (StyLit: 0.95).",
     "", 0, 1, &O::budget_coverage},
    {"coherence-sweeps",
     "Error budget: sweeps after the patch assignment in which every stray match (continuing "
     "fewer than two of its neighbours' source regions, or on the finest level in a piece "
     "smaller than half a patch) takes a neighbour's shifted match where that is closer: fewer "
     "seams, closer to the exemplar; 0 = off (StyLit as published).",
     "iterations", 0, 100, &O::coherence_sweeps},
    {"piece-sweeps",
     "Sweeps after every search on the levels above the finest (up to piece-levels) in which "
     "each target takes, of its own match and its neighbours' shifted matches (within the vote's "
     "footprint), the one of least patch distance + piece-weight x mean distance x (neighbours it "
     "does not continue): larger exemplar pieces, fewer seams, closer to the exemplar; 0 = off.",
     "iterations", 0, 100, &O::piece_sweeps},
    {"finest-piece-sweeps",
     "The same sweeps on the finest level (over the last vote's footprint); 0 = none.",
     "iterations", 0, 100, &O::finest_piece_sweeps},
    {"piece-weight",
     "Piece sweeps: cost of a neighbour a match does not continue, relative to the field's mean "
     "patch distance; larger = larger pieces, guides followed less.",
     "", 0, 100, &O::piece_weight},
    {"piece-iterations",
     "Of each level above the finest, how many of the last EM iterations are followed by piece "
     "sweeps; 0 = every iteration.",
     "iterations", 0, 100, &O::piece_iterations},
    {"piece-levels",
     "How many of the finest levels run piece sweeps, the finest included (never the coarsest).",
     "levels", 1, 16, &O::piece_levels},
    {"uniform-coherence-sweeps",
     "Uniform usage: sweeps after the assignment in which every stray match takes a neighbour's "
     "shifted source where that lowers the summed error, moving to it or swapping sources with "
     "another stray target so that every count stays K or K + 1: larger exemplar pieces; "
     "0 = off (LazyFluids as published).",
     "iterations", 0, 100, &O::uniform_coherence_sweeps},
    {"budget-polish-iterations",
     "Error budget and uniform usage: the finest level searches plain nearest neighbours from "
     "the field the usage laid out, this many iterations instead of finest-em-iterations ones: "
     "the seams of its mosaic "
     "move to where the pieces agree (closer to the exemplar, faster), but the finest grain "
     "partly washes out; 0 = off (StyLit as published).",
     "iterations", 0, 100, &O::budget_polish_iterations},
    {"budget-polish-levels",
     "Error budget and uniform usage: how many of the finest levels polish; the finest when "
     "budget-polish-iterations > 0 (else it keeps the usage), the others (never the coarsest) "
     "keep their EM iterations but search plain nearest neighbours from the upsampled field. "
     "1 = the finest only.",
     "levels", 1, 16, &O::budget_polish_levels},
    {"polish-patch-size",
     "Error budget and uniform usage: patch width of the levels that polish (where it fits); "
     "wider patches place the seams between the pieces the usage laid out where wider strips "
     "of the exemplar agree: closer to the exemplar, for more CPU; odd, 0 = patch-size.",
     "px", 0, 31, &O::polish_patch_size},
    {"budget-max-rounds", "Error budget: maximal reversed-retrieval rounds per EM iteration.",
     "rounds", 1, 1000, &O::budget_max_rounds},
    {"budget-focus",
     "Error budget: below this fraction of free target patches, rounds query only the sources "
     "next to a free target's match or not used yet; 0 = query all sources every round, 1 = "
     "every round after the first.",
     "", 0, 1, &O::budget_focus},
    {"occurrence-strength",
     "Occurrence penalty h_s: added squared error per use of a source patch above the "
     "threshold.",
     "", 0, 1e6, &O::occurrence_strength},
    {"occurrence-threshold",
     "Occurrence penalty h_tau: uses of a source patch before the penalty starts; 0 = automatic "
     "(2 x target/source area ratio).",
     "uses", 0, 1e9, &O::occurrence_threshold},
    {"seed", "Random seed; the same seed gives the same output for any thread count.", "", 0,
     9007199254740992.0, &O::seed},
}};

std::string format_number(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

bool same_name(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const char ca = a[i] == '_' ? '-' : a[i];
        const char cb = b[i] == '_' ? '-' : b[i];
        if (ca != cb) return false;
    }
    return true;
}
}  // namespace

std::span<const OptionSpec> synthesis_option_specs() {
    return kSpecs;
}

double get_option(const SynthesisOptions& options, const OptionSpec& spec) {
    return get_table_option(options, spec);
}

Status set_option(SynthesisOptions& options, const OptionSpec& spec, double value) {
    const bool integral = !std::holds_alternative<float SynthesisOptions::*>(spec.field);
    // Widths of patches and vote footprints are odd (0 = "off" where the range allows it).
    const bool odd_rule = spec.name == "patch-size" || spec.name == "final-vote-size" ||
                          spec.name == "polish-patch-size";
    // A patch width that may be 0 ("as patch-size") is otherwise a patch-size: 3 or more.
    const double smallest = spec.name == "polish-patch-size" ? 3.0 : spec.min;
    const bool bad = !std::isfinite(value) || value < spec.min || value > spec.max ||
                     (integral && value != std::floor(value)) ||
                     (odd_rule && value != 0.0 && static_cast<long long>(value) % 2 == 0) ||
                     (value != 0.0 && value < smallest);
    if (bad) {
        std::string message(spec.name);
        message.append(": ").append(format_number(value)).append(" is invalid (must be ");
        if (odd_rule) message.append(spec.min > 0.0 ? "odd, " : "0 or odd, ");
        if (integral && !odd_rule) message.append("an integer, ");
        message.append(format_number(smallest)).append("..").append(format_number(spec.max));
        message.append(")");
        return invalid_argument(std::move(message));
    }
    assign_table_option(options, spec, value);
    return Status::ok();
}

const OptionSpec* find_option(std::string_view name) {
    for (const OptionSpec& spec : kSpecs) {
        if (same_name(spec.name, name)) return &spec;
    }
    return nullptr;
}

Status validate(const SynthesisOptions& options) {
    return validate_table_options(options, std::span<const OptionSpec>(kSpecs));
}

}  // namespace exemplar
