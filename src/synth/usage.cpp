#include "usage.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <span>
#include <utility>

#include "exemplar/core/check.hpp"
#include "exemplar/core/parallel.hpp"
#include "exemplar/core/rng.hpp"
#include "patchmatch.hpp"

namespace exemplar::synth {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
// Uniform usage: rounds of reversed retrieval before the remaining targets are assigned by a
// capacity-limited forward search (guarantees termination; see docs/algorithms.md).
constexpr int kUniformMaxReverseRounds = 64;

int search_iterations(const SearchSetup& setup) {
    return setup.warm ? setup.options.warm_search_iterations : setup.options.search_iterations;
}

struct Candidate {
    float error;
    int source;   // source pixel index
    int target;   // target pixel index
    float angle;  // target -> source rotation
};

// Low 32 bits of a candidate key: the source pixel index; high 32 bits: the error's float bits.
constexpr std::uint64_t kSourceMask = 0xffffffffu;
std::uint64_t candidate_key(float error, std::size_t index) {
    return (static_cast<std::uint64_t>(std::bit_cast<std::uint32_t>(error)) << 32) |
           static_cast<std::uint64_t>(index);
}
float key_error(std::uint64_t key) {
    return std::bit_cast<float>(static_cast<std::uint32_t>(key >> 32));
}

// Fixed pieces of the parallel passes over a round's arrays (the same pieces for any thread
// count).
constexpr int kChunk = 8192;

// The keys key_of(v) of the entries v of `slots` other than `none`, in order. Parallel over fixed
// chunks: each counts its entries, then writes their keys at its offset.
template <class KeyOf>
std::vector<std::uint64_t> compact(const std::vector<std::uint32_t>& slots, std::uint32_t none,
                                   KeyOf key_of, int threads) {
    const int chunks = static_cast<int>((slots.size() + kChunk - 1) / kChunk);
    std::vector<std::size_t> offset(static_cast<std::size_t>(chunks) + 1, 0);
    auto chunk_range = [&](int c) {
        const std::size_t b = static_cast<std::size_t>(c) * kChunk;
        return std::pair{b, std::min(slots.size(), b + kChunk)};
    };
    parallel_for(0, chunks, threads, [&](int c) {
        const auto [b, e] = chunk_range(c);
        offset[static_cast<std::size_t>(c) + 1] =
            static_cast<std::size_t>(std::count_if(slots.begin() + static_cast<std::ptrdiff_t>(b),
                                                   slots.begin() + static_cast<std::ptrdiff_t>(e),
                                                   [&](std::uint32_t v) { return v != none; }));
    });
    std::partial_sum(offset.begin(), offset.end(), offset.begin());
    std::vector<std::uint64_t> out(offset.back());
    parallel_for(0, chunks, threads, [&](int c) {
        const auto [b, e] = chunk_range(c);
        std::size_t o = offset[static_cast<std::size_t>(c)];
        for (std::size_t i = b; i < e; ++i) {
            if (slots[i] != none) out[o++] = key_of(slots[i]);
        }
    });
    return out;
}

// The unique keys of `v`, sorted ascending: halves sorted in parallel, then merged in pieces
// split where the output's are (merge path), each piece on its own thread. Unique keys have one
// sorted order, whatever the thread count.
std::vector<std::uint64_t> parallel_sort(std::vector<std::uint64_t> v, int threads) {
    constexpr std::size_t kPiece = 2048;  // of the merge
    if (threads == 1 || v.size() < 2 * kPiece) {
        std::sort(v.begin(), v.end());
        return v;
    }
    const auto a = std::span(v).first(v.size() / 2);
    const auto b = std::span(v).subspan(v.size() / 2);
    parallel_for(0, 2, threads, [&](int half) {
        const auto part = half == 0 ? a : b;
        std::sort(part.begin(), part.end());
    });
    std::vector<std::uint64_t> out(v.size());
    const int pieces = static_cast<int>((v.size() + kPiece - 1) / kPiece);
    // The number of a's entries among the output's first k: the i with a[i - 1] < b[k - i] and
    // b[k - i - 1] < a[i] (keys are unique).
    auto split = [&](std::size_t k) {
        std::size_t lo = k > b.size() ? k - b.size() : 0, hi = std::min(k, a.size());
        while (lo < hi) {
            const std::size_t i = (lo + hi) / 2;
            if (a[i] < b[k - i - 1]) {
                lo = i + 1;
            } else {
                hi = i;
            }
        }
        return lo;
    };
    parallel_for(0, pieces, threads, [&](int p) {
        const std::size_t k0 = static_cast<std::size_t>(p) * kPiece;
        const std::size_t k1 = std::min(v.size(), k0 + kPiece);
        const std::size_t i0 = split(k0), i1 = split(k1);
        std::merge(a.begin() + static_cast<std::ptrdiff_t>(i0),
                   a.begin() + static_cast<std::ptrdiff_t>(i1),
                   b.begin() + static_cast<std::ptrdiff_t>(k0 - i0),
                   b.begin() + static_cast<std::ptrdiff_t>(k1 - i1),
                   out.begin() + static_cast<std::ptrdiff_t>(k0));
    });
    return out;
}

// The forward problem of a search over the target pixels in `process`, from the sources in
// `allowed` (nullptr = any), with an optional per-source penalty; it tries the setup's
// candidate fields (ribbons) in every PatchMatch iteration.
ForwardProblem forward_problem(const SearchSetup& setup, const std::uint8_t* process,
                               const std::uint8_t* allowed, const float* penalty) {
    ForwardProblem problem{setup.level, process, allowed, penalty};
    problem.candidates = setup.candidates;
    return problem;
}

bool candidate_less(const Candidate& a, const Candidate& b) {
    if (a.error != b.error) return a.error < b.error;
    return a.source < b.source;
}

// Reversed-retrieval state shared by the uniform and error-budget strategies.
class ReverseRetrieval {
public:
    // `border_targets`: whether target patches over the border are assigned too (the error
    // budget, where that measured closer to the exemplar: stylit 0.0375 vs 0.0389, texbynum
    // 0.0759 vs 0.0772 over seeds 1-3), or left to search_border_targets (uniform usage, whose
    // K / K + 1 counts are over the patches inside both images).
    ReverseRetrieval(const SearchSetup& setup, Nnf& nnf, bool border_targets)
        : s_(setup),
          L_(setup.level),
          nnf_(nnf),
          reverse_(setup.reverse_field != nullptr ? *setup.reverse_field : own_reverse_) {
        const std::size_t n_t = static_cast<std::size_t>(L_.tw) * L_.th;
        free_.assign(n_t, 0);
        for (std::size_t t = 0; t < n_t; ++t) {
            if (L_.target_active[t] && (border_targets || L_.target_inside(t))) {
                free_[t] = 1;
                ++free_count_;
            }
        }
        active_count_ = free_count_;
        query_.assign(static_cast<std::size_t>(L_.sw) * L_.sh, 0);
        free_bits_ = pack_mask(free_);
        warm_ = reverse_.width() == L_.sw && reverse_.height() == L_.sh;
        if (!warm_) {
            reverse_ = Nnf(L_.sw, L_.sh);
            for (Match& m : reverse_.matches()) m = Match{-1, -1, 0.0f, kInf};
        }
        rebuild_free_lists();
    }

    ReverseRetrieval(const ReverseRetrieval&) = delete;
    ReverseRetrieval& operator=(const ReverseRetrieval&) = delete;
    ~ReverseRetrieval() {
        if (!first_round_.empty()) reverse_ = std::move(first_round_);
    }

    // After the last round: the run's last search (SearchSetup::last) releases the field.
    void end_rounds() {
        if (s_.last) reverse_ = Nnf();
    }

    std::size_t free_count() const { return free_count_; }
    const Nnf& nnf() const { return nnf_; }
    std::size_t active_count() const { return active_count_; }
    std::vector<std::uint8_t>& query_mask() { return query_; }
    // Sets the query mask to the valid sources inside the source (patches over its border are
    // for nearest-neighbour matches, not patches to distribute) whose label group still has free
    // targets and for which `wanted(s)` holds. Rows in parallel: `wanted` may only read shared
    // state.
    template <class Wanted>
    void select_queries(Wanted wanted) {
        parallel_for(0, L_.sh, s_.threads, [&](int y) {
            for (int x = 0; x < L_.sw; ++x) {
                const std::size_t s = L_.source_index(x, y);
                query_[s] = L_.source_valid[s] && L_.source_inside(s) &&
                            !free_by_group_[static_cast<std::size_t>(L_.source_group(s))].empty() &&
                            wanted(s);
            }
        });
    }
    const std::vector<std::uint8_t>& free_mask() const { return free_; }

    // One reversed retrieval over the sources in query_mask(); returns the keys (candidate_key)
    // of the collision-free candidates (one per target, the smallest error), sorted by error
    // (candidate() decodes one).
    std::vector<std::uint64_t> retrieve(int round) {
        // After the first round, matches whose target was taken resume at the nearest free one.
        if (round > 0) update_nearest_free();
        ReverseProblem problem{L_, query_.data(), free_bits_.data(), free_by_group_,
                               round > 0 ? nearest_free_.data() : nullptr};
        problem.uniform_draw = round == 0;
        const std::uint64_t key = hash_keys(s_.key, 0xBEEF, static_cast<std::uint64_t>(round));
        // Target features do not change between the rounds of one search, so after the first
        // round only entries whose target was taken need a new target.
        evaluate_field(problem, reverse_, key, s_.threads,
                       round > 0 ? FieldCosts::Invalid : FieldCosts::All);
        // The first round starts from the previous EM iteration's first-round field (warm), an
        // upsampled coarser level's field or random matches; later rounds from this search's.
        const bool warm = round > 0 || warm_;
        int iterations = warm ? s_.options.warm_search_iterations : s_.options.search_iterations;
        if (round == 0 && warm_ && s_.first_round_iterations > 0) {
            iterations = s_.first_round_iterations;
        }
        run_patchmatch(problem, reverse_, iterations, hash_keys(key, 1), s_.threads);
        // Later rounds pull the field toward the few targets still free; the next EM
        // iteration (all targets free again) starts better from this round's field.
        if (round == 0 && &reverse_ != &own_reverse_ && !s_.last) first_round_ = reverse_;
        return collision_free_candidates();
    }

    void assign(const Candidate& c) {
        take(c);
        --free_count_;
    }

    // Assigns the candidates of `keys` (from retrieve(): their targets and sources differ) and
    // marks their sources in `used`. In parallel: only the packed bits share memory (atomic).
    void assign_keys(std::span<const std::uint64_t> keys, std::vector<std::uint8_t>& used) {
        parallel_for_ranges(0, static_cast<int>(keys.size()), s_.threads, 4096, [&](int b, int e) {
            for (int i = b; i < e; ++i) {
                const Candidate c = candidate(keys[static_cast<std::size_t>(i)]);
                used[static_cast<std::size_t>(c.source)] = 1;
                take(c);
            }
        });
        free_count_ -= keys.size();
    }

    // Assigns the candidates of every row (distinct targets; a source may serve several) and
    // marks their sources in `used`. Rows in parallel; returns how many.
    std::size_t assign_rows(const std::vector<std::vector<Candidate>>& rows,
                            std::vector<std::uint8_t>& used) {
        parallel_for(0, static_cast<int>(rows.size()), s_.threads, [&](int y) {
            for (const Candidate& c : rows[static_cast<std::size_t>(y)]) {
                std::atomic_ref<std::uint8_t>(used[static_cast<std::size_t>(c.source)])
                    .store(1, std::memory_order_relaxed);
                take(c);
            }
        });
        std::size_t count = 0;
        for (const std::vector<Candidate>& row : rows) count += row.size();
        free_count_ -= count;
        return count;
    }

    // nearest_free_[t]: the free target pixel nearest to t (t itself if free; -1 if none).
    void update_nearest_free() {
        nearest_set_pixel(free_, L_.tw, L_.th, s_.threads, nearest_free_);
    }

    void rebuild_free_lists() {
        const std::size_t groups = L_.valid_by_group.size();
        free_by_group_.assign(groups, {});
        for (std::size_t t = 0; t < free_.size(); ++t) {
            if (free_[t]) {
                free_by_group_[static_cast<std::size_t>(L_.target_group(t))].push_back(
                    static_cast<int>(t));
            }
        }
    }

    // The candidate of a key that retrieve() returned.
    Candidate candidate(std::uint64_t key) const {
        const auto si = static_cast<std::size_t>(key & kSourceMask);
        const Match& m = reverse_[si];
        return Candidate{m.error, static_cast<int>(si), static_cast<int>(L_.target_index(m.x, m.y)),
                         -m.angle_rad};
    }

    // Per target, the querying source with the smallest error (ties: smaller source index), as
    // keys sorted by (error, source), candidate_less's order. Parallel and deterministic: a
    // candidate is one 64-bit key (error bits, source), errors are >= 0 so their bits order like
    // the values, and each target keeps the source of the minimum key (order-independent) in a
    // 32-bit slot (the slots are a round's largest array: guided2's peak of memory). Keys are
    // unique (a source has one match).
    std::vector<std::uint64_t> collision_free_candidates() const {
        constexpr std::uint32_t kNone = ~std::uint32_t{0};
        const auto key_of = [&](std::uint32_t si) { return candidate_key(reverse_[si].error, si); };
        std::vector<std::uint32_t> best(free_.size(), kNone);
        const int threads = s_.threads;
        parallel_for(0, L_.sh, threads, [&](int y) {
            for (int x = 0; x < L_.sw; ++x) {
                const std::size_t si = L_.source_index(x, y);
                if (!query_[si]) continue;
                const Match& m = reverse_[si];
                if (!(m.error < kInf)) continue;
                const std::uint64_t key = candidate_key(m.error, si);
                std::atomic_ref<std::uint32_t> slot(best[L_.target_index(m.x, m.y)]);
                std::uint32_t seen = slot.load(std::memory_order_relaxed);
                while ((seen == kNone || key < key_of(seen)) &&
                       !slot.compare_exchange_weak(seen, static_cast<std::uint32_t>(si),
                                                   std::memory_order_relaxed)) {
                }
            }
        });
        // The targets' keys, compacted, then sorted: keys and no decoded candidates (16 bytes
        // each), which were the largest arrays of a round (guided2's peak).
        std::vector<std::uint64_t> keys = compact(best, kNone, key_of, threads);
        std::vector<std::uint32_t>().swap(best);
        return parallel_sort(std::move(keys), threads);
    }

    // Forward search from the free targets to the sources in `allowed` (nullptr = any): their
    // entries of the field become the nearest neighbours found.
    void forward_search(const std::uint8_t* allowed, int pass) {
        ForwardProblem problem = forward_problem(s_, free_.data(), allowed, nullptr);
        std::vector<std::vector<int>> lists;
        if (allowed != nullptr) {
            lists.resize(L_.valid_by_group.size());
            for (std::size_t g = 0; g < lists.size(); ++g) {
                for (int s : L_.valid_by_group[g]) {
                    if (allowed[static_cast<std::size_t>(s)]) lists[g].push_back(s);
                }
            }
            problem.draw_lists = &lists;
        }
        const std::uint64_t key = hash_keys(s_.key, 0xF0F0, static_cast<std::uint64_t>(pass));
        evaluate_field(problem, nnf_, key, s_.threads);
        run_patchmatch(problem, nnf_, search_iterations(s_), hash_keys(key, 1), s_.threads);
    }

    // forward_search, then one candidate per free target, sorted by error.
    std::vector<Candidate> forward_candidates(const std::uint8_t* allowed, int pass) {
        forward_search(allowed, pass);
        std::vector<Candidate> out;
        for (std::size_t t = 0; t < free_.size(); ++t) {
            if (!free_[t]) continue;
            const Match& m = nnf_[t];
            if (!(m.error < kInf)) continue;
            out.push_back(Candidate{m.error, static_cast<int>(L_.source_index(m.x, m.y)),
                                    static_cast<int>(t), m.angle_rad});
        }
        std::sort(out.begin(), out.end(), candidate_less);
        return out;
    }

private:
    // Gives the candidate's target its source (the free count is the caller's).
    void take(const Candidate& c) {
        const auto t = static_cast<std::size_t>(c.target);
        EXEMPLAR_DCHECK(free_[t]);
        free_[t] = 0;
        std::atomic_ref<std::uint64_t>(free_bits_[t / 64])
            .fetch_and(~(std::uint64_t{1} << (t % 64)), std::memory_order_relaxed);
        nnf_[t] = Match{c.source % L_.sw, c.source / L_.sw, c.angle, c.error};
    }

    const SearchSetup& s_;
    const Level& L_;
    Nnf& nnf_;
    std::vector<std::uint8_t> free_;
    std::vector<std::uint64_t> free_bits_;  // free_, packed (pack_mask)
    std::vector<std::uint8_t> query_;
    std::vector<std::vector<int>> free_by_group_;
    std::vector<int> nearest_free_;
    std::size_t free_count_ = 0;
    std::size_t active_count_ = 0;
    Nnf own_reverse_;  // used when the caller keeps no field between iterations
    Nnf& reverse_;
    Nnf first_round_;  // the field after the first round, kept for the next EM iteration
    bool warm_ = false;
};

// Uniform usage leaves target patches over the border out, as source patches over the border
// are: neither is the image's own patch. They take nearest neighbours over every source (border
// patches included, so an identity keeps its border exact). Returns how many.
std::size_t search_border_targets(const SearchSetup& setup, Nnf& nnf) {
    const Level& L = setup.level;
    std::vector<std::uint8_t> border(L.target_active.size(), 0);
    std::size_t count = 0;
    for (std::size_t t = 0; t < border.size(); ++t) {
        border[t] = L.target_active[t] && !L.target_inside(t) ? 1 : 0;
        count += border[t];
    }
    if (count == 0) return 0;
    const ForwardProblem problem = forward_problem(setup, border.data(), nullptr, nullptr);
    evaluate_field(problem, nnf, hash_keys(setup.key, 0xB0), setup.threads);
    run_patchmatch(problem, nnf, search_iterations(setup), hash_keys(setup.key, 0xB1),
                   setup.threads);
    return count;
}

SearchStats search_forward(const SearchSetup& setup, Nnf& nnf) {
    const ForwardProblem problem =
        forward_problem(setup, setup.level.target_active.data(), nullptr, nullptr);
    // The same validity and costs as the engine's evaluation of the level's active pixels.
    if (!setup.evaluated) evaluate_field(problem, nnf, hash_keys(setup.key, 0xA), setup.threads);
    run_patchmatch(problem, nnf, search_iterations(setup), hash_keys(setup.key, 0xB),
                   setup.threads);
    SearchStats stats;
    stats.forward_assigned = static_cast<std::size_t>(
        std::count(setup.level.target_active.begin(), setup.level.target_active.end(), 1));
    return stats;
}

void merge_uniform_strays(const SearchSetup& setup, Nnf& nnf,
                          const std::vector<std::uint8_t>& uniform,
                          std::vector<std::uint32_t>& count, const std::vector<std::size_t>& K);

// LazyFluids §5.4.1: every source patch is used K = |X| / |Z| or K + 1 times (R = |X| mod |Z|
// of them K + 1), per label group. Z: the patches inside the source (Level::source_inside).
SearchStats search_uniform(const SearchSetup& setup, Nnf& nnf) {
    const Level& L = setup.level;
    ReverseRetrieval rr(setup, nnf, /*border_targets=*/false);
    const std::size_t groups = L.valid_by_group.size();
    std::vector<std::size_t> K(groups), R(groups);
    {
        std::vector<std::size_t> targets(groups, 0);
        for (std::size_t t = 0; t < rr.free_mask().size(); ++t) {
            if (rr.free_mask()[t]) ++targets[static_cast<std::size_t>(L.target_group(t))];
        }
        for (std::size_t g = 0; g < groups; ++g) {
            const auto& valid = L.valid_by_group[g];
            const auto sources =
                static_cast<std::size_t>(std::count_if(valid.begin(), valid.end(), [&](int s) {
                    return L.source_inside(static_cast<std::size_t>(s));
                }));
            K[g] = sources == 0 ? 0 : targets[g] / sources;
            R[g] = sources == 0 ? 0 : targets[g] % sources;
        }
    }
    std::vector<std::uint32_t> count(static_cast<std::size_t>(L.sw) * L.sh, 0);
    auto has_capacity = [&](std::size_t s) {
        const auto g = static_cast<std::size_t>(L.source_group(s));
        return L.source_inside(s) && (count[s] < K[g] || (count[s] == K[g] && R[g] > 0));
    };
    auto try_assign = [&](const Candidate& c) {
        const auto s = static_cast<std::size_t>(c.source);
        const auto g = static_cast<std::size_t>(L.source_group(s));
        if (count[s] < K[g]) {
            ++count[s];
        } else if (count[s] == K[g] && R[g] > 0) {
            ++count[s];
            --R[g];
        } else {
            return false;
        }
        rr.assign(c);
        return true;
    };

    const std::vector<std::uint8_t> uniform = rr.free_mask();  // the targets counted
    SearchStats stats;
    // Reversed retrieval rounds.
    while (rr.free_count() > 0 && stats.rounds < kUniformMaxReverseRounds) {
        rr.select_queries(has_capacity);  // counts and R are only read here
        const std::vector<std::uint64_t> keys = rr.retrieve(stats.rounds);
        ++stats.rounds;
        std::size_t assigned = 0;
        for (const std::uint64_t key : keys) assigned += try_assign(rr.candidate(key)) ? 1 : 0;
        stats.reverse_assigned += assigned;
        rr.rebuild_free_lists();
        // A round that assigns almost nothing means the reversed search is starving on a few
        // scattered free targets; the forward pass below finishes those efficiently.
        if (assigned == 0 || assigned * 200 < rr.free_count()) break;
    }
    rr.end_rounds();
    // Remaining targets: forward search restricted to sources with capacity left, assigned in
    // order of increasing error under the same K/R rules. Each pass assigns at least one target.
    std::vector<std::uint8_t> allowed(count.size(), 0);
    for (int pass = 0; rr.free_count() > 0; ++pass) {
        for (std::size_t s = 0; s < allowed.size(); ++s) {
            allowed[s] = L.source_valid[s] && has_capacity(s);
        }
        const std::vector<Candidate> candidates = rr.forward_candidates(allowed.data(), pass);
        std::size_t assigned = 0;
        for (const Candidate& c : candidates) {
            if (has_capacity(static_cast<std::size_t>(c.source))) {
                assigned += try_assign(c) ? 1 : 0;
            }
        }
        stats.forward_assigned += assigned;
        rr.rebuild_free_lists();
        // Capacity equals the number of targets, so a pass assigns at least its best candidate;
        // zero means no target could reach any source with capacity (e.g. a label group whose
        // sources all vanished). Those few keep unconstrained nearest neighbours.
        if (assigned == 0) {
            stats.forward_assigned += rr.free_count();
            rr.forward_search(nullptr, pass + 1);
            break;
        }
    }
    if (setup.options.uniform_coherence_sweeps > 0)
        merge_uniform_strays(setup, nnf, uniform, count, K);
    stats.forward_assigned += search_border_targets(setup, nnf);
    return stats;
}

// Of the sources no target uses yet, a late round queries one in this many, a subset that
// rotates from round to round (every such source queries every this many rounds). They are
// 47-80% of a late round's queries and win 11-25% of its targets (texbynum's finest level); the
// sources near a free target's match win the rest. With 4: 13-26% less CPU on the four examples,
// texture and patch fidelity within the seeds' spread (docs/performance-history.md).
constexpr int kUnusedQueryStride = 4;

// Late error-budget rounds: most sources' best free target is one that another source takes
// first, so searching from every source again is mostly wasted. A free target t is most likely
// won by a source close to its current (forward) match, or by a source no target uses yet (which
// keeps the usage diverse); `query` keeps those, the unused ones on the rotating subset of round
// `round` (kUnusedQueryStride).
void focus_query(const Level& L, const std::vector<std::uint8_t>& free, const Nnf& nnf,
                 const std::vector<std::uint8_t>& used, int round, std::vector<std::uint8_t>& query,
                 int threads) {
    // Rows in parallel: `near` is only ever set to 1 (relaxed stores, any order: the same mask).
    std::vector<std::uint8_t> near(query.size(), 0);
    parallel_for(0, L.th, threads, [&](int ty) {
        for (int tx = 0; tx < L.tw; ++tx) {
            const std::size_t t = L.target_index(tx, ty);
            if (!free[t]) continue;
            const Match& m = nnf[t];
            if (m.x < 0 || m.y < 0) continue;
            for (int y = std::max(0, m.y - 1); y <= std::min(L.sh - 1, m.y + 1); ++y) {
                for (int x = std::max(0, m.x - 1); x <= std::min(L.sw - 1, m.x + 1); ++x) {
                    std::atomic_ref<std::uint8_t>(near[L.source_index(x, y)])
                        .store(1, std::memory_order_relaxed);
                }
            }
        }
    });
    parallel_for(0, L.sh, threads, [&](int y) {
        for (int x = 0; x < L.sw; ++x) {
            const std::size_t s = L.source_index(x, y);
            // Diagonal lines (x + 3y + round) mod stride = 0: spread over the source, shifted
            // by one every round.
            const bool in_turn = (x + 3 * y + round) % kUnusedQueryStride == 0;
            query[s] = query[s] && (near[s] || (!used[s] && in_turn));
        }
    });
}

// A target pixel whose match continues the source region of fewer than this many of its four
// neighbours' matches is a stray (an isolated pick or a seam pixel) that merge_stray_matches may
// replace. 2 keeps region borders (a border pixel continues its own region's neighbours): with 1
// or 0 a region may grow over another one, e.g. a source shadow over the object beside it
// (measurements in docs/PERFORMANCE.md).
constexpr int kStrayBelowAgreeing = 2;

// Whether the active target (x + dx, y + dy) continues the source region of the match at (x, y)
// (its match is (x, y)'s shifted by the step, rotated with it).
bool continues(const Level& L, const Nnf& nnf, int x, int y, int dx, int dy) {
    const int nx = x + dx, ny = y + dy;
    if (nx < 0 || ny < 0 || nx >= L.tw || ny >= L.th) return false;
    const std::size_t n = L.target_index(nx, ny);
    if (!L.target_active[n]) return false;
    const Match& m = nnf[L.target_index(x, y)];
    const RotatedOffset o = rotated_step(m.angle_rad, dx, dy);
    return nnf[n].x == m.x + o.dx && nnf[n].y == m.y + o.dy;
}

// Whether the match at target (x, y) is a stray (see kStrayBelowAgreeing).
bool stray_match(const Level& L, const Nnf& nnf, int x, int y) {
    constexpr std::array<std::array<int, 2>, 4> kSteps{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};
    int agreeing = 0;
    for (const auto& [dx, dy] : kSteps) agreeing += continues(L, nnf, x, y, dx, dy) ? 1 : 0;
    return agreeing < kStrayBelowAgreeing;
}

// Marks in `stray` the active targets of pieces smaller than half a patch (a piece: the targets
// connected through neighbours that continue each other's source region). No output patch over
// such a piece is an exemplar patch, every one straddles its seams; merged into the pieces
// around it on the finest level, the mosaic has fewer seams (docs/PERFORMANCE.md, "Small pieces
// are strays"). Sequential (union-find over the scan order), so the same for any thread count;
// linear in the pixels.
void mark_small_pieces(const Level& L, const Nnf& nnf, std::vector<std::uint8_t>& stray) {
    const std::size_t n = L.target_active.size();
    std::vector<std::uint32_t> root(n);
    std::iota(root.begin(), root.end(), 0u);
    auto find = [&](std::uint32_t a) {
        while (root[a] != a) a = root[a] = root[root[a]];  // path halving
        return a;
    };
    for (int y = 0; y < L.th; ++y) {
        for (int x = 0; x < L.tw; ++x) {
            const auto t = static_cast<std::uint32_t>(L.target_index(x, y));
            if (!L.target_active[t]) continue;
            for (const auto& [dx, dy] : {std::array{1, 0}, std::array{0, 1}}) {
                if (!continues(L, nnf, x, y, dx, dy)) continue;
                const std::uint32_t a = find(t);
                const std::uint32_t b =
                    find(static_cast<std::uint32_t>(L.target_index(x + dx, y + dy)));
                if (a != b) root[std::max(a, b)] = std::min(a, b);
            }
        }
    }
    std::vector<std::uint32_t> size(n, 0);
    for (std::size_t t = 0; t < n; ++t) size[find(static_cast<std::uint32_t>(t))] += 1;
    const auto small = static_cast<std::uint32_t>((L.patch_size * L.patch_size + 1) / 2);
    for (std::size_t t = 0; t < n; ++t) {
        if (L.target_active[t] && size[find(static_cast<std::uint32_t>(t))] < small) stray[t] = 1;
    }
}

// The error budget assigns targets one by one, so neighbours often take unrelated sources and
// the result is a mosaic of small pieces whose seams no exemplar patch contains. Propagation-only
// sweeps let each stray match (kStrayBelowAgreeing, or on the finest level in a piece smaller
// than half a patch) take a neighbour's shifted match where that is closer, merging the strays into
// the regions around them (options.coherence_sweeps iterations; the strays are chosen once, before
// the sweeps). Matches inside larger coherent regions stay, so usage stays controlled.
void merge_stray_matches(const SearchSetup& setup, Nnf& nnf) {
    const Level& L = setup.level;
    std::vector<std::uint8_t> stray(L.target_active.size(), 0);
    parallel_for(0, L.th, setup.threads, [&](int y) {
        for (int x = 0; x < L.tw; ++x) {
            const std::size_t t = L.target_index(x, y);
            stray[t] = L.target_active[t] && stray_match(L, nnf, x, y);
        }
    });
    if (setup.finest) mark_small_pieces(L, nnf, stray);
    ForwardProblem problem = forward_problem(setup, stray.data(), nullptr, nullptr);
    problem.matched = L.target_active.data();
    run_patchmatch(problem, nnf, setup.options.coherence_sweeps, hash_keys(setup.key, 0xC0),
                   setup.threads, Exploration::PropagationOnly);
}

// Mean cost of the active, matched entries of `nnf` (the stored errors): rows summed apart in
// doubles, then added in row order, so the same for any thread count.
double mean_match_error(const Level& L, const Nnf& nnf, int threads) {
    std::vector<double> sums(static_cast<std::size_t>(L.th), 0.0);
    std::vector<std::size_t> counts(static_cast<std::size_t>(L.th), 0);
    parallel_for(0, L.th, threads, [&](int y) {
        for (int x = 0; x < L.tw; ++x) {
            const std::size_t t = L.target_index(x, y);
            if (!L.target_active[t] || !(nnf[t].error < kInf)) continue;
            sums[static_cast<std::size_t>(y)] += nnf[t].error;
            ++counts[static_cast<std::size_t>(y)];
        }
    });
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t y = 0; y < sums.size(); ++y) {
        sum += sums[y];
        count += counts[y];
    }
    return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

}  // namespace

// The largest window grow_pieces takes: the largest patch's (31 x 31), less its centre.
constexpr std::size_t kMaxPieceWindow = 31 * 31 - 1;

std::size_t grow_pieces(const Level& L, Nnf& nnf, int sweeps, float weight, int radius,
                        int threads) {
    const float lambda = static_cast<float>(weight * mean_match_error(L, nnf, threads));
    if (!(lambda > 0.0f) || sweeps <= 0) return 0;
    const ForwardProblem problem{L, L.target_active.data()};
    std::vector<std::array<int, 2>> window;
    for (int dy = -radius; dy <= radius; ++dy) {
        for (int dx = -radius; dx <= radius; ++dx) {
            if (dx != 0 || dy != 0) window.push_back({dx, dy});
        }
    }
    struct Proposal {
        int x, y;   // a neighbour's match shifted back to this target
        int votes;  // how many neighbours of the window propose it
    };
    // Unturned levels: a neighbour proposes its match shifted back, which continues the target's
    // own match when the two have the same offset (match - position), so the window is read as
    // packed offsets (kNoOffset: inactive) and most targets, inside pieces, are passed over by
    // counting equal offsets.
    constexpr std::int64_t kNoOffset = std::numeric_limits<std::int64_t>::min();
    const bool turned = L.rotated();
    auto pack = [](int dx, int dy) {
        return static_cast<std::int64_t>(static_cast<std::uint64_t>(static_cast<std::uint32_t>(dy))
                                             << 32 |
                                         static_cast<std::uint32_t>(dx));
    };
    std::vector<std::int64_t> offset(turned ? 0 : L.target_active.size(), kNoOffset);
    auto set_offset = [&](int x, int y) {
        const std::size_t t = L.target_index(x, y);
        if (L.target_active[t]) offset[t] = pack(nnf[t].x - x, nnf[t].y - y);
    };
    if (!turned) {
        parallel_for(0, L.th, threads, [&](int y) {
            for (int x = 0; x < L.tw; ++x) set_offset(x, y);
        });
    }
    std::vector<std::size_t> changed(static_cast<std::size_t>(L.th), 0);
    // Targets of one phase are more than `radius` apart: none reads another's match.
    const int period = radius + 1;
    const int phases = period * period;
    for (int step = 0; step < sweeps * phases; ++step) {
        const int phase = step % phases;
        const int px = phase % period, py = phase / period;
        const int rows = (L.th - py + period - 1) / period;
        parallel_for(0, rows, threads, [&](int row) {
            const int y = py + row * period;
            const int y0 = std::max(0, y - radius), y1 = std::min(L.th - 1, y + radius);
            std::array<Proposal, kMaxPieceWindow> proposed;
            std::array<std::int64_t, kMaxPieceWindow> distinct;
            for (int x = px; x < L.tw; x += period) {
                const std::size_t t = L.target_index(x, y);
                if (!L.target_active[t]) continue;
                const Match own = nnf[t];
                // Each active neighbour proposes its match shifted back by the step between
                // them; a neighbour continues a candidate when it proposes it.
                int neighbours = 0, own_votes = 0, count = 0;
                auto propose = [&](int cx, int cy) {
                    if (cx < 0 || cy < 0 || cx >= L.sw || cy >= L.sh) return;
                    int k = 0;
                    while (k < count && (proposed[static_cast<std::size_t>(k)].x != cx ||
                                         proposed[static_cast<std::size_t>(k)].y != cy)) {
                        ++k;
                    }
                    if (k == count) proposed[static_cast<std::size_t>(count++)] = {cx, cy, 0};
                    ++proposed[static_cast<std::size_t>(k)].votes;
                };
                if (!turned) {
                    const int x0 = std::max(0, x - radius), x1 = std::min(L.tw - 1, x + radius);
                    const std::int64_t mine = offset[t];
                    for (int ny = y0; ny <= y1; ++ny) {
                        const std::int64_t* o = &offset[L.target_index(0, ny)];
                        for (int nx = x0; nx <= x1; ++nx) {
                            neighbours += o[nx] != kNoOffset ? 1 : 0;
                            own_votes += o[nx] == mine ? 1 : 0;
                        }
                    }
                    --neighbours;  // the target itself
                    --own_votes;
                    if (own_votes == neighbours) continue;
                    // Distinct offsets and their votes (runs of one offset along a row are
                    // common: counted without a search).
                    neighbours = own_votes = 0;
                    std::int64_t last = kNoOffset;
                    int last_k = 0;
                    for (int ny = y0; ny <= y1; ++ny) {
                        const std::int64_t* o = &offset[L.target_index(0, ny)];
                        for (int nx = x0; nx <= x1; ++nx) {
                            const std::int64_t v = o[nx];
                            if (v == kNoOffset || (nx == x && ny == y)) continue;
                            ++neighbours;
                            if (v == mine) {
                                ++own_votes;
                                continue;
                            }
                            if (v != last) {
                                int k = 0;
                                while (k < count && distinct[static_cast<std::size_t>(k)] != v) ++k;
                                if (k == count) {
                                    distinct[static_cast<std::size_t>(count)] = v;
                                    const Match& m = nnf[L.target_index(nx, ny)];
                                    proposed[static_cast<std::size_t>(count++)] = {m.x - nx + x,
                                                                                   m.y - ny + y, 0};
                                }
                                last = v;
                                last_k = k;
                            }
                            ++proposed[static_cast<std::size_t>(last_k)].votes;
                        }
                    }
                    // Proposals outside the source are no candidates (their votes still count
                    // the neighbours that disagree with the own match).
                    int kept = 0;
                    for (int k = 0; k < count; ++k) {
                        const Proposal& c = proposed[static_cast<std::size_t>(k)];
                        if (c.x >= 0 && c.y >= 0 && c.x < L.sw && c.y < L.sh) {
                            proposed[static_cast<std::size_t>(kept++)] = c;
                        }
                    }
                    count = kept;
                } else {
                    for (const auto& [dx, dy] : window) {
                        const int nx = x + dx, ny = y + dy;
                        if (nx < 0 || ny < 0 || nx >= L.tw || ny >= L.th) continue;
                        const std::size_t n = L.target_index(nx, ny);
                        if (!L.target_active[n]) continue;
                        ++neighbours;
                        const Match& m = nnf[n];
                        const RotatedOffset o = rotated_step(m.angle_rad, -dx, -dy);
                        const int cx = m.x + o.dx, cy = m.y + o.dy;
                        if (cx == own.x && cy == own.y) {
                            ++own_votes;
                        } else {
                            propose(cx, cy);
                        }
                    }
                }
                if (own_votes == neighbours) continue;
                Match best = own;
                float best_total = own.error + lambda * static_cast<float>(neighbours - own_votes);
                for (int k = 0; k < count; ++k) {
                    const Proposal& c = proposed[static_cast<std::size_t>(k)];
                    const float smooth = lambda * static_cast<float>(neighbours - c.votes);
                    const float bound = best_total - smooth;
                    if (!(bound > 0.0f) || !problem.db_ok(t, c.x, c.y)) continue;
                    const float angle = problem.angle(t, c.x, c.y);
                    const float d = problem.cost(x, y, c.x, c.y, angle, bound);
                    if (d < bound) {
                        best = Match{c.x, c.y, angle, d};
                        best_total = d + smooth;
                    }
                }
                if (best.x != own.x || best.y != own.y) {
                    nnf[t] = best;
                    if (!turned) set_offset(x, y);
                    ++changed[static_cast<std::size_t>(y)];
                }
            }
        });
    }
    return std::accumulate(changed.begin(), changed.end(), std::size_t{0});
}

namespace {

// A stray target examines at most this many other stray users of a source for a swap (with a
// large K a source has dozens of users; the first strays in scan order are as good as any).
constexpr int kSwapUsersExamined = 2;

// Uniform usage's counterpart of merge_stray_matches. The assignment places the exemplar's
// patches one by one, so many targets end up as strays between unrelated pieces, and the vote
// averages those flat (LazyFluids on a photo: docs/fluid.md, "Wash-out"). In each sweep every
// stray target t (source s) proposes, from its neighbours' shifted sources c, the best of
//   - a move to c, if K > 0, s is used K + 1 times and c K times (every count stays K or K + 1
//     and as many sources as before are used K + 1 times), when D(t, c) < D(t, s). Not for
//     K = 0 (an exemplar segment larger than the target's): that move would take s out of use,
//     and the moves grew the pieces the assignment had picked, the exemplar's smoothest (the ink
//     photo of examples/fluid on its 256x256 plume kept 0.69 of its gradient energy with moves
//     for K = 0, 0.79 without, 0.78 without the sweeps);
//   - a swap with a stray target t' that uses c (t' takes s; no count changes), when
//     D(t, c) + D(t', s) < D(t, s) + D(t', c).
// Sequential in scan order, so that a piece grows along the scan within one sweep (proposals
// found in parallel from each sweep's starting field grew less: 0.33 instead of 0.47 of
// neighbouring targets continuing each other after 2 sweeps); the same result for any thread
// count. `uniform` marks the targets the counts are over.
void merge_uniform_strays(const SearchSetup& setup, Nnf& nnf,
                          const std::vector<std::uint8_t>& uniform,
                          std::vector<std::uint32_t>& count, const std::vector<std::size_t>& K) {
    constexpr std::array<std::array<int, 2>, 4> kSteps{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};
    constexpr int kNone = -1, kMove = -2;
    struct Proposal {
        int partner = kNone;  // kNone, kMove, or the target t' of a swap
        Match match;          // t's new match
    };
    const Level& L = setup.level;
    std::vector<std::vector<int>> users(count.size());
    for (std::size_t t = 0; t < uniform.size(); ++t) {
        if (uniform[t]) users[L.source_index(nnf[t].x, nnf[t].y)].push_back(static_cast<int>(t));
    }
    auto distance = [&](std::size_t t, int sx, int sy, float angle, float bound) {
        return patch_distance(L, static_cast<int>(t % static_cast<std::size_t>(L.tw)),
                              static_cast<int>(t / static_cast<std::size_t>(L.tw)), sx, sy, angle,
                              bound);
    };
    constexpr float kInfinity = std::numeric_limits<float>::infinity();
    auto propose = [&](int x, int y) {
        Proposal best;
        const std::size_t t = L.target_index(x, y);
        const Match& m = nnf[t];
        const std::size_t s = L.source_index(m.x, m.y);
        const std::size_t g = static_cast<std::size_t>(L.source_group(s));
        const float d_ts = m.error;  // the searches store exact distances
        float best_gain = 0.0f;
        for (const auto& [dx, dy] : kSteps) {
            const int nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= L.tw || ny >= L.th) continue;
            const std::size_t n = L.target_index(nx, ny);
            if (!uniform[n]) continue;
            const RotatedOffset o = rotated_step(nnf[n].angle_rad, -dx, -dy);
            const int cx = nnf[n].x + o.dx, cy = nnf[n].y + o.dy;
            if (cx < 0 || cy < 0 || cx >= L.sw || cy >= L.sh) continue;
            const std::size_t c = L.source_index(cx, cy);
            if (c == s || !L.source_inside(c) || !L.compatible(t, cx, cy)) continue;
            const float angle = L.angle_for(t, cx, cy);
            const float d_tc = distance(t, cx, cy, angle, kInfinity);
            if (K[g] > 0 && count[s] == K[g] + 1 && count[c] == K[g] && d_ts - d_tc > best_gain) {
                best_gain = d_ts - d_tc;
                best = Proposal{kMove, Match{cx, cy, angle, d_tc}};
            }
            int examined = 0;
            for (int u : users[c]) {
                if (examined == kSwapUsersExamined) break;
                const auto tu = static_cast<std::size_t>(u);
                if (!stray_match(L, nnf, u % L.tw, u / L.tw) || !L.compatible(tu, m.x, m.y)) {
                    continue;
                }
                ++examined;
                const float d_uc = nnf[tu].error;
                const float room = d_ts + d_uc - d_tc - best_gain;  // D(t', s) must stay below
                if (!(room > 0.0f)) continue;
                const float d_us = distance(tu, m.x, m.y, L.angle_for(tu, m.x, m.y), room);
                if (d_us < room) {
                    best_gain = d_ts + d_uc - d_tc - d_us;
                    best = Proposal{u, Match{cx, cy, angle, d_tc}};
                }
            }
        }
        return best;
    };
    for (int sweep = 0; sweep < setup.options.uniform_coherence_sweeps; ++sweep) {
        std::size_t applied = 0;
        for (int y = 0; y < L.th; ++y) {
            for (int x = 0; x < L.tw; ++x) {
                const std::size_t t = L.target_index(x, y);
                if (!uniform[t] || !stray_match(L, nnf, x, y)) continue;
                const Proposal p = propose(x, y);
                if (p.partner == kNone) continue;
                const Match m = nnf[t];
                const std::size_t s = L.source_index(m.x, m.y);
                const std::size_t c = L.source_index(p.match.x, p.match.y);
                if (p.partner == kMove) {
                    --count[s];
                    ++count[c];
                } else {
                    const auto tu = static_cast<std::size_t>(p.partner);
                    const float angle = L.angle_for(tu, m.x, m.y);
                    nnf[tu] = Match{m.x, m.y, angle, distance(tu, m.x, m.y, angle, kInfinity)};
                    auto& list = users[c];
                    list.erase(std::find(list.begin(), list.end(), p.partner));
                    users[s].push_back(p.partner);
                }
                auto& list = users[s];
                list.erase(std::find(list.begin(), list.end(), static_cast<int>(t)));
                users[c].push_back(static_cast<int>(t));
                nnf[t] = p.match;
                ++applied;
            }
        }
        if (applied == 0) break;
    }
}

// On the finest level, a free target next to targets the budget just assigned takes the best of
// their matches shifted by one step (continuing their exemplar piece) if its error is at most this
// fraction of the round's largest assigned error. With half, at `default`: 11-19% less CPU on
// facestyle, texbynum and guided2 (fewer and smaller late rounds), 3% on stylit; facestyle keeps
// 2% more texture, patch fidelity within 3%. With the round's largest error as the bound the
// mean patch error rose 5-9%. On the coarse levels too it let a region grow over another
// (RenderStylit's cow 0.898 -> 0.869 blue). docs/performance-history.md, "Late budget rounds".
constexpr float kGrowErrorFraction = 0.5f;

// After a round of the error budget on the finest level: every free target next to an assigned
// one proposes the best shifted match of its assigned 4-neighbours within `bound`
// (kGrowErrorFraction); the proposals, found in parallel from the state before any is applied, are
// all assigned. A piece the round laid grows by one pixel where the exemplar continues it closely
// enough, which the reversed retrieval would otherwise find only rounds later, from a source placed
// anywhere. Returns how many targets it assigned.
std::size_t grow_assigned(const SearchSetup& setup, ReverseRetrieval& rr, const Nnf& nnf,
                          float bound, std::vector<std::uint8_t>& used) {
    constexpr std::array<std::array<int, 2>, 4> kSteps{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};
    const Level& L = setup.level;
    const std::vector<std::uint8_t>& free = rr.free_mask();
    // Each row's proposals apart, then assigned row by row in parallel: the memory follows the
    // proposals (a whole-level table of candidates beside the round's own raised guided2's peak
    // by 2.5 MB).
    std::vector<std::vector<Candidate>> proposals(static_cast<std::size_t>(L.th));
    parallel_for(0, L.th, setup.threads, [&](int y) {
        std::vector<Candidate>& row = proposals[static_cast<std::size_t>(y)];
        for (int x = 0; x < L.tw; ++x) {
            const std::size_t t = L.target_index(x, y);
            if (!free[t]) continue;
            Candidate best{kInf, -1, -1, 0.0f};
            for (const auto& [dx, dy] : kSteps) {
                const int nx = x + dx, ny = y + dy;
                if (nx < 0 || ny < 0 || nx >= L.tw || ny >= L.th) continue;
                const std::size_t n = L.target_index(nx, ny);
                if (free[n] || !L.target_active[n]) continue;
                const Match& m = nnf[n];
                const RotatedOffset o = rotated_step(m.angle_rad, -dx, -dy);
                const int cx = m.x + o.dx, cy = m.y + o.dy;
                if (cx < 0 || cy < 0 || cx >= L.sw || cy >= L.sh) continue;
                const std::size_t c = L.source_index(cx, cy);
                if (!L.source_valid[c] || !L.compatible(t, cx, cy)) continue;
                const float angle = L.angle_for(t, cx, cy);
                const float d = patch_distance(L, x, y, cx, cy, angle, std::min(best.error, bound));
                if (d < best.error && d <= bound) {
                    best = Candidate{d, static_cast<int>(c), static_cast<int>(t), angle};
                }
            }
            if (best.source >= 0) row.push_back(best);
        }
    });
    return rr.assign_rows(proposals, used);
}

// StyLit §8.3.3: repeated reversed retrieval; each round assigns the collision-free candidates
// whose summed error stays within the budget T estimated at the knee of the sorted errors; once
// `budget_coverage` of the targets are covered the rest take forward nearest neighbours.
SearchStats search_error_budget(const SearchSetup& setup, Nnf& nnf) {
    const Level& L = setup.level;
    ReverseRetrieval rr(setup, nnf, /*border_targets=*/true);
    SearchStats stats;
    const auto target_total = static_cast<double>(rr.active_count());
    std::vector<std::uint8_t> used(static_cast<std::size_t>(L.sw) * L.sh, 0);
    while (rr.free_count() > 0 && stats.rounds < setup.options.budget_max_rounds) {
        const double covered = 1.0 - static_cast<double>(rr.free_count()) / target_total;
        if (covered >= setup.options.budget_coverage) break;
        rr.select_queries([](std::size_t) { return true; });
        if (stats.rounds > 0 &&
            static_cast<double>(rr.free_count()) < setup.options.budget_focus * target_total) {
            focus_query(L, rr.free_mask(), rr.nnf(), used, stats.rounds, rr.query_mask(),
                        setup.threads);
        }
        const std::vector<std::uint64_t> keys = rr.retrieve(stats.rounds);
        ++stats.rounds;
        if (keys.empty()) break;
        std::vector<float> errors(keys.size());
        std::transform(keys.begin(), keys.end(), errors.begin(), key_error);
        const KneeFit fit = fit_knee(errors);
        double budget = 0.0;
        for (std::size_t i = 0; i < fit.knee_index; ++i) budget += errors[i];
        double spent = 0.0;
        std::size_t assigned = 0;
        for (const float error : errors) {
            // Always take the best candidate so that every round makes progress.
            if (assigned > 0 && spent + error > budget) break;
            spent += error;
            ++assigned;
        }
        rr.assign_keys(std::span(keys).first(assigned), used);
        stats.reverse_assigned += assigned;
        if (setup.finest) {
            stats.reverse_assigned +=
                grow_assigned(setup, rr, nnf, kGrowErrorFraction * errors[assigned - 1], used);
        }
        rr.rebuild_free_lists();
    }
    rr.end_rounds();
    if (rr.free_count() > 0) {
        stats.forward_assigned = rr.free_count();
        rr.forward_search(nullptr, 0);
    }
    if (setup.options.coherence_sweeps > 0) merge_stray_matches(setup, nnf);
    return stats;
}

// Forward search whose cost adds h_s * max(0, H(p) - h_tau), H the (blurred) usage histogram of
// the current NNF, recomputed before every PatchMatch iteration.
SearchStats search_occurrence(const SearchSetup& setup, Nnf& nnf) {
    const Level& L = setup.level;
    const auto active =
        static_cast<double>(std::count(L.target_active.begin(), L.target_active.end(), 1));
    std::size_t sources = 0;
    for (const auto& g : L.valid_by_group) sources += g.size();
    const double threshold = setup.options.occurrence_threshold > 0.0f
                                 ? setup.options.occurrence_threshold
                                 : std::max(1.0, 2.0 * active / std::max<double>(1, sources));
    std::vector<float> penalty(static_cast<std::size_t>(L.sw) * L.sh, 0.0f);
    for (int iter = 0; iter < search_iterations(setup); ++iter) {
        const std::vector<float> usage = usage_counts(L, nnf);
        // Small 3x3 binomial blur of the histogram (Bénard: "a small Gaussian kernel").
        for (int y = 0; y < L.sh; ++y) {
            for (int x = 0; x < L.sw; ++x) {
                double h = 0.0, wsum = 0.0;
                for (int dy = -1; dy <= 1; ++dy) {
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int xx = x + dx, yy = y + dy;
                        if (xx < 0 || yy < 0 || xx >= L.sw || yy >= L.sh) continue;
                        const double w = (dx == 0 ? 2.0 : 1.0) * (dy == 0 ? 2.0 : 1.0);
                        h += w * usage[L.source_index(xx, yy)];
                        wsum += w;
                    }
                }
                penalty[L.source_index(x, y)] = static_cast<float>(
                    setup.options.occurrence_strength * std::max(0.0, h / wsum - threshold));
            }
        }
        const ForwardProblem problem =
            forward_problem(setup, L.target_active.data(), nullptr, penalty.data());
        const std::uint64_t key = hash_keys(setup.key, 0xC, static_cast<std::uint64_t>(iter));
        evaluate_field(problem, nnf, key, setup.threads);
        run_patchmatch(problem, nnf, 1, hash_keys(key, 1), setup.threads);
    }
    SearchStats stats;
    stats.forward_assigned = static_cast<std::size_t>(active);
    return stats;
}

}  // namespace

KneeFit fit_knee(std::span<const float> sorted_errors) {
    KneeFit fit;
    const std::size_t n = sorted_errors.size();
    fit.knee_index = n;
    if (n < 3) return fit;
    const double max_error = sorted_errors[n - 1];
    if (!(max_error > 0.0)) return fit;
    // Weighted linear least squares on 1/y = a - b x. Weights y^4 make the residuals comparable
    // to residuals in y (d(1/y) = -dy / y^2), so tiny errors near zero do not dominate the fit.
    double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double y = sorted_errors[i] / max_error;
        if (!(y > 1e-6)) continue;
        const double x = static_cast<double>(i) / static_cast<double>(n - 1);
        const double w = y * y * y * y;
        const double v = 1.0 / y;
        sw += w;
        sx += w * x;
        sy += w * v;
        sxx += w * x * x;
        sxy += w * x * v;
    }
    const double det = sw * sxx - sx * sx;
    if (!(std::abs(det) > 1e-18)) return fit;
    const double slope = (sw * sxy - sx * sy) / det;  // = -b
    fit.b = -slope;
    fit.a = (sy - slope * sx) / sw;
    if (!(fit.b > 0.0)) return fit;  // not increasing: no knee, everything is feasible
    // f'(x) = b / (a - b x)^2 = 1  =>  x = (a - sqrt(b)) / b, the root before the pole at a/b.
    fit.knee_x = std::clamp((fit.a - std::sqrt(fit.b)) / fit.b, 0.0, 1.0);
    fit.knee_index =
        std::min(n, static_cast<std::size_t>(std::ceil(fit.knee_x * static_cast<double>(n - 1))));
    return fit;
}

// The separable exact transform of Felzenszwalb and Huttenlocher (2012): the nearest set pixel of
// every column, then per row the lower envelope of the parabolas (x - x')^2 + dy(x')^2. Both
// passes are parallel over fixed pieces, so the result does not depend on the thread count.
void nearest_set_pixel(const std::vector<std::uint8_t>& set, int w, int h, int threads,
                       std::vector<int>& nearest) {
    EXEMPLAR_CHECK_EQ(set.size(), static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    auto index = [w](int x, int y) {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
               static_cast<std::size_t>(x);
    };
    // Pass 1: per pixel, the row of the nearest set pixel in its column (-1: none). Every entry
    // is written, so the buffer needs no filling first.
    std::vector<int> column_row(set.size());
    constexpr int kChunk = 64;
    parallel_for(0, (w + kChunk - 1) / kChunk, threads, [&](int chunk) {
        const int x0 = chunk * kChunk, x1 = std::min(w, x0 + kChunk);
        std::array<int, kChunk> last;
        last.fill(-1);
        for (int y = 0; y < h; ++y) {
            for (int x = x0; x < x1; ++x) {
                const std::size_t t = index(x, y);
                if (set[t]) last[static_cast<std::size_t>(x - x0)] = y;
                column_row[t] = last[static_cast<std::size_t>(x - x0)];
            }
        }
        last.fill(-1);
        for (int y = h - 1; y >= 0; --y) {
            for (int x = x0; x < x1; ++x) {
                const std::size_t t = index(x, y);
                int& below = last[static_cast<std::size_t>(x - x0)];
                if (set[t]) below = y;
                int& row = column_row[t];
                if (below >= 0 && (row < 0 || below - y < y - row)) row = below;
            }
        }
    });
    // Pass 2: per row, the lower envelope of the columns' parabolas (each row writes all of its
    // entries). The envelope's arrays and each column's parabola at x = 0 serve a whole range
    // of rows.
    nearest.resize(set.size());
    parallel_for_ranges(0, h, threads, 1, [&](int y_begin, int y_end) {
        std::vector<int> v(static_cast<std::size_t>(w));         // envelope's columns
        std::vector<double> z(static_cast<std::size_t>(w) + 1);  // their left borders
        std::vector<double> g(static_cast<std::size_t>(w));      // dy² + x² per column
        for (int y = y_begin; y < y_end; ++y) {
            const int* rows = column_row.data() + index(0, y);
            int* out = nearest.data() + index(0, y);
            int k = -1;
            for (int q = 0; q < w; ++q) {
                if (rows[q] < 0) continue;
                const double dy = y - rows[q];
                const double gq = dy * dy + static_cast<double>(q) * q;
                g[static_cast<std::size_t>(q)] = gq;
                double border = -std::numeric_limits<double>::infinity();
                while (k >= 0) {
                    const int p = v[static_cast<std::size_t>(k)];
                    border = (gq - g[static_cast<std::size_t>(p)]) / (2.0 * (q - p));
                    if (border > z[static_cast<std::size_t>(k)]) break;
                    --k;
                    border = -std::numeric_limits<double>::infinity();
                }
                ++k;
                v[static_cast<std::size_t>(k)] = q;
                z[static_cast<std::size_t>(k)] = border;
            }
            if (k < 0) {
                std::fill_n(out, w, -1);
                continue;
            }
            const int count = k + 1;
            z[static_cast<std::size_t>(count)] = std::numeric_limits<double>::infinity();
            k = 0;
            for (int x = 0; x < w; ++x) {
                while (z[static_cast<std::size_t>(k) + 1] < x) ++k;
                const int column = v[static_cast<std::size_t>(k)];
                out[x] = static_cast<int>(index(column, rows[column]));
            }
        }
    });
}

std::vector<int> nearest_set_pixel(const std::vector<std::uint8_t>& set, int w, int h,
                                   int threads) {
    std::vector<int> nearest;
    nearest_set_pixel(set, w, h, threads, nearest);
    return nearest;
}

std::vector<float> usage_counts(const Level& level, const Nnf& nnf) {
    std::vector<float> usage(static_cast<std::size_t>(level.sw) * level.sh, 0.0f);
    for (std::size_t t = 0; t < nnf.pixel_count(); ++t) {
        if (!level.target_active[t]) continue;
        const Match& m = nnf[t];
        usage[level.source_index(m.x, m.y)] += 1.0f;
    }
    return usage;
}

SearchStats search(const SearchSetup& setup, Nnf& nnf) {
    switch (setup.options.usage) {
        case UsageStrategy::None: return search_forward(setup, nnf);
        case UsageStrategy::Uniform: return search_uniform(setup, nnf);
        case UsageStrategy::ErrorBudget: return search_error_budget(setup, nnf);
        case UsageStrategy::OccurrencePenalty: return search_occurrence(setup, nnf);
    }
    return {};
}

}  // namespace exemplar::synth
