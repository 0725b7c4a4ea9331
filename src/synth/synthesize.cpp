// Multi-scale EM synthesis driver (Kwatra et al. 2005; Wexler et al. 2007; as used by StyLit,
// Fišer et al. 2016, §8.3.3-8.3.4): build pyramids; for each level coarse to fine: initialize
// or upsample the NNF, then alternate nearest-neighbour search (with the selected usage
// strategy) and voting.

#include "exemplar/synth/synthesize.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <string>

#include "exemplar/core/rng.hpp"
#include "exemplar/filters/resample.hpp"
#include "level_builder.hpp"
#include "patchmatch.hpp"
#include "usage.hpp"
#include "vote.hpp"

namespace exemplar {

namespace {

std::string guide_name(const GuidePair& g, std::size_t i) {
    return g.name.empty() ? "guide " + std::to_string(i + 1) : g.name;
}

Status check_single_channel(const Image& im, const char* what, int w, int h) {
    if (im.channels() != 1) {
        return invalid_argument(std::string(what) + ": has " + std::to_string(im.channels()) +
                                " channels (must be 1)");
    }
    if (im.width() != w || im.height() != h) {
        return invalid_argument(std::string(what) + ": is " + size_str(im) + " (must be " +
                                std::to_string(w) + "x" + std::to_string(h) + ")");
    }
    if (!all_finite(im)) return invalid_argument(std::string(what) + ": contains NaN or infinity");
    return Status::ok();
}

Status check_mask(const Image& mask, const char* what, int w, int h) {
    EXEMPLAR_RETURN_IF_ERROR(check_single_channel(mask, what, w, h));
    const auto inside =
        std::count_if(mask.data().begin(), mask.data().end(), [](float v) { return v > 0.5f; });
    if (inside == 0) return invalid_argument(std::string(what) + ": is empty (no pixel > 0.5)");
    return Status::ok();
}

// A given field: the target's size, every match inside the style or "no match" (-1, -1; for
// candidate fields any x = -1).
Status check_nnf(const Nnf& nnf, const std::string& what, int tw, int th, const Image& style) {
    if (nnf.width() != tw || nnf.height() != th) {
        return invalid_argument(what + ": is " + std::to_string(nnf.width()) + "x" +
                                std::to_string(nnf.height()) + " but the target is " +
                                std::to_string(tw) + "x" + std::to_string(th));
    }
    for (const Match& m : nnf.matches()) {
        const bool no_match = m.x == -1;  // border marker of saved NNFs
        if (!no_match && (m.x < 0 || m.y < 0 || m.x >= style.width() || m.y >= style.height())) {
            return invalid_argument(what + ": refers to " + std::to_string(m.x) + "," +
                                    std::to_string(m.y) + " outside the " + size_str(style) +
                                    " style");
        }
    }
    return Status::ok();
}

std::set<long> label_set(const Image& labels, const Image& mask) {
    std::set<long> out;
    for (std::size_t i = 0; i < labels.pixel_count(); ++i) {
        if (mask.empty() || mask.data()[i] > 0.5f) out.insert(std::lround(labels.data()[i]));
    }
    return out;
}

// An NNF with no valid entry: evaluate_field replaces each with a random valid match.
Nnf unassigned_nnf(int width, int height) {
    Nnf out(width, height);
    for (Match& m : out.matches()) m = Match{-1, -1, 0.0f, 0.0f};
    return out;
}

// The given full-resolution NNF sampled onto the grid of (coarse) level L.
Nnf downscale_nnf(const Nnf& full, const Image& style, const synth::Level& L) {
    const double rx = static_cast<double>(L.tw) / full.width();
    const double ry = static_cast<double>(L.th) / full.height();
    const double sx = static_cast<double>(L.sw) / style.width();
    const double sy = static_cast<double>(L.sh) / style.height();
    Nnf out(L.tw, L.th);
    for (int y = 0; y < L.th; ++y) {
        for (int x = 0; x < L.tw; ++x) {
            const Match& m = full.at(std::min(full.width() - 1, static_cast<int>((x + 0.5) / rx)),
                                     std::min(full.height() - 1, static_cast<int>((y + 0.5) / ry)));
            // "No match" entries stay invalid; evaluate_field gives them a random match.
            out.at(x, y) = m.x < 0 ? Match{-1, -1, 0.0f, 0.0f}
                                   : Match{static_cast<int>(std::lround((m.x + 0.5) * sx - 0.5)),
                                           static_cast<int>(std::lround((m.y + 0.5) * sy - 0.5)),
                                           m.angle_rad, 0.0f};
        }
    }
    return out;
}

// Each active entry of `field` takes the match of `candidates` at its position where that match
// is valid for the problem (mask, labels) and costs less (the problem's own distance).
template <class Problem>
void adopt_candidates(const Problem& P, const Nnf& candidates, Nnf& field, int threads) {
    parallel_for(0, field.height(), threads, [&](int y) {
        for (int x = 0; x < field.width(); ++x) {
            const std::size_t qi = static_cast<std::size_t>(y) * field.width() + x;
            const Match& c = candidates[qi];
            if (!P.query_active(qi) || c.x < 0 || c.y < 0 || c.x >= P.db_width() ||
                c.y >= P.db_height() || !P.db_ok(qi, c.x, c.y)) {
                continue;
            }
            Match& m = field[qi];
            const float angle = P.angle(qi, c.x, c.y);
            const float d = P.cost(x, y, c.x, c.y, angle, m.error);
            if (d < m.error) m = Match{c.x, c.y, angle, d};
        }
    });
}

// Per-pixel distance of the final NNF against the final B' (0 where no patch is centred);
// entries that are not patch centres become (-1, -1).
Image final_errors(const synth::Level& L, Nnf& nnf, int threads) {
    Image error(L.tw, L.th, 1, 0.0f);
    error.set_channel_names({"error"});
    parallel_for(0, L.th, threads, [&](int y) {
        for (int x = 0; x < L.tw; ++x) {
            const std::size_t i = L.target_index(x, y);
            Match& m = nnf[i];
            if (!L.target_active[i]) {
                m = Match{-1, -1, 0.0f, 0.0f};
                continue;
            }
            error.data()[i] = synth::patch_distance(L, x, y, m.x, m.y, m.angle_rad);
        }
    });
    return error;
}

// Vote parameters of a level; `weights` receives the weighted vote's weights if needed
// (`coherence`: SynthesisOptions::vote_coherence).
synth::VoteParams vote_params(const synth::Level& L, VoteMode mode, float coherence, const Nnf& nnf,
                              std::vector<float>* weights, int threads) {
    synth::VoteParams vp;
    vp.patch_size = L.patch_size;
    vp.clamp_source = true;  // source patches over the border repeat its pixels
    vp.active = L.target_active.data();
    vp.fixed = L.target_fixed.empty() ? nullptr : L.target_fixed.data();
    if (mode == VoteMode::Weighted && weights != nullptr) {
        *weights = synth::vote_weights(nnf, vp.active, L.patch_size, coherence, threads);
        vp.patch_weights = *weights;
    }
    return vp;
}

// Progress over the whole run; work units are target pixels x EM iterations x patch area.
struct ProgressTracker {
    const RunContext& context;
    int levels;
    double total_work;
    double done_work = 0.0;
    bool cancelled = false;

    void step(int level, int iteration, int iterations, double work) {
        done_work += work;
        context.report(ProgressEvent{"synthesis", level, levels, iteration, iterations,
                                     std::min(1.0, done_work / total_work)});
    }
};

// Footprint of the run's last vote on a level with this patch size (see final_vote_size).
int last_vote_size(const SynthesisOptions& options, int patch_size) {
    return options.final_vote_size > 0 ? std::min(options.final_vote_size, patch_size) : patch_size;
}

// EM iterations on one level: search with the usage strategy, then vote. `reverse_field` is the
// reversed-retrieval state; with `warm_start` the first search already counts as warm (the NNF
// and reverse_field come from a previous pass over the same level). Every search also tries
// `candidates` (the level's candidate fields; empty = none). On the `finest` level the first
// reversed round runs options.finest_first_round_iterations; with `polish` every search is a
// plain nearest-neighbour one whatever the usage strategy; `piece_sweeps` > 0 runs that many
// sweeps of synth::grow_pieces after every search, over the window of the vote that follows;
// when these iterations `end_run`, the last one votes with the footprint of last_vote_size.
void run_em(synth::Level& L, const SynthesisOptions& options, int iterations, std::uint64_t key,
            int threads, bool warm_start, const std::vector<Nnf>& candidates, bool finest,
            bool polish, int piece_sweeps, bool end_run, Nnf& nnf, Nnf& reverse_field,
            Image& current, ProgressTracker& tracker, const DebugSink& debug) {
    synth::ForwardProblem all{L, L.target_active.data()};
    evaluate_field(all, nnf, hash_keys(key, 0x2), threads);
    const double work = static_cast<double>(L.tw) * L.th * L.patch_size * L.patch_size /
                        (options.patch_size * options.patch_size);
    std::vector<float> weights, histogram;
    // The exemplar's side of the colour-histogram weight, the same for every vote of the level.
    std::optional<synth::SourceHistogram> source_histogram;
    if (options.vote_histogram > 0.0f) source_histogram.emplace(L.source_style);
    // The error budget's polish: plain nearest neighbours from the field the budget laid out
    // (see SynthesisOptions::budget_polish_iterations); the field is a close one (upsampled or
    // the previous iteration's) unless this is the coarsest level.
    SynthesisOptions nearest = options;
    nearest.usage = UsageStrategy::None;
    for (int it = 0; it < iterations; ++it) {
        if (tracker.context.cancelled()) {
            tracker.cancelled = true;
            return;
        }
        const synth::SearchSetup setup{L,
                                       polish ? nearest : options,
                                       hash_keys(key, 0x100 + static_cast<std::uint64_t>(it)),
                                       threads,
                                       &reverse_field,
                                       it > 0 || warm_start || (polish && L.index > 0),
                                       candidates.empty() ? nullptr : &candidates,
                                       finest ? options.finest_first_round_iterations : 0,
                                       finest,
                                       end_run && it + 1 == iterations,
                                       /*evaluated=*/it == 0};
        synth::search(setup, nnf);
        const bool last_vote = end_run && it + 1 == iterations;
        const bool sweeps_now =
            finest || options.piece_iterations == 0 || it + options.piece_iterations >= iterations;
        if (piece_sweeps > 0 && sweeps_now) {
            // The window of the seams counted: the footprint of the vote that follows.
            const int footprint = last_vote ? last_vote_size(options, L.patch_size) : L.patch_size;
            synth::grow_pieces(L, nnf, piece_sweeps, options.piece_weight, footprint / 2, threads);
        }
        synth::VoteParams vp =
            vote_params(L, options.vote, options.vote_coherence, nnf, &weights, threads);
        if (last_vote) {
            vp.footprint = last_vote_size(options, L.patch_size);
            vp.blend_seams = options.final_vote_seams != 0;
        }
        if (source_histogram) {
            // Against the histogram of the target as it stands before this vote.
            histogram = source_histogram->weights(current, L.target_active.data(),
                                                  options.vote_histogram, threads);
            vp.source_weights = histogram;
        }
        synth::vote(nnf, L.source_style, vp, current, threads);
        set_target_style(L, current, threads);
        tracker.step(L.index, it, iterations, work);
        if (debug) {
            const std::vector<float> counts = synth::usage_counts(L, nnf);
            Image usage(L.sw, L.sh, 1);
            std::copy(counts.begin(), counts.end(), usage.data().begin());
            debug(DebugFrame{L.index, it, &nnf, &usage, &current});
        }
    }
}

}  // namespace

Status validate_input(const SynthesisInput& in, const SynthesisOptions& options) {
    EXEMPLAR_RETURN_IF_ERROR(validate(options));
    if (in.style.empty()) return invalid_argument("style: is empty");
    if (!all_finite(in.style)) return invalid_argument("style: contains NaN or infinity");
    const int sw = in.style.width(), sh = in.style.height();
    if (!in.style_channel_weights.empty()) {
        if (static_cast<int>(in.style_channel_weights.size()) != in.style.channels()) {
            return invalid_argument(
                "style-weights: " + std::to_string(in.style_channel_weights.size()) +
                " values given but the style has " + std::to_string(in.style.channels()) +
                " channels");
        }
        for (float w : in.style_channel_weights) {
            if (!(w >= 0.0f) || !std::isfinite(w)) {
                return invalid_argument("style-weights: " + std::to_string(w) +
                                        " is invalid (must be >= 0)");
            }
        }
    }
    for (std::size_t i = 0; i < in.guides.size(); ++i) {
        const GuidePair& g = in.guides[i];
        const std::string name = guide_name(g, i);
        if (g.source.empty() || g.target.empty()) return invalid_argument(name + ": is empty");
        if (!g.source.same_size(in.style)) {
            return invalid_argument(name + ": source guide is " + size_str(g.source) +
                                    " but the style is " + size_str(in.style));
        }
        if (!g.target.same_size(in.guides.front().target)) {
            return invalid_argument(name + ": target guide is " + size_str(g.target) +
                                    " but the first target guide is " +
                                    size_str(in.guides.front().target));
        }
        if (g.source.channels() != g.target.channels()) {
            return invalid_argument(
                name + ": source guide has " + std::to_string(g.source.channels()) +
                " channels but the target guide has " + std::to_string(g.target.channels()));
        }
        if (!(g.weight >= 0.0f) || !std::isfinite(g.weight)) {
            return invalid_argument(name + ": weight " + std::to_string(g.weight) +
                                    " is invalid (must be >= 0)");
        }
        if (!all_finite(g.source) || !all_finite(g.target)) {
            return invalid_argument(name + ": contains NaN or infinity");
        }
    }
    int tw = 0, th = 0;
    synth::target_size(in, tw, th);
    if (tw <= 0 || th <= 0) {
        return invalid_argument("target size: unknown (give guides, an initial target or a size)");
    }
    for (std::size_t i = 0; i < in.guides.size(); ++i) {
        const GuidePair& g = in.guides[i];
        if (g.target_weight_map.empty()) continue;
        const std::string what = guide_name(g, i) + " weight map";
        EXEMPLAR_RETURN_IF_ERROR(check_single_channel(g.target_weight_map, what.c_str(), tw, th));
        for (float v : g.target_weight_map.data()) {
            if (v < 0.0f) return invalid_argument(what + ": has negative values");
        }
    }
    if (!in.initial_target.empty()) {
        if (in.initial_target.width() != tw || in.initial_target.height() != th) {
            return invalid_argument("initial target: is " + size_str(in.initial_target) +
                                    " but the target is " + std::to_string(tw) + "x" +
                                    std::to_string(th));
        }
        if (in.initial_target.channels() != in.style.channels()) {
            return invalid_argument(
                "initial target: has " + std::to_string(in.initial_target.channels()) +
                " channels but the style has " + std::to_string(in.style.channels()));
        }
        if (!all_finite(in.initial_target)) {
            return invalid_argument("initial target: contains NaN or infinity");
        }
    }
    if (!in.target_mask.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(check_mask(in.target_mask, "target mask", tw, th));
        if (in.initial_target.empty()) {
            return invalid_argument(
                "target mask: needs an initial target (the content kept outside the mask)");
        }
    }
    if (!in.source_mask.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(check_mask(in.source_mask, "source mask", sw, sh));
    }
    if (in.source_labels.empty() != in.target_labels.empty()) {
        return invalid_argument("labels: give both source and target labels, or neither");
    }
    if (!in.source_labels.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(check_single_channel(in.source_labels, "source labels", sw, sh));
        EXEMPLAR_RETURN_IF_ERROR(check_single_channel(in.target_labels, "target labels", tw, th));
        const std::set<long> have = label_set(in.source_labels, in.source_mask);
        for (long label : label_set(in.target_labels, in.target_mask)) {
            if (!have.count(label)) {
                return invalid_argument("target labels: label " + std::to_string(label) +
                                        " does not occur in the source labels" +
                                        (in.source_mask.empty() ? "" : " inside the source mask"));
            }
        }
    }
    if (in.source_orientation.empty() != in.target_orientation.empty()) {
        return invalid_argument(
            "orientation: give both source and target orientation fields, or neither");
    }
    if (!in.source_orientation.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(
            check_single_channel(in.source_orientation, "source orientation", sw, sh));
        EXEMPLAR_RETURN_IF_ERROR(
            check_single_channel(in.target_orientation, "target orientation", tw, th));
    }
    if (in.orientation_steps != 0 && (in.orientation_steps < 4 || in.orientation_steps > 1024)) {
        return invalid_argument("orientation steps: " + std::to_string(in.orientation_steps) +
                                " is invalid (must be 0 or 4..1024)");
    }
    if (in.rotate_target_patches && (in.orientation_steps == 0 || in.source_orientation.empty())) {
        return invalid_argument(
            "rotate target patches: needs orientation fields and orientation steps (4..1024)");
    }
    const bool rotated = !in.source_orientation.empty();
    const int room =
        synth::max_levels(std::min(sw, sh), options.patch_size, options.pyramid_ratio, rotated);
    if (room < 1) {
        return invalid_argument("patch-size: " + std::to_string(options.patch_size) +
                                " is too large for the " + size_str(in.style) + " style" +
                                (rotated ? " with rotated patches" : ""));
    }
    const int troom =
        synth::max_levels(std::min(tw, th), options.patch_size, options.pyramid_ratio, false);
    if (troom < 1) {
        return invalid_argument("patch-size: " + std::to_string(options.patch_size) +
                                " is too large for the " + std::to_string(tw) + "x" +
                                std::to_string(th) + " target");
    }
    if (options.levels > std::min(room, troom)) {
        return invalid_argument("levels: " + std::to_string(options.levels) +
                                " is too many for these sizes and patch-size " +
                                std::to_string(options.patch_size) + " (at most " +
                                std::to_string(std::min(room, troom)) + ")");
    }
    if (!in.initial_nnf.empty()) {
        EXEMPLAR_RETURN_IF_ERROR(check_nnf(in.initial_nnf, "initial nnf", tw, th, in.style));
    }
    for (std::size_t i = 0; i < in.candidate_nnfs.size(); ++i) {
        const std::string what = "candidate nnf " + std::to_string(i + 1);
        EXEMPLAR_RETURN_IF_ERROR(check_nnf(in.candidate_nnfs[i], what, tw, th, in.style));
    }
    if (!in.source_mask.empty()) {
        // Some patch must fit entirely inside the mask at full resolution.
        const std::vector<std::uint8_t> valid =
            synth::source_validity(sw, sh, options.patch_size / 2, in.source_mask);
        const bool any = std::find(valid.begin(), valid.end(), 1) != valid.end();
        if (!any) {
            return invalid_argument("source mask: no " + std::to_string(options.patch_size) + "x" +
                                    std::to_string(options.patch_size) +
                                    " patch fits entirely inside it");
        }
    }
    return Status::ok();
}

namespace {

// `owned`: the caller's input to release after the finest level is built (nullptr: keep it).
Result<SynthesisResult> run_synthesis(const SynthesisInput& in, SynthesisInput* owned,
                                      const SynthesisOptions& options, const RunContext& context,
                                      const DebugSink& debug) {
    EXEMPLAR_RETURN_IF_ERROR(validate_input(in, options));
    const int threads = context.threads;
    int tw = 0, th = 0;
    synth::target_size(in, tw, th);
    const bool rotated = !in.source_orientation.empty();
    const int min_side = std::min({in.style.width(), in.style.height(), tw, th});
    const int levels =
        options.levels > 0
            ? options.levels
            : std::min(
                  synth::automatic_levels(min_side, options.patch_size, options.pyramid_ratio),
                  synth::max_levels(min_side, options.patch_size, options.pyramid_ratio, rotated));
    synth::LevelBuilder builder(in, options, levels, threads);
    // Patch width of level l (polish_patch_size where it polishes and fits, as patch_size must).
    const int polish_room =
        options.polish_patch_size > 0
            ? synth::max_levels(min_side, options.polish_patch_size, options.pyramid_ratio, rotated)
            : 0;
    const auto level_patch_size = [&](int l) {
        const int depth = levels - 1 - l;
        return patch_size_of_level(options, depth, levels, depth < polish_room);
    };

    // Progress is proportional to target pixels x EM iterations x patch area.
    double total_work = 0.0;
    for (int l = 0; l < levels; ++l) {
        const int depth = levels - 1 - l, p = level_patch_size(l);
        total_work += static_cast<double>(pyramid_level_size(tw, options.pyramid_ratio, depth)) *
                      pyramid_level_size(th, options.pyramid_ratio, depth) *
                      em_iterations_of_level(options, depth, levels) * p * p /
                      (options.patch_size * options.patch_size);
    }
    if (options.final_pass_iterations > 0 && options.patch_size > 3) {
        total_work += static_cast<double>(tw) * th * options.final_pass_iterations * 9.0 /
                      (options.patch_size * options.patch_size);
    }
    ProgressTracker tracker{context, levels, total_work};

    Nnf nnf;
    Nnf reverse_field;  // reversed-retrieval state (usage strategies), carried across levels
    Image current;      // B' at the current level
    int prev_sw = 0, prev_sh = 0, prev_tw = 0, prev_th = 0;
    SynthesisResult result;
    result.guide_compression = builder.guide_compression();
    const std::vector<std::string> style_channel_names = in.style.channel_names();
    for (int l = 0; l < levels; ++l) {
        if (context.cancelled()) return cancelled();
        synth::Level L = builder.build(l, level_patch_size(l));
        if (l == levels - 1) L.search_radius = options.finest_search_radius;
        if (!in.source_labels.empty() && L.target_label.empty()) {
            result.unlabelled_levels.push_back(levels - 1 - l);
        }
        const std::uint64_t level_key = hash_keys(options.seed, static_cast<std::uint64_t>(l));
        synth::ForwardProblem all{L, L.target_active.data()};
        // Candidate fields on this level's grid: tried once below, then in every PatchMatch
        // iteration of the searches (as B' changes, a candidate that lost here may win later).
        std::vector<Nnf> candidates;
        for (const Nnf& c : in.candidate_nnfs) candidates.push_back(downscale_nnf(c, in.style, L));

        // The run's last vote (finest level, or the final pass after it) keeps the fine grain.
        const bool finest = l == levels - 1;
        const bool final_pass = options.final_pass_iterations > 0 && options.patch_size > 3;
        // Initialize the NNF: random at the coarsest level (or the given one), else upsampled.
        if (l == 0) {
            nnf = in.initial_nnf.empty() ? unassigned_nnf(L.tw, L.th)
                                         : downscale_nnf(in.initial_nnf, in.style, L);
        }
        if (finest && !final_pass && owned != nullptr) {
            // Nothing reads the full-resolution inputs any more: the level holds its own copies.
            // Released before the level's fields are upsampled (the run's peak of memory was
            // both at once: guided2 19.5 MB of heap).
            builder.release_inputs();
            *owned = SynthesisInput{};
        }
        if (l > 0) {
            nnf = upsample_nnf(nnf, prev_sw, prev_sh, L.tw, L.th, L.sw, L.sh, threads);
            // The reversed-retrieval state starts from the coarser level's too.
            if (!reverse_field.empty()) {
                reverse_field =
                    upsample_nnf(reverse_field, prev_tw, prev_th, L.sw, L.sh, L.tw, L.th, threads);
            }
        }

        // Initial B' of this level: the initial target on the coarsest level if given, else
        // the vote of the initial NNF. Fixed pixels always hold the initial target.
        current = L.fixed_style.empty() ? Image(L.tw, L.th, L.style_channels) : L.fixed_style;
        current.set_channel_names(style_channel_names);
        set_target_style(L, current, threads);
        // Valid entries for the initial vote (an average: no costs); run_em evaluates the costs
        // against the voted B'.
        evaluate_field(all, nnf, hash_keys(level_key, 0x1), threads, synth::FieldCosts::None);
        const bool keep_initial = l == 0 && !L.fixed_style.empty() && L.target_fixed.empty();
        auto vote_initial = [&] {
            if (keep_initial) return;
            synth::vote(nnf, L.source_style,
                        vote_params(L, VoteMode::Average, 0.0f, nnf, {}, threads), current,
                        threads);
            set_target_style(L, current, threads);
        };
        vote_initial();
        if (!candidates.empty()) {
            // Candidates compete on costs against this initial B' (before the vote the coarsest
            // level's B' is empty, which would favour dark patches), then B' is voted again.
            evaluate_field(all, nnf, hash_keys(level_key, 0x1), threads);
            for (const Nnf& c : candidates) adopt_candidates(all, c, nnf, threads);
            vote_initial();
        }
        const int iterations = em_iterations_of_level(options, levels - 1 - l, levels);
        run_em(L, options, iterations, level_key, threads, /*warm_start=*/false, candidates, finest,
               /*polish=*/polishes_level(options, levels - 1 - l, levels),
               piece_sweeps_of_level(options, levels - 1 - l, levels),
               /*end_run=*/finest && !final_pass, nnf, reverse_field, current, tracker, debug);
        if (tracker.cancelled) return cancelled();
        prev_sw = L.sw;
        prev_sh = L.sh;
        prev_tw = L.tw;
        prev_th = L.th;

        if (finest) {
            // Optional final iterations with 3x3 patches restore the finest grain.
            if (final_pass) {
                synth::Level fine = builder.build(l, 3);
                fine.search_radius = L.search_radius;
                set_target_style(fine, current, threads);
                // Same grid as the last pass: both fields carry over (every 5x5 match is a
                // valid 3x3 match).
                run_em(fine, options, options.final_pass_iterations, hash_keys(level_key, 0x333),
                       threads, /*warm_start=*/true, candidates, /*finest=*/true,
                       /*polish=*/false, /*piece_sweeps=*/0, /*end_run=*/true, nnf, reverse_field,
                       current, tracker, debug);
                if (tracker.cancelled) return cancelled();
                L = std::move(fine);
            }
            result.nnf_patch_size = L.patch_size;
            result.vote_size = last_vote_size(options, L.patch_size);
            result.vote_seams = options.final_vote_seams != 0;
            result.vote_coherence =
                options.vote == VoteMode::Weighted ? options.vote_coherence : 0.0f;
            result.error = final_errors(L, nnf, threads);
        }
    }
    // A cancel asked for at the run's last progress report (after its last check) cancels too.
    if (context.cancelled()) return cancelled();
    result.image = std::move(current);
    result.nnf = std::move(nnf);
    return result;
}

}  // namespace

Result<SynthesisResult> synthesize(const SynthesisInput& in, const SynthesisOptions& options,
                                   const RunContext& context, const DebugSink& debug) {
    return run_synthesis(in, nullptr, options, context, debug);
}

Result<SynthesisResult> synthesize(SynthesisInput&& in, const SynthesisOptions& options,
                                   const RunContext& context, const DebugSink& debug) {
    return run_synthesis(in, &in, options, context, debug);
}

}  // namespace exemplar
