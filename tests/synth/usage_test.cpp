#include "usage.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "level_builder.hpp"
#include "patchmatch.hpp"
#include "test_images.hpp"

namespace exemplar::synth {
namespace {

// Normalized hyperbola with a known knee: y = 1 / (a - b x), a - b = 1 so y(1) = 1; the knee
// (f' = 1) is at x = (a - sqrt(b)) / b.
std::vector<float> hyperbola(int n, double a, double b, double scale) {
    std::vector<float> v(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        const double x = static_cast<double>(i) / (n - 1);
        v[static_cast<std::size_t>(i)] = static_cast<float>(scale / (a - b * x));
    }
    return v;
}

TEST(KneeFit, FindsKnownKnee) {
    for (double b : {2.0, 4.0, 9.0, 20.0}) {
        const double a = 1.0 + b;
        const double knee = (a - std::sqrt(b)) / b;
        for (double scale : {1.0, 0.003, 250.0}) {  // errors come in any unit
            const KneeFit fit = fit_knee(hyperbola(2000, a, b, scale));
            EXPECT_NEAR(fit.a, a, 1e-3 * a) << "b=" << b;
            EXPECT_NEAR(fit.b, b, 1e-3 * b);
            EXPECT_NEAR(fit.knee_x, knee, 1e-3) << "b=" << b << " scale=" << scale;
            EXPECT_NEAR(static_cast<double>(fit.knee_index) / 1999.0, knee, 2e-3);
        }
    }
}

TEST(KneeFit, NoisyCurveStillCloseAndFlatCurveHasNoKnee) {
    std::vector<float> v = hyperbola(5000, 5.0, 4.0, 1.0);
    KeyedRng rng(3, 0);
    for (float& e : v) e *= 1.0f + 0.05f * (rng.uniform() - 0.5f);
    std::sort(v.begin(), v.end());
    EXPECT_NEAR(fit_knee(v).knee_x, 0.75, 0.03);

    const std::vector<float> flat(100, 0.5f);
    const KneeFit f = fit_knee(flat);
    EXPECT_EQ(f.knee_index, flat.size());  // nothing erroneous
}

struct UsageFixture {
    SynthesisInput in;
    SynthesisOptions opt;
    Level L;
    Nnf nnf;
};

UsageFixture make(int sw, int sh, int tw, int th, UsageStrategy usage, bool labels) {
    UsageFixture f;
    f.in.style = testing::texture(sw, sh, 3, 40);
    GuidePair g;
    g.source = testing::texture(sw, sh, 1, 41);
    g.target = testing::texture(tw, th, 1, 42);
    f.in.guides.push_back(g);
    if (labels) {
        f.in.source_labels = Image(sw, sh, 1);
        f.in.target_labels = Image(tw, th, 1);
        for (int y = 0; y < sh; ++y)
            for (int x = 0; x < sw; ++x) f.in.source_labels.at(x, y, 0) = x < sw / 3 ? 1.f : 2.f;
        for (int y = 0; y < th; ++y)
            for (int x = 0; x < tw; ++x) f.in.target_labels.at(x, y, 0) = y < th / 2 ? 1.f : 2.f;
    }
    f.opt.usage = usage;
    LevelBuilder builder(f.in, f.opt, 1, 1);
    f.L = builder.build(0);
    set_target_style(f.L, testing::texture(tw, th, 3, 43));
    f.nnf = Nnf(tw, th);
    for (Match& m : f.nnf.matches()) m = Match{-1, -1, 0.0f, 0.0f};
    ForwardProblem all{f.L, f.L.target_active.data()};
    evaluate_field(all, f.nnf, 1, 1);
    return f;
}

void expect_uniform(const UsageFixture& f) {
    const std::vector<float> usage = usage_counts(f.L, f.nnf);
    for (std::size_t g = 0; g < f.L.valid_by_group.size(); ++g) {
        // Patches over the border (target or source) are not distributed: border targets take
        // nearest neighbours, from any source.
        std::vector<float> inner_usage(usage.size(), 0.0f);
        std::size_t targets = 0;
        for (std::size_t t = 0; t < f.nnf.pixel_count(); ++t) {
            if (!f.L.target_active[t] || !f.L.target_inside(t)) continue;
            inner_usage[f.L.source_index(f.nnf[t].x, f.nnf[t].y)] += 1.0f;
            targets += f.L.target_group(t) == static_cast<int>(g) ? 1 : 0;
        }
        std::vector<int> inside;
        for (int s : f.L.valid_by_group[g]) {
            if (f.L.source_inside(static_cast<std::size_t>(s))) inside.push_back(s);
        }
        const std::size_t sources = inside.size();
        const float K = static_cast<float>(targets / sources);
        std::size_t k_plus_one = 0;
        for (int s : inside) {
            const float u = inner_usage[static_cast<std::size_t>(s)];
            ASSERT_TRUE(u == K || u == K + 1) << "source " << s << " used " << u << ", K=" << K;
            k_plus_one += u == K + 1 ? 1 : 0;
        }
        EXPECT_EQ(k_plus_one, targets % sources) << "group " << g;
    }
    // Every match respects validity and labels.
    for (std::size_t t = 0; t < f.nnf.pixel_count(); ++t) {
        if (!f.L.target_active[t]) continue;
        ASSERT_TRUE(f.L.compatible(t, f.nnf[t].x, f.nnf[t].y));
    }
}

// The nearest set pixel against brute force: the same (squared) distance everywhere, on sparse
// and dense random sets, single points, empty sets and thin grids; and the same pixels for any
// thread count.
TEST(NearestSetPixel, MatchesBruteForceDistances) {
    const struct {
        int w, h;
        double density;
    } cases[] = {{37, 29, 0.002}, {37, 29, 0.05}, {64, 48, 0.5}, {1, 40, 0.1},
                 {40, 1, 0.1},    {150, 3, 0.01}, {13, 11, 0.0}};
    std::uint64_t state = 7;
    auto next = [&] {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<double>(state >> 11) / 9007199254740992.0;
    };
    for (const auto& c : cases) {
        std::vector<std::uint8_t> set(static_cast<std::size_t>(c.w) * c.h, 0);
        for (auto& v : set) v = next() < c.density ? 1 : 0;
        if (c.density > 0.0 && std::count(set.begin(), set.end(), 1) == 0) set[set.size() / 2] = 1;
        const std::vector<int> one = nearest_set_pixel(set, c.w, c.h, 1);
        EXPECT_EQ(one, nearest_set_pixel(set, c.w, c.h, 2));
        for (int y = 0; y < c.h; ++y) {
            for (int x = 0; x < c.w; ++x) {
                long best = -1;
                for (int i = 0; i < static_cast<int>(set.size()); ++i) {
                    if (!set[static_cast<std::size_t>(i)]) continue;
                    const long dx = i % c.w - x, dy = i / c.w - y;
                    if (best < 0 || dx * dx + dy * dy < best) best = dx * dx + dy * dy;
                }
                const int got = one[static_cast<std::size_t>(y) * c.w + x];
                if (best < 0) {
                    EXPECT_EQ(got, -1);
                    continue;
                }
                ASSERT_GE(got, 0);
                ASSERT_TRUE(set[static_cast<std::size_t>(got)]);
                const long dx = got % c.w - x, dy = got / c.w - y;
                EXPECT_EQ(dx * dx + dy * dy, best) << c.w << "x" << c.h << " at " << x << "," << y;
            }
        }
    }
}

TEST(UniformUsage, EverySourcePatchUsedKOrKPlusOneTimes) {
    // Target larger than the source: K >= 1 with a remainder.
    UsageFixture f = make(20, 18, 41, 37, UsageStrategy::Uniform, false);
    const SearchStats stats = search(SearchSetup{f.L, f.opt, 77, 2}, f.nnf);
    EXPECT_GT(stats.reverse_assigned, stats.forward_assigned);  // mostly the paper's retrieval
    expect_uniform(f);
}

TEST(UniformUsage, SmallerTargetUsesEachPatchAtMostOnce) {
    UsageFixture f = make(40, 40, 20, 22, UsageStrategy::Uniform, false);
    search(SearchSetup{f.L, f.opt, 5, 1}, f.nnf);
    expect_uniform(f);  // K = 0, R = |X|
}

TEST(UniformUsage, PerLabelSegment) {
    UsageFixture f = make(30, 24, 36, 30, UsageStrategy::Uniform, true);
    ASSERT_EQ(f.L.valid_by_group.size(), 2u);
    search(SearchSetup{f.L, f.opt, 8, 2}, f.nnf);
    expect_uniform(f);
}

// On the finest level the budget's pieces also grow between rounds (grow_assigned): the grown
// matches count as the rounds' and must be as exact and as compatible as the others.
class ErrorBudgetOnLevel : public ::testing::TestWithParam<bool> {};

TEST_P(ErrorBudgetOnLevel, CoversEveryTargetAndPrefersLowErrors) {
    UsageFixture f = make(24, 24, 40, 36, UsageStrategy::ErrorBudget, false);
    SearchSetup setup{f.L, f.opt, 3, 2};
    setup.finest = GetParam();
    const SearchStats stats = search(setup, f.nnf);
    EXPECT_GE(stats.rounds, 2);  // the target is larger: patches must be reused
    EXPECT_GT(stats.reverse_assigned, 0u);
    const auto active =
        static_cast<std::size_t>(std::count(f.L.target_active.begin(), f.L.target_active.end(), 1));
    EXPECT_EQ(stats.reverse_assigned + stats.forward_assigned, active);
    for (std::size_t t = 0; t < f.nnf.pixel_count(); ++t) {
        if (!f.L.target_active[t]) continue;
        const Match& m = f.nnf[t];
        ASSERT_TRUE(f.L.compatible(t, m.x, m.y));
        ASSERT_NEAR(m.error,
                    patch_distance_reference(f.L, static_cast<int>(t % f.L.tw),
                                             static_cast<int>(t / f.L.tw), m.x, m.y, 0.0f),
                    1e-4f);
    }
    // Coverage by reversed retrieval reaches the configured 95% (or the round limit).
    const double covered =
        static_cast<double>(stats.reverse_assigned) / static_cast<double>(active);
    EXPECT_TRUE(covered >= 0.95 || stats.rounds == f.opt.budget_max_rounds) << covered;
}

INSTANTIATE_TEST_SUITE_P(ErrorBudget, ErrorBudgetOnLevel, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& level) {
                             return level.param ? "FinestLevel" : "CoarserLevel";
                         });

// Stray matches: those continuing the source region of fewer than 2 of their 4 neighbours, and
// those of pieces (targets connected through neighbours that continue each other's source
// region) smaller than half a patch (angle 0 here): 1 for the former, 2 for the latter only.
// Pieces by flood fill.
std::vector<std::uint8_t> strays(const Level& L, const Nnf& nnf) {
    std::vector<std::uint8_t> out(nnf.pixel_count(), 0);
    const std::pair<int, int> steps[] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    auto continues = [&](std::size_t t, int x, int y, int dx, int dy) {
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= L.tw || ny >= L.th) return false;
        const std::size_t n = L.target_index(nx, ny);
        return L.target_active[n] && nnf[n].x == nnf[t].x + dx && nnf[n].y == nnf[t].y + dy;
    };
    std::vector<int> piece(nnf.pixel_count(), -1);
    std::vector<std::size_t> piece_size;
    for (int y = 0; y < L.th; ++y) {
        for (int x = 0; x < L.tw; ++x) {
            const std::size_t t = L.target_index(x, y);
            if (!L.target_active[t]) continue;
            int agreeing = 0;
            for (const auto& [dx, dy] : steps) agreeing += continues(t, x, y, dx, dy) ? 1 : 0;
            out[t] = agreeing < 2 ? 1 : 0;
            if (piece[t] >= 0) continue;
            const int id = static_cast<int>(piece_size.size());
            std::vector<std::size_t> stack{t};
            piece[t] = id;
            std::size_t size = 0;
            while (!stack.empty()) {
                const std::size_t p = stack.back();
                stack.pop_back();
                ++size;
                const int px = static_cast<int>(p % L.tw), py = static_cast<int>(p / L.tw);
                for (const auto& [dx, dy] : steps) {
                    if (!continues(p, px, py, dx, dy)) continue;
                    const std::size_t n = L.target_index(px + dx, py + dy);
                    if (piece[n] < 0) {
                        piece[n] = id;
                        stack.push_back(n);
                    }
                }
            }
            piece_size.push_back(size);
        }
    }
    const std::size_t small = (L.patch_size * L.patch_size + 1) / 2;
    for (std::size_t t = 0; t < out.size(); ++t) {
        if (out[t] == 0 && piece[t] >= 0 &&
            piece_size[static_cast<std::size_t>(piece[t])] < small) {
            out[t] = 2;
        }
    }
    return out;
}

// The coherence sweeps after the error budget's assignment on the finest level: only stray
// matches (isolated picks, seam pixels, small pieces) change, each to a closer one (with its exact
// distance), and fewer strays remain; the same for any thread count.
TEST(ErrorBudget, CoherenceSweepsMergeOnlyStrayMatches) {
    UsageFixture plain = make(24, 24, 40, 36, UsageStrategy::ErrorBudget, true);
    plain.opt.coherence_sweeps = 0;
    SearchSetup plain_setup{plain.L, plain.opt, 3, 2};
    plain_setup.finest = true;  // small pieces are strays on the finest level
    search(plain_setup, plain.nnf);
    const std::vector<std::uint8_t> before = strays(plain.L, plain.nnf);
    std::size_t changed = 0, changed_in_small_pieces = 0;
    for (const int threads : {1, 2}) {
        UsageFixture swept = make(24, 24, 40, 36, UsageStrategy::ErrorBudget, true);
        swept.opt.coherence_sweeps = 2;
        SearchSetup setup{swept.L, swept.opt, 3, threads};
        setup.finest = true;
        search(setup, swept.nnf);
        changed = changed_in_small_pieces = 0;
        for (std::size_t t = 0; t < swept.nnf.pixel_count(); ++t) {
            if (!swept.L.target_active[t]) continue;
            const Match& a = plain.nnf[t];
            const Match& b = swept.nnf[t];
            if (a.x == b.x && a.y == b.y) continue;
            ++changed;
            changed_in_small_pieces += before[t] == 2 ? 1 : 0;
            ASSERT_TRUE(before[t]) << "a coherent match changed at " << t;
            ASSERT_LT(b.error, a.error) << t;
            ASSERT_TRUE(swept.L.compatible(t, b.x, b.y)) << t;  // labels kept
            ASSERT_NEAR(b.error,
                        patch_distance_reference(swept.L, static_cast<int>(t % swept.L.tw),
                                                 static_cast<int>(t / swept.L.tw), b.x, b.y, 0.0f),
                        1e-4f);
        }
        const std::vector<std::uint8_t> after = strays(swept.L, swept.nnf);
        const auto count = [](const std::vector<std::uint8_t>& v) {
            return v.size() - static_cast<std::size_t>(std::count(v.begin(), v.end(), 0));
        };
        EXPECT_GT(changed, 0u);
        EXPECT_GT(changed_in_small_pieces, 0u);
        EXPECT_LT(count(after), count(before)) << "threads " << threads;
    }
}

// The uniform usage's coherence sweeps: moves and swaps keep every count at K or K + 1 (also for
// K = 0 and per label), fewer strays remain, the summed error of the assignment goes down, every
// stored error is the exact distance, and the result is the same for any thread count.
TEST(UniformUsage, CoherenceSweepsKeepTheCountsAndMergeStrays) {
    const struct {
        int sw, sh, tw, th;
        bool labels;
    } cases[] = {{20, 18, 41, 37, false}, {40, 40, 20, 22, false}, {30, 24, 36, 30, true}};
    for (const auto& c : cases) {
        UsageFixture plain = make(c.sw, c.sh, c.tw, c.th, UsageStrategy::Uniform, c.labels);
        search(SearchSetup{plain.L, plain.opt, 9, 2}, plain.nnf);
        std::vector<Nnf> swept_nnfs;
        for (const int threads : {1, 2}) {
            UsageFixture swept = make(c.sw, c.sh, c.tw, c.th, UsageStrategy::Uniform, c.labels);
            swept.opt.uniform_coherence_sweeps = 2;
            search(SearchSetup{swept.L, swept.opt, 9, threads}, swept.nnf);
            expect_uniform(swept);
            double error_plain = 0.0, error_swept = 0.0;
            for (std::size_t t = 0; t < swept.nnf.pixel_count(); ++t) {
                if (!swept.L.target_active[t] || !swept.L.target_inside(t)) continue;
                error_plain += plain.nnf[t].error;
                error_swept += swept.nnf[t].error;
                const Match& m = swept.nnf[t];
                ASSERT_NEAR(
                    m.error,
                    patch_distance_reference(swept.L, static_cast<int>(t % swept.L.tw),
                                             static_cast<int>(t / swept.L.tw), m.x, m.y, 0.0f),
                    1e-4f * std::max(1.0f, m.error));
            }
            const auto count = [](const std::vector<std::uint8_t>& v) {
                return std::count(v.begin(), v.end(), 1);
            };
            EXPECT_LT(count(strays(swept.L, swept.nnf)), count(strays(plain.L, plain.nnf)))
                << c.sw << "x" << c.sh << " -> " << c.tw << "x" << c.th;
            EXPECT_LT(error_swept, error_plain);
            swept_nnfs.push_back(std::move(swept.nnf));
        }
        for (std::size_t t = 0; t < swept_nnfs[0].pixel_count(); ++t) {
            ASSERT_EQ(swept_nnfs[0][t].x, swept_nnfs[1][t].x) << t;
            ASSERT_EQ(swept_nnfs[0][t].y, swept_nnfs[1][t].y) << t;
        }
    }
}

// grow_pieces against its definition, written plainly: in each of the (r + 1)^2 phases every
// target of the phase takes, of its match and its window's matches shifted back to it, the one of
// least distance + lambda x (window neighbours that do not propose it), lambda = weight x the mean
// stored error on entry. Then: the field has fewer seams, the energy (distances + lambda x the
// disagreeing pairs) is lower, every stored error is the exact distance, and the result is the
// same for 1, 2 and 3 threads.
Nnf plain_pieces(const Level& L, Nnf nnf, int sweeps, float weight, int r) {
    double sum = 0.0;
    int count = 0;
    for (std::size_t t = 0; t < nnf.pixel_count(); ++t) {
        if (L.target_active[t]) sum += nnf[t].error, ++count;
    }
    const float lambda = static_cast<float>(weight * (sum / count));
    for (int step = 0; step < sweeps * (r + 1) * (r + 1); ++step) {
        const int phase = step % ((r + 1) * (r + 1));
        for (int y = phase / (r + 1); y < L.th; y += r + 1) {
            for (int x = phase % (r + 1); x < L.tw; x += r + 1) {
                const std::size_t t = L.target_index(x, y);
                if (!L.target_active[t]) continue;
                // Candidates in the window's order, the own match first; each costed once.
                std::vector<std::pair<int, int>> candidates{{nnf[t].x, nnf[t].y}};
                for (int dy = -r; dy <= r; ++dy) {
                    for (int dx = -r; dx <= r; ++dx) {
                        const int nx = x + dx, ny = y + dy;
                        if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= L.tw || ny >= L.th ||
                            !L.target_active[L.target_index(nx, ny)]) {
                            continue;
                        }
                        const Match& m = nnf[L.target_index(nx, ny)];
                        const std::pair c{m.x - dx, m.y - dy};
                        if (c.first < 0 || c.second < 0 || c.first >= L.sw || c.second >= L.sh ||
                            std::find(candidates.begin(), candidates.end(), c) !=
                                candidates.end()) {
                            continue;
                        }
                        candidates.push_back(c);
                    }
                }
                auto seams = [&](int cx, int cy) {
                    int n = 0;
                    for (int dy = -r; dy <= r; ++dy) {
                        for (int dx = -r; dx <= r; ++dx) {
                            const int nx = x + dx, ny = y + dy;
                            if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= L.tw ||
                                ny >= L.th || !L.target_active[L.target_index(nx, ny)]) {
                                continue;
                            }
                            const Match& m = nnf[L.target_index(nx, ny)];
                            n += m.x - dx == cx && m.y - dy == cy ? 0 : 1;
                        }
                    }
                    return n;
                };
                Match best = nnf[t];
                float best_total = best.error + lambda * static_cast<float>(seams(best.x, best.y));
                for (std::size_t k = 1; k < candidates.size(); ++k) {
                    const auto [cx, cy] = candidates[k];
                    if (!L.compatible(t, cx, cy)) continue;
                    const float smooth = lambda * static_cast<float>(seams(cx, cy));
                    const float d = patch_distance(L, x, y, cx, cy, 0.0f);
                    if (d < best_total - smooth)
                        best = Match{cx, cy, 0.0f, d}, best_total = d + smooth;
                }
                nnf[t] = best;
            }
        }
    }
    return nnf;
}

// Pairs of active targets within Chebyshev distance r whose matches do not continue each other.
std::size_t seam_pairs(const Level& L, const Nnf& nnf, int r) {
    std::size_t n = 0;
    for (int y = 0; y < L.th; ++y) {
        for (int x = 0; x < L.tw; ++x) {
            for (int dy = 0; dy <= r; ++dy) {
                for (int dx = -r; dx <= r; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    if ((dy == 0 && dx <= 0) || nx < 0 || nx >= L.tw || ny >= L.th) continue;
                    const std::size_t a = L.target_index(x, y), b = L.target_index(nx, ny);
                    if (!L.target_active[a] || !L.target_active[b]) continue;
                    n += nnf[b].x - nnf[a].x == dx && nnf[b].y - nnf[a].y == dy ? 0 : 1;
                }
            }
        }
    }
    return n;
}

TEST(GrowPieces, MatchesItsDefinitionMergesPiecesAndLowersTheEnergy) {
    for (const int r : {1, 2}) {
        UsageFixture f = make(24, 24, 40, 36, UsageStrategy::ErrorBudget, true);
        SearchSetup setup{f.L, f.opt, 3, 2};
        setup.finest = true;
        search(setup, f.nnf);  // the budget's mosaic
        constexpr float kWeight = 1.0f;
        double sum = 0.0, count = 0.0;
        for (std::size_t t = 0; t < f.nnf.pixel_count(); ++t) {
            if (f.L.target_active[t]) sum += f.nnf[t].error, count += 1.0;
        }
        const double lambda = kWeight * sum / count;
        auto energy = [&](const Nnf& nnf) {
            double e = 0.0;
            for (std::size_t t = 0; t < nnf.pixel_count(); ++t) {
                if (f.L.target_active[t]) e += nnf[t].error;
            }
            return e + lambda * static_cast<double>(seam_pairs(f.L, nnf, r));
        };
        const Nnf expected = plain_pieces(f.L, f.nnf, 2, kWeight, r);
        for (const int threads : {1, 2, 3}) {
            Nnf grown = f.nnf;
            EXPECT_GT(grow_pieces(f.L, grown, 2, kWeight, r, threads), 0u);
            for (std::size_t t = 0; t < grown.pixel_count(); ++t) {
                if (!f.L.target_active[t]) continue;
                ASSERT_EQ(grown[t].x, expected[t].x) << "r " << r << " threads " << threads;
                ASSERT_EQ(grown[t].y, expected[t].y) << "r " << r << " threads " << threads;
                ASSERT_TRUE(f.L.compatible(t, grown[t].x, grown[t].y));  // labels kept
                ASSERT_NEAR(grown[t].error,
                            patch_distance_reference(f.L, static_cast<int>(t % f.L.tw),
                                                     static_cast<int>(t / f.L.tw), grown[t].x,
                                                     grown[t].y, 0.0f),
                            1e-4f * std::max(1.0f, grown[t].error));
            }
            EXPECT_LT(seam_pairs(f.L, grown, r), seam_pairs(f.L, f.nnf, r)) << "r " << r;
            EXPECT_LT(energy(grown), energy(f.nnf)) << "r " << r;
        }
    }
}

TEST(OccurrencePenalty, ReducesMaximalUsage) {
    // A flat target makes plain nearest neighbours pile onto a few source patches.
    auto max_usage = [](UsageStrategy usage, float strength) {
        UsageFixture f = make(30, 30, 40, 40, usage, false);
        f.opt.occurrence_strength = strength;
        Image flat(40, 40, 3, 0.5f);
        set_target_style(f.L, flat);
        ForwardProblem all{f.L, f.L.target_active.data()};
        evaluate_field(all, f.nnf, 1, 1);
        search(SearchSetup{f.L, f.opt, 4, 1}, f.nnf);
        const std::vector<float> u = usage_counts(f.L, f.nnf);
        return *std::max_element(u.begin(), u.end());
    };
    const float plain = max_usage(UsageStrategy::None, 0.0f);
    const float penalized = max_usage(UsageStrategy::OccurrencePenalty, 1.0f);
    EXPECT_LT(penalized, plain * 0.5f) << "plain " << plain << " penalized " << penalized;
}

TEST(Usage, StrategiesAreDeterministicAcrossThreadCounts) {
    for (UsageStrategy s : {UsageStrategy::None, UsageStrategy::Uniform, UsageStrategy::ErrorBudget,
                            UsageStrategy::OccurrencePenalty}) {
        UsageFixture a = make(26, 22, 33, 29, s, true);
        UsageFixture b = make(26, 22, 33, 29, s, true);
        for (bool finest : {false, true}) {  // the finest level's budget grows its pieces
            SearchSetup one{a.L, a.opt, 12, 1}, two{b.L, b.opt, 12, 2};
            one.finest = two.finest = finest;
            search(one, a.nnf);
            search(two, b.nnf);
            for (std::size_t i = 0; i < a.nnf.pixel_count(); ++i) {
                ASSERT_EQ(a.nnf[i].x, b.nnf[i].x) << to_string(s) << " finest " << finest;
                ASSERT_EQ(a.nnf[i].y, b.nnf[i].y) << to_string(s) << " finest " << finest;
            }
        }
    }
}

// A level whose first rounds have over 4,096 candidates (5,816 and 4,276), which take the parallel
// compaction, sort and merge, and the parallel assignment: the same field on 1 and 3 threads. The
// run's last search (SearchSetup::last) finds the same field as any other and drops its reversed
// field; a search kept for a next iteration keeps its first round's.
TEST(ErrorBudget, LargeRoundsAreDeterministicAndTheLastSearchDropsItsReversedField) {
    UsageFixture base = make(128, 112, 136, 120, UsageStrategy::ErrorBudget, false);
    std::vector<Nnf> fields;
    for (const auto& [threads, last] : {std::pair{1, false}, {3, false}, {3, true}}) {
        UsageFixture f = base;
        Nnf reverse;
        SearchSetup setup{f.L, f.opt, 21, threads, &reverse};
        setup.finest = true;
        setup.last = last;
        const SearchStats stats = search(setup, f.nnf);
        EXPECT_GT(stats.reverse_assigned, 4096u);
        EXPECT_EQ(reverse.empty(), last) << "threads " << threads;
        fields.push_back(f.nnf);
    }
    for (std::size_t k = 1; k < fields.size(); ++k) {
        for (std::size_t i = 0; i < fields[0].pixel_count(); ++i) {
            ASSERT_EQ(fields[0][i].x, fields[k][i].x) << "run " << k << " pixel " << i;
            ASSERT_EQ(fields[0][i].y, fields[k][i].y) << "run " << k << " pixel " << i;
            ASSERT_EQ(fields[0][i].error, fields[k][i].error) << "run " << k << " pixel " << i;
        }
    }
}

}  // namespace
}  // namespace exemplar::synth
