#include "guide_pca.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>

namespace exemplar::synth {
namespace {

double uniform(std::uint64_t& state) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
}

// Two guide pairs whose six channels are built from two random signals a, b per pixel (rank 2
// plus a constant channel), with different weights.
std::vector<GuidePair> low_rank_guides(int sw, int sh, int tw, int th) {
    std::uint64_t state = 11;
    auto fill = [&](Image& one, Image& two) {
        for (std::size_t i = 0; i < one.pixel_count(); ++i) {
            const auto a = static_cast<float>(uniform(state));
            const auto b = static_cast<float>(uniform(state));
            float* p = one.data().data() + i * 3;
            float* q = two.data().data() + i * 3;
            p[0] = a;
            p[1] = b;
            p[2] = 0.5f * (a + b);
            q[0] = 2.0f * a;
            q[1] = b - a;
            q[2] = 0.25f;
        }
    };
    Image s1(sw, sh, 3), s2(sw, sh, 3), t1(tw, th, 3), t2(tw, th, 3);
    fill(s1, s2);
    fill(t1, t2);
    return {GuidePair{"one", s1, t1, 0.5f, {}}, GuidePair{"two", s2, t2, 2.0f, {}}};
}

double weighted_distance(const std::vector<GuidePair>& guides, std::size_t s, std::size_t t) {
    double sum = 0.0;
    for (const GuidePair& g : guides) {
        const int C = g.source.channels();
        for (int c = 0; c < C; ++c) {
            const double d = g.source.data()[s * C + c] - g.target.data()[t * C + c];
            sum += g.weight * d * d;
        }
    }
    return sum;
}

TEST(GuidePca, LowRankGuidesKeepEveryDistance) {
    const std::vector<GuidePair> guides = low_rank_guides(23, 17, 19, 21);
    const auto compressed = compress_guides(guides, 0.999, 2);
    ASSERT_TRUE(compressed.has_value());
    EXPECT_EQ(compressed->channels_before, 6);
    EXPECT_EQ(compressed->kept, 2);
    EXPECT_NEAR(compressed->explained_variance, 1.0, 1e-9);
    ASSERT_EQ(compressed->source.channels(), 2);
    ASSERT_TRUE(compressed->source.same_size(guides[0].source));
    ASSERT_TRUE(compressed->target.same_size(guides[0].target));
    std::uint64_t state = 5;
    for (int k = 0; k < 500; ++k) {
        const auto s = static_cast<std::size_t>(uniform(state) * 23 * 17);
        const auto t = static_cast<std::size_t>(uniform(state) * 19 * 21);
        double projected = 0.0;
        for (int c = 0; c < 2; ++c) {
            const double d =
                compressed->source.data()[s * 2 + c] - compressed->target.data()[t * 2 + c];
            projected += d * d;
        }
        const double exact = weighted_distance(guides, s, t);
        EXPECT_NEAR(projected, exact, 1e-4 * (1.0 + exact)) << s << " " << t;
    }
}

TEST(GuidePca, SameResultForAnyThreadCount) {
    const std::vector<GuidePair> guides = low_rank_guides(40, 30, 33, 29);
    const auto one = compress_guides(guides, 0.999, 1);
    const auto two = compress_guides(guides, 0.999, 2);
    ASSERT_TRUE(one.has_value() && two.has_value());
    const auto same = [](const Image& a, const Image& b) {
        return std::equal(a.data().begin(), a.data().end(), b.data().begin(), b.data().end());
    };
    EXPECT_TRUE(same(one->source, two->source));
    EXPECT_TRUE(same(one->target, two->target));
}

TEST(GuidePca, LeavesGuidesAloneWhenNothingWouldBeDropped) {
    // Independent random channels: every component is needed for the exact variance.
    std::uint64_t state = 3;
    Image s(16, 16, 3), t(16, 16, 3);
    for (float& v : s.data()) v = static_cast<float>(uniform(state));
    for (float& v : t.data()) v = static_cast<float>(uniform(state));
    const std::vector<GuidePair> guides{GuidePair{"g", s, t, 1.0f, {}}};
    EXPECT_FALSE(compress_guides(guides, 1.0, 2).has_value());
    // Off, or per-pixel weight maps, or a single channel: never compressed.
    const std::vector<GuidePair> low = low_rank_guides(12, 12, 12, 12);
    EXPECT_FALSE(compress_guides(low, 0.0, 2).has_value());
    std::vector<GuidePair> mapped = low;
    mapped[1].target_weight_map = Image(12, 12, 1, 1.0f);
    EXPECT_FALSE(compress_guides(mapped, 0.999, 2).has_value());
    const std::vector<GuidePair> single{GuidePair{"g", Image(8, 8, 1), Image(8, 8, 1), 1.0f, {}}};
    EXPECT_FALSE(compress_guides(single, 0.999, 2).has_value());
    // A looser goal keeps fewer components of full-rank guides.
    const auto loose = compress_guides(guides, 0.5, 2);
    ASSERT_TRUE(loose.has_value());
    EXPECT_LT(loose->kept, 3);
    EXPECT_GE(loose->explained_variance, 0.5);
}

}  // namespace
}  // namespace exemplar::synth
