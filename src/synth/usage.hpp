#pragma once
// Nearest-neighbour search with patch-usage control: the E-step of one EM iteration.
//   none        forward PatchMatch (Kwatra et al. 2005)
//   uniform     reversed retrieval with counters, K and R (Jamriška et al. 2015, LazyFluids §5.4.1)
//   error-budget reversed retrieval under a knee-based budget (Fišer et al. 2016, StyLit §8.3.3)
//   occurrence  forward search with a penalty on over-used source patches (Kaspar et al. 2015,
//               Bénard et al. 2013 eq. 8)

#include <cstdint>
#include <span>
#include <vector>

#include "exemplar/synth/nnf.hpp"
#include "exemplar/synth/options.hpp"
#include "level.hpp"

namespace exemplar::synth {

/// Least-squares fit of f(x) = 1 / (a - b x) to errors sorted ascending, with x = i / (n - 1)
/// and y = error / max error (the normalized axes of StyLit Fig. 8.6).
struct KneeFit {
    double a = 0.0;
    double b = 0.0;
    double knee_x = 1.0;         ///< Where f'(x) = 1, clamped to [0, 1].
    std::size_t knee_index = 0;  ///< First index at or beyond the knee (n if none).
};
KneeFit fit_knee(std::span<const float> sorted_errors);

/// Statistics of one search, for tests and debugging.
struct SearchStats {
    int rounds = 0;                    ///< Reversed-retrieval rounds.
    std::size_t reverse_assigned = 0;  ///< Target patches assigned by reversed retrieval.
    std::size_t forward_assigned = 0;  ///< Target patches assigned by forward search.
};

/// Per-call settings shared by the strategies.
struct SearchSetup {
    const Level& level;
    const SynthesisOptions& options;
    std::uint64_t key;  ///< Hash of (seed, level, iteration); randomness derives from it.
    int threads;
    /// Optional reversed field kept between the EM iterations of a level (uniform and
    /// error-budget strategies): a warm start lets the first reversed round run as few
    /// PatchMatch iterations as the later rounds.
    Nnf* reverse_field = nullptr;
    /// The NNF (and reverse_field, if any) come from the previous EM iteration of this level:
    /// searches run options.warm_search_iterations instead of search_iterations.
    bool warm = false;
    /// Optional candidate fields on the level's target grid (SynthesisInput::candidate_nnfs,
    /// downscaled): every forward PatchMatch iteration also tries their entries per pixel. The
    /// reversed retrieval (source → target) does not; its forward passes do.
    const std::vector<Nnf>* candidates = nullptr;
    /// PatchMatch iterations of the first reversed-retrieval round when it starts warm; 0 = as
    /// the later rounds (options.warm_search_iterations). The engine sets it on the finest level
    /// (options.finest_first_round_iterations).
    int first_round_iterations = 0;
    /// The search is on the finest level: the error budget's coherence sweeps also merge the
    /// pieces smaller than half a patch (merging them on the coarse levels lets a region grow
    /// over another; docs/algorithms.md, Error budget).
    bool finest = false;
    /// The run's last search: nothing reads reverse_field after it, so the first round's field
    /// is not copied for a next iteration (2.56 MB on guided2's finest level, at the peak of the
    /// rounds) and the field is released once the rounds end.
    bool last = false;
    /// The NNF's active entries are valid and their costs those of the level's target as it
    /// stands (evaluate_field of all active pixels just ran): the forward search (usage None)
    /// does not evaluate them again.
    bool evaluated = false;
};

/// Runs the E-step with `setup.options.usage` on the active target pixels, updating `nnf`
/// (whose active entries must hold valid matches on entry, e.g. from the previous iteration).
SearchStats search(const SearchSetup& setup, Nnf& nnf);

/// Coherent pieces: `sweeps` sweeps of iterated conditional modes (Besag 1986) on the Markov
/// random field over the matches E = sum_p D(p, s(p)) + lambda sum_{p~q} [q does not continue
/// s(p)], a Potts term on the offsets over the neighbours q within `radius` (Chebyshev) of p,
/// lambda = weight x the field's mean stored error. Every active target takes, of its own match
/// and its neighbours' matches shifted back to it, the one of least D + lambda x (neighbours
/// that do not propose it); the searches' field becomes a mosaic of fewer, larger exemplar
/// pieces. Targets are visited in (radius + 1)^2 phases of targets more than `radius` apart, so
/// the result does not depend on the thread count. Returns how many matches changed.
std::size_t grow_pieces(const Level& level, Nnf& nnf, int sweeps, float weight, int radius,
                        int threads);

/// Per pixel of a w x h grid, the index of the nearest pixel (Euclidean) whose `set` entry is
/// non-zero (itself if set), or -1 if none is set. Ties go to a fixed one, whatever `threads`.
std::vector<int> nearest_set_pixel(const std::vector<std::uint8_t>& set, int w, int h, int threads);
/// The same into `nearest` (resized to w x h; its storage is reused from call to call).
void nearest_set_pixel(const std::vector<std::uint8_t>& set, int w, int h, int threads,
                       std::vector<int>& nearest);

/// Number of active target pixels whose NNF centre is each source pixel (sw*sh counts).
std::vector<float> usage_counts(const Level& level, const Nnf& nnf);

}  // namespace exemplar::synth
