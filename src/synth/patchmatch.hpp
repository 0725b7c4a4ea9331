#pragma once
// PatchMatch (Barnes et al. 2009) over a generic "problem": for every active query position find
// the database position of least cost, by propagation from scan-order neighbours and random
// search around the current best, plus one uniformly drawn valid candidate per pixel (this keeps
// label/mask-constrained searches from stalling when the allowed region is small), plus the
// problem's extra candidates for the position if it has any (ribbons, Bénard et al. 2013 §4.1).
// Far exploration (windows wider than kNearRadius, and in the reversed retrieval the uniform
// draw) runs for half of the queries of an iteration, on a checkerboard that alternates between
// iterations: its candidates are the ones that miss the caches, they rarely win, and propagation
// hands a far find to the neighbours (measurements in docs/PERFORMANCE.md). The forward search
// draws for every query: there the draw is what finds rare allowed patches (thin strokes,
// small label regions), and it is a small share of the candidates. The reversed retrieval draws
// only in the first round of a search: later rounds look for the few targets still free,
// scattered between taken ones, where a uniformly drawn target almost never wins (about 1 in
// 10,000 draws) and when it does, it is an incoherent match far from the query's neighbours.
//
// The same code serves the forward search (query = target pixel, database = source patch) and
// the reversed retrieval of the usage strategies (query = source patch, database = target pixel).
//
// Determinism: the query grid is cut into fixed bands of kBandRows rows, processed in parallel.
// Inside a band, propagation reads the current field; across band borders it reads a copy of
// the neighbouring band's border row taken at the start of the iteration. Random numbers are keyed
// by (key, iteration, pixel). Hence the result does not depend on the number of threads.

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <vector>

#include "exemplar/core/parallel.hpp"
#include "exemplar/core/rng.hpp"
#include "exemplar/synth/nnf.hpp"
#include "patch_distance.hpp"

namespace exemplar::synth {

inline constexpr int kBandRows = 8;
/// Random-search windows up to this radius (pixels of the database grid) are sampled for every
/// query; wider ones (and the reversed retrieval's uniform draw) only for the queries of
/// far_exploration().
inline constexpr int kNearRadius = 64;

/// Whether query (x, y) explores far (wide windows, uniform draw) in PatchMatch iteration
/// `iter` of a run keyed `key`: a checkerboard whose phase flips every iteration and depends on
/// the key, so every query explores far in every other iteration of a run and in half of the
/// one-iteration runs (occurrence penalty, animation sweeps).
inline bool far_exploration(int x, int y, int iter, std::uint64_t key) {
    return ((static_cast<std::uint64_t>(x + y + iter) + (key >> 17)) & 1u) == 0;
}

/// A mask packed one bit per entry: 8x smaller than a byte mask, so the random lookups of the
/// search (is this candidate allowed?) hit the L2 cache instead of waiting on memory.
inline std::vector<std::uint64_t> pack_mask(const std::vector<std::uint8_t>& mask) {
    std::vector<std::uint64_t> bits((mask.size() + 63) / 64, 0);
    for (std::size_t i = 0; i < mask.size(); ++i) {
        if (mask[i]) bits[i / 64] |= std::uint64_t{1} << (i % 64);
    }
    return bits;
}
inline bool mask_bit(const std::uint64_t* bits, std::size_t i) {
    return (bits[i / 64] >> (i % 64)) & 1u;
}

/// Offset of a one-pixel step (dx, dy) in a neighbour's match rotated by its angle.
inline RotatedOffset rotated_step(float angle_rad, int dx, int dy) {
    if (angle_rad == 0.0f) return {dx, dy};
    return rotate_offset(dx, dy, std::cos(angle_rad), std::sin(angle_rad));
}

/// rotated_step for a one-pixel move (|dx| + |dy| = 1) on level L: the level's table when the
/// angle is one of its orientation steps (the same offsets without a cosine and a sine).
inline RotatedOffset rotated_step(const Level& L, float angle_rad, int dx, int dy) {
    if (angle_rad == 0.0f) return {dx, dy};
    if (const int k = L.table_step(angle_rad); k >= 0) {
        const int move = dx != 0 ? (dx > 0 ? 0 : 1) : (dy > 0 ? 2 : 3);
        const int* o = &L.step_moves[static_cast<std::size_t>(8 * k + 2 * move)];
        return {o[0], o[1]};
    }
    return rotated_step(angle_rad, dx, dy);
}

/// Random-search windows per query at most: one per halving of the database's larger side.
inline constexpr int kMaxWindows = 32;

/// Asks the caches for the first rows of the patch centred at (x, y) of `features` (clamped to
/// the image), the rows a patch distance reads before it can stop early. No effect on results.
inline void prefetch_patch(const FeatureImage& features, int radius, int x, int y) {
    constexpr int kRows = 2;
    const int x0 = std::max(0, x - radius);
    const int x1 = std::min(features.width() - 1, x + radius);
    for (int k = 0; k < kRows; ++k) {
        const int row = std::clamp(y - radius + k, 0, features.height() - 1);
        // A patch row may straddle cache lines: its first and its last byte.
        __builtin_prefetch(features.pixel(x0, row));
        __builtin_prefetch(features.pixel(x1, row) + features.stride() - 1);
    }
}

/// What evaluate_field computes besides making every active entry valid.
enum class FieldCosts {
    All,      ///< The cost of every active entry.
    Invalid,  ///< Only replaced entries' and those without one (when only validity changed).
    /// None: valid entries keep their stored error, replaced ones get infinity (for a field
    /// whose costs nothing reads before they are evaluated again).
    None,
};

/// Evaluates the cost of every active entry (entries whose position is no longer valid are
/// replaced by a random valid one) and sets its angle. Call after the problem's costs changed.
/// `costs` says which costs are computed.
template <class Problem>
void evaluate_field(const Problem& P, Nnf& field, std::uint64_t key, int threads,
                    FieldCosts costs = FieldCosts::All) {
    parallel_for(0, field.height(), threads, [&](int y) {
        for (int x = 0; x < field.width(); ++x) {
            const std::size_t qi = static_cast<std::size_t>(y) * field.width() + x;
            if (!P.query_active(qi)) continue;
            Match& m = field[qi];
            const bool in_bounds =
                m.x >= 0 && m.y >= 0 && m.x < P.db_width() && m.y < P.db_height();
            const bool valid = in_bounds && P.db_ok(qi, m.x, m.y);
            if (valid && costs == FieldCosts::Invalid &&
                m.error < std::numeric_limits<float>::infinity()) {
                continue;
            }
            if (!valid) {
                KeyedRng rng(key, qi);
                int dx = 0, dy = 0;
                if (!P.repair(qi, m, rng, dx, dy)) {
                    m.error = std::numeric_limits<float>::infinity();
                    continue;
                }
                m.x = dx;
                m.y = dy;
            }
            m.angle_rad = P.angle(qi, m.x, m.y);
            if (costs == FieldCosts::None) {
                if (!valid) m.error = std::numeric_limits<float>::infinity();
                continue;
            }
            m.error = P.cost(x, y, m.x, m.y, m.angle_rad, std::numeric_limits<float>::infinity());
        }
    });
}

/// What a PatchMatch iteration tries per query.
enum class Exploration {
    /// Propagation, the problem's candidates, random search and the uniform draw.
    Full,
    /// Propagation only: a query takes its scan-order neighbour's shifted match where that is
    /// closer. Grows coherent regions (every accepted step makes two neighbours continue one
    /// source region) and finds nothing new.
    PropagationOnly,
};

/// Runs `iterations` PatchMatch iterations on `field` (whose active entries must be evaluated).
template <class Problem>
void run_patchmatch(const Problem& P, Nnf& field, int iterations, std::uint64_t key, int threads,
                    Exploration exploration = Exploration::Full) {
    const int w = field.width();
    const int h = field.height();
    const int bands = (h + kBandRows - 1) / kBandRows;
    // The one row each band reads across its border, as it was at the start of the iteration.
    std::vector<Match> border(static_cast<std::size_t>(bands) * static_cast<std::size_t>(w));
    const int max_x = P.db_width() - 1;
    const int max_y = P.db_height() - 1;
    const int whole = std::max(P.db_width(), P.db_height());
    const int max_radius = P.L.search_radius > 0 ? std::min(whole, P.L.search_radius) : whole;
    for (int iter = 0; iter < iterations; ++iter) {
        const bool forward_scan = iter % 2 == 0;
        const int step = forward_scan ? 1 : -1;
        for (int band = 0; band < bands; ++band) {
            const int row = forward_scan ? band * kBandRows - 1 : (band + 1) * kBandRows;
            if (row < 0 || row >= h) continue;
            std::copy_n(&field[static_cast<std::size_t>(row) * w], w,
                        border.begin() + static_cast<std::ptrdiff_t>(band) * w);
        }
        parallel_for(0, bands, threads, [&](int band) {
            const int y0 = band * kBandRows;
            const int y1 = std::min(h, y0 + kBandRows);
            std::array<int, kMaxWindows> window_dx{}, window_dy{};
            for (int yi = 0; yi < y1 - y0; ++yi) {
                const int y = forward_scan ? y0 + yi : y1 - 1 - yi;
                for (int xi = 0; xi < w; ++xi) {
                    const int x = forward_scan ? xi : w - 1 - xi;
                    const std::size_t qi = static_cast<std::size_t>(y) * w + x;
                    if (!P.query_active(qi)) continue;
                    Match best = field[qi];

                    auto try_candidate = [&](int cx, int cy) {
                        if (cx < 0 || cy < 0 || cx >= P.db_width() || cy >= P.db_height()) return;
                        if (cx == best.x && cy == best.y) return;
                        if (!P.db_ok(qi, cx, cy)) return;
                        const float angle = P.angle(qi, cx, cy);
                        const float d = P.cost(x, y, cx, cy, angle, best.error);
                        if (d < best.error) best = Match{cx, cy, angle, d};
                    };

                    // Propagation from the neighbours already visited in this scan.
                    const int nx = x - step;
                    const int ny = y - step;
                    if (nx >= 0 && nx < w) {
                        const std::size_t ni = static_cast<std::size_t>(y) * w + nx;
                        if (P.has_match(ni)) {
                            const Match& m = field[ni];
                            const RotatedOffset o = rotated_step(P.L, m.angle_rad, step, 0);
                            try_candidate(m.x + o.dx, m.y + o.dy);
                        }
                    }
                    if (ny >= 0 && ny < h) {
                        const std::size_t ni = static_cast<std::size_t>(ny) * w + x;
                        if (P.has_match(ni)) {
                            const bool same_band = ny >= y0 && ny < y1;
                            const Match& m = same_band
                                                 ? field[ni]
                                                 : border[static_cast<std::size_t>(band) * w + x];
                            const RotatedOffset o = rotated_step(P.L, m.angle_rad, 0, step);
                            try_candidate(m.x + o.dx, m.y + o.dy);
                        }
                    }

                    if (exploration == Exploration::PropagationOnly) {
                        field[qi] = best;
                        continue;
                    }

                    // Extra candidates at this position (ribbons), before the random search
                    // so that it explores around them too.
                    for (int k = 0; k < P.candidate_count(); ++k) {
                        const Match& c = P.candidate(k, qi);
                        if (c.x >= 0) try_candidate(c.x, c.y);
                    }

                    // Random search in shrinking windows around the best match. The windows'
                    // offsets do not depend on the best match, so they are drawn first (the
                    // generator's stream as before) and the candidates' patches are requested
                    // from memory together before any is costed: most lie far from the queries
                    // around, and one at a time each waited for its cache misses.
                    KeyedRng rng(key, static_cast<std::uint64_t>(iter), qi);
                    const bool far = far_exploration(x, y, iter, key);
                    int windows = 0;
                    for (int radius = max_radius; radius >= 1; radius /= 2) {
                        if (radius > kNearRadius && !far) continue;
                        const auto i = static_cast<std::size_t>(windows++);
                        window_dx[i] = rng.range(-radius, radius);
                        window_dy[i] = rng.range(-radius, radius);
                    }
                    for (int i = 0; i < windows; ++i) {
                        const auto ui = static_cast<std::size_t>(i);
                        P.prefetch(std::clamp(best.x + window_dx[ui], 0, max_x),
                                   std::clamp(best.y + window_dy[ui], 0, max_y));
                    }
                    for (int i = 0; i < windows; ++i) {
                        const auto ui = static_cast<std::size_t>(i);
                        try_candidate(std::clamp(best.x + window_dx[ui], 0, max_x),
                                      std::clamp(best.y + window_dy[ui], 0, max_y));
                    }
                    // One candidate drawn from everything this query may use.
                    int rx = 0, ry = 0;
                    if (P.draws(far) && P.random_db(qi, rng, rx, ry)) {
                        try_candidate(rx, ry);
                    }

                    field[qi] = best;
                }
            }
        });
    }
}

/// A key no other ForwardProblem of the process has (for its cache of turned target patches).
inline std::uint64_t next_problem_key() {
    static std::atomic<std::uint64_t> next{0};
    return next.fetch_add(1, std::memory_order_relaxed) + 1;
}

/// Forward search: target pixels → source patch centres. The level's target features must not
/// change while a problem is in use (they are read through a per-thread cache).
struct ForwardProblem {
    const Level& L;
    const std::uint8_t* process;            ///< Target pixels to optimize (tw*th).
    const std::uint8_t* allowed = nullptr;  ///< Optional: source centres allowed (sw*sh).
    const float* penalty = nullptr;         ///< Optional: cost added per source centre.
    /// Optional: the lists random candidates are drawn from, per label group (default: every
    /// valid source centre of the group). Must agree with `allowed`.
    const std::vector<std::vector<int>>* draw_lists = nullptr;
    /// Optional: fields on the target grid whose entry at a pixel every iteration tries as one
    /// more candidate (x = -1: none); see SynthesisInput::candidate_nnfs.
    const std::vector<Nnf>* candidates = nullptr;

    /// Optional (tw*th): target pixels whose matches propagate to their neighbours (default:
    /// `process`); set when only some of the matched pixels are optimized.
    const std::uint8_t* matched = nullptr;
    /// Identifies this problem's turned target patches in the per-thread cache (turned_target).
    std::uint64_t key = next_problem_key();

    int db_width() const { return L.sw; }
    int db_height() const { return L.sh; }
    bool query_active(std::size_t qi) const { return process[qi] != 0; }
    bool has_match(std::size_t qi) const {
        return (matched != nullptr ? matched : process)[qi] != 0;
    }
    bool db_ok(std::size_t qi, int sx, int sy) const {
        return L.compatible(qi, sx, sy) && (allowed == nullptr || allowed[L.source_index(sx, sy)]);
    }
    float angle(std::size_t qi, int sx, int sy) const { return L.angle_for(qi, sx, sy); }
    void prefetch(int sx, int sy) const { prefetch_patch(L.source_features, L.radius, sx, sy); }
    float cost(int tx, int ty, int sx, int sy, float angle_rad, float bound) const {
        const float extra = penalty != nullptr ? penalty[L.source_index(sx, sy)] : 0.0f;
        // patch_distance's value; a turned target patch is gathered once for all the
        // candidates of a query at the same step.
        if (const int step = turned_target_step(L, tx, ty, sx, sy, angle_rad); step >= 0) {
            return turned_target_distance(L, turned_target(tx, ty, step), sx, sy, bound - extra) +
                   extra;
        }
        return patch_distance(L, tx, ty, sx, sy, angle_rad, bound - extra) + extra;
    }
    /// gather_target_patch(L, tx, ty, step), kept per thread until another is asked for.
    const std::uint8_t* turned_target(int tx, int ty, int step) const {
        struct Cache {
            std::uint64_t key = 0;
            int tx = 0, ty = 0, step = 0;
            alignas(64) std::uint8_t block[kTargetPatchBytes];
        };
        thread_local Cache cache;
        if (cache.key != key || cache.tx != tx || cache.ty != ty || cache.step != step) {
            gather_target_patch(L, tx, ty, step, cache.block);
            cache.key = key;
            cache.tx = tx;
            cache.ty = ty;
            cache.step = step;
        }
        return cache.block;
    }
    int candidate_count() const {
        return candidates != nullptr ? static_cast<int>(candidates->size()) : 0;
    }
    const Match& candidate(int k, std::size_t qi) const {
        return (*candidates)[static_cast<std::size_t>(k)][qi];
    }
    /// Every query draws a uniform candidate in every iteration (see the file comment).
    bool draws(bool /*far*/) const { return true; }
    /// Replacement for an invalid entry: a random valid source centre.
    bool repair(std::size_t qi, const Match&, KeyedRng& rng, int& sx, int& sy) const {
        return random_db(qi, rng, sx, sy);
    }
    bool random_db(std::size_t qi, KeyedRng& rng, int& sx, int& sy) const {
        const auto& lists = draw_lists != nullptr ? *draw_lists : L.valid_by_group;
        const auto& list = lists[static_cast<std::size_t>(L.target_group(qi))];
        if (list.empty()) return false;
        for (int attempt = 0; attempt < 8; ++attempt) {
            const int s = list[rng.below(static_cast<std::uint32_t>(list.size()))];
            if (allowed != nullptr && !allowed[static_cast<std::size_t>(s)]) continue;
            sx = s % L.sw;
            sy = s / L.sw;
            return true;
        }
        return false;
    }
};

/// Reversed retrieval: source patch centres → free target pixels. Stored angles are the
/// rotation from source to target coordinates (the negated forward angle).
struct ReverseProblem {
    const Level& L;
    const std::uint8_t* query_ok;      ///< Source centres that look for a target (sw*sh).
    const std::uint64_t* target_free;  ///< Target pixels still to be assigned (pack_mask).
    const std::vector<std::vector<int>>& free_by_group;  ///< Free target pixels per label group.
    /// Optional (tw*th): the nearest free target pixel of every target pixel, or -1.
    const int* nearest_free = nullptr;

    int db_width() const { return L.tw; }
    int db_height() const { return L.th; }
    bool query_active(std::size_t si) const { return query_ok[si] != 0; }
    bool has_match(std::size_t si) const { return query_active(si); }
    bool db_ok(std::size_t si, int tx, int ty) const {
        const std::size_t ti = L.target_index(tx, ty);
        return mask_bit(target_free, ti) && L.target_group(ti) == L.source_group(si);
    }
    float angle(std::size_t si, int tx, int ty) const {
        return -L.angle_for_source(L.target_index(tx, ty), si);
    }
    void prefetch(int tx, int ty) const { prefetch_patch(L.target_features, L.radius, tx, ty); }
    float cost(int sx, int sy, int tx, int ty, float angle_rad, float bound) const {
        return patch_distance(L, tx, ty, sx, sy, -angle_rad, bound);
    }
    int candidate_count() const { return 0; }  // candidate fields are target → source
    Match candidate(int, std::size_t) const { return Match{-1, -1, 0.0f, 0.0f}; }
    /// Whether the uniform draw is on (the first round of a search; see the file comment).
    bool uniform_draw = true;
    /// The uniform draw is part of the far exploration (see the file comment).
    bool draws(bool far) const { return uniform_draw && far; }
    /// Replacement for an entry whose target was taken: the free target nearest to it (similar
    /// content, so the search resumes close to its optimum), else a random free target.
    bool repair(std::size_t si, const Match& old, KeyedRng& rng, int& tx, int& ty) const {
        if (nearest_free != nullptr && old.x >= 0 && old.y >= 0 && old.x < L.tw && old.y < L.th) {
            const int t = nearest_free[L.target_index(old.x, old.y)];
            if (t >= 0 && L.target_group(static_cast<std::size_t>(t)) == L.source_group(si)) {
                tx = t % L.tw;
                ty = t / L.tw;
                return true;
            }
        }
        return random_db(si, rng, tx, ty);
    }
    bool random_db(std::size_t si, KeyedRng& rng, int& tx, int& ty) const {
        const auto& list = free_by_group[static_cast<std::size_t>(L.source_group(si))];
        if (list.empty()) return false;
        const int t = list[rng.below(static_cast<std::uint32_t>(list.size()))];
        tx = t % L.tw;
        ty = t / L.tw;
        return true;
    }
};

}  // namespace exemplar::synth
