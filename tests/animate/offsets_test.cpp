// Offset-field operations: nearest-sample advection with extrapolation, upsampling, merges,
// the dot screen.

#include "exemplar/animate/offsets.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace exemplar::animate {
namespace {

Nnf identity_field(int w, int h) {
    Nnf f(w, h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) f.at(x, y) = Match{x, y, 0.0f, 0.0f};
    }
    return f;
}

TEST(Offsets, AdvectionFollowsTheFlowAndExtrapolatesSubPixelShifts) {
    const Nnf from = identity_field(16, 16);
    Image flow(16, 16, 2);
    for (std::size_t i = 0; i < flow.pixel_count(); ++i) {
        flow.data()[2 * i] = -3.0f;  // p came from p + (-3, +1.6)
        flow.data()[2 * i + 1] = 1.6f;
    }
    const Nnf out = advect_nnf(from, flow, Image(), 16, 16);
    // Pixel (8, 4): position (5, 5.6); nearest sample (5, 6) maps to (5, 6), extrapolated by
    // (0, -0.4) → (5, 5.6) → rounded (5, 6).
    EXPECT_EQ(out.at(8, 4).x, 5);
    EXPECT_EQ(out.at(8, 4).y, 6);
    // Pixels whose source position leaves the frame get "no match".
    EXPECT_EQ(out.at(1, 4).x, -1);
    EXPECT_EQ(out.at(8, 15).x, -1);
}

TEST(Offsets, AdvectionRotatesTheSubPixelRestWithTheMatch) {
    Nnf from(8, 8);
    for (Match& m : from.matches()) m = Match{20, 20, static_cast<float>(M_PI / 2), 0.0f};
    Image flow(8, 8, 2);
    for (std::size_t i = 0; i < flow.pixel_count(); ++i) flow.data()[2 * i] = 0.4f;
    // Rest (+0.4, 0) rotated by 90°: (0, +0.4) → still rounds to (20, 20); with 0.6 → (20, 21)?
    // Use a rest that does not round away: flow 0.4 → nearest sample is p itself, rest 0.4.
    const Nnf a = advect_nnf(from, flow, Image(), 64, 64);
    EXPECT_EQ(a.at(3, 3).x, 20);
    EXPECT_EQ(a.at(3, 3).y, 20);
    for (std::size_t i = 0; i < flow.pixel_count(); ++i) flow.data()[2 * i] = 1.6f;  // rest −0.4
    // Nearest sample p + 2, rest −0.4 along x, rotated by 90° into −0.4 along y: (20, 19.6) → 20.
    const Nnf b = advect_nnf(from, flow, Image(), 64, 64);
    EXPECT_EQ(b.at(3, 3).x, 20);
    EXPECT_EQ(b.at(3, 3).y, 20);
    EXPECT_FLOAT_EQ(b.at(3, 3).angle_rad, static_cast<float>(M_PI / 2));
}

TEST(Offsets, InvisiblePixelsGetNoMatch) {
    const Nnf from = identity_field(8, 8);
    Image flow(8, 8, 2);
    Image visible(8, 8, 1, 1.0f);
    visible.at(2, 3, 0) = 0.0f;
    const Nnf out = advect_nnf(from, flow, visible, 8, 8);
    EXPECT_EQ(out.at(2, 3).x, -1);
    EXPECT_EQ(out.at(3, 3).x, 3);
}

TEST(Offsets, UpsamplingDoublesPositionsAndKeepsSubPixelDetail) {
    const Nnf coarse = identity_field(8, 8);
    const Nnf fine = upsample_nnf(coarse, {{0, 8, 8}}, 16, 16, {{0, 16, 16}});
    // An identity field stays an identity field (up to the rounding of pixel centres).
    for (int y = 1; y < 15; ++y) {
        for (int x = 1; x < 15; ++x) {
            EXPECT_NEAR(fine.at(x, y).x, x, 1);
            EXPECT_NEAR(fine.at(x, y).y, y, 1);
        }
    }
}

TEST(Offsets, UpsamplingMapsEachAtlasSlotOnItsOwn) {
    // Coarse atlas: style 5 wide at x 0, key 8 wide at x 6; fine: style 9 wide, key 16 at x 10.
    Nnf coarse(8, 8);
    for (Match& m : coarse.matches()) m = Match{-1, -1, 0.0f, 0.0f};
    coarse.at(2, 2) = Match{8, 2, 0.0f, 0.0f};  // key slot, local (2, 2)
    coarse.at(5, 5) = Match{1, 1, 0.0f, 0.0f};  // style slot
    const Nnf fine =
        upsample_nnf(coarse, {{0, 5, 8}, {6, 8, 8}}, 16, 16, {{0, 9, 16}, {10, 16, 16}});
    // Fine pixel (4, 4) sits over coarse (1.75, 1.75) → nearest (2, 2), rest (−0.25, −0.25):
    // key-local (1.75, 1.75) → fine (4, 4) (centres aligned) → atlas x 14.
    EXPECT_EQ(fine.at(4, 4).x, 14);
    EXPECT_EQ(fine.at(4, 4).y, 4);
    EXPECT_LT(fine.at(10, 10).x, 9);  // stays in the style slot
    EXPECT_EQ(fine.at(0, 0).x, -1);
}

TEST(Offsets, RandomMergeTakesBothSourcesAndFallsBackOnNoMatch) {
    Nnf a(32, 32), b(32, 32);
    for (Match& m : a.matches()) m = Match{1, 1, 0.0f, 0.0f};
    for (Match& m : b.matches()) m = Match{2, 2, 0.0f, 0.0f};
    a.at(0, 0) = Match{-1, -1, 0.0f, 0.0f};
    const Nnf m = random_merge(a, b, 0.25f, 42);
    int from_a = 0;
    for (const Match& e : m.matches()) from_a += e.x == 1;
    EXPECT_NEAR(from_a / 1024.0, 0.25, 0.05);
    EXPECT_EQ(m.at(0, 0).x, 2);
    const Nnf again = random_merge(a, b, 0.25f, 42);
    for (std::size_t i = 0; i < m.pixel_count(); ++i) EXPECT_EQ(m[i].x, again[i].x);
}

// One draw for every frame: the pixels that take b at a probability of a also take it at any
// lower one (a dissolve only grows), and "no match" still falls back on the other field.
TEST(Offsets, ThresholdMergeTakesBWhereTheDrawReachesTheProbability) {
    Nnf a(16, 16), b(16, 16);
    for (Match& m : a.matches()) m = Match{1, 1, 0.0f, 0.0f};
    for (Match& m : b.matches()) m = Match{2, 2, 0.0f, 0.0f};
    a.at(0, 0) = Match{-1, -1, 0.0f, 0.0f};
    b.at(1, 0) = Match{-1, -1, 0.0f, 0.0f};
    const Image draw = dot_screen(16, 16, 6.0f, 5);
    Nnf previous = threshold_merge(a, b, 1.0f, draw);
    for (float p : {0.8f, 0.5f, 0.2f}) {
        const Nnf m = threshold_merge(a, b, p, draw);
        for (std::size_t i = 0; i < m.pixel_count(); ++i) {
            if (i == 0 || i == 1) continue;
            EXPECT_EQ(m[i].x, draw.data()[i] < p ? 1 : 2);
            if (previous[i].x == 2) {
                EXPECT_EQ(m[i].x, 2);  // switched pixels stay switched
            }
        }
        EXPECT_EQ(m.at(0, 0).x, 2);
        EXPECT_EQ(m.at(1, 0).x, 1);
        previous = m;
    }
}

// The dot screen: values uniform in [0, 1) (a share s of the pixels below s), the same for a
// seed, smooth (blobs, not pixel noise: neighbours differ by far less than independent draws'
// 1/3) and balanced (every block of 2 x 2 cells holds about half its pixels below 1/2).
TEST(Offsets, DotScreenIsUniformSmoothAndBalanced) {
    const int w = 96, h = 64;
    const float cell = 16.0f;
    const Image s = dot_screen(w, h, cell, 3);
    const Image again = dot_screen(w, h, cell, 3);
    for (std::size_t i = 0; i < s.pixel_count(); ++i) EXPECT_EQ(s.data()[i], again.data()[i]);
    for (float q : {0.1f, 0.5f, 0.9f}) {
        int below = 0;
        for (float v : s.data()) below += v < q ? 1 : 0;
        EXPECT_NEAR(below / static_cast<double>(w * h), q, 1.0 / (w * h));
    }
    double step = 0.0;
    for (int y = 0; y < h; ++y) {
        for (int x = 1; x < w; ++x) step += std::abs(s.at(x, y, 0) - s.at(x - 1, y, 0));
    }
    EXPECT_LT(step / ((w - 1) * h), 0.08);
    for (int by = 0; by + 32 <= h; by += 32) {
        for (int bx = 0; bx + 32 <= w; bx += 32) {
            int below = 0;
            for (int y = by; y < by + 32; ++y) {
                for (int x = bx; x < bx + 32; ++x) below += s.at(x, y, 0) < 0.5f ? 1 : 0;
            }
            EXPECT_NEAR(below / 1024.0, 0.5, 0.15) << "block at " << bx << "," << by;
        }
    }
}

// g_∂in's guide: G_t = I_t + (S(C_n) − I_n) pulled along the flow where χ holds, weight 0 (and
// G_t = I_t) where χ = 0, the sample leaves the frame or the neighbour has no match.
TEST(Offsets, InputDerivativeGuideHasZeroWeightWhereChiIsZero) {
    const int w = 8, h = 6;
    Image frame(w, h, 1), prev(w, h, 1), source(10, h, 1);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            frame.at(x, y, 0) = 0.1f * x + 0.01f * y;
            prev.at(x, y, 0) = 0.05f * x;
        }
        for (int x = 0; x < 10; ++x) source.at(x, y, 0) = 0.3f + 0.02f * x * y;
    }
    Nnf offsets(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) offsets.at(x, y) = Match{x + 2, y, 0.0f, 0.0f};
    Image flow(w, h, 2, 0.0f);  // t's pixel p came from p + (1, 0) in the neighbour
    for (std::size_t i = 0; i < flow.pixel_count(); ++i) flow.data()[2 * i] = 1.0f;
    Image visible(w, h, 1, 1.0f);

    // Everything visible and matched except the last column (its sample leaves the frame).
    {
        auto g = input_derivative_guide(frame, prev, offsets, source, flow, visible);
        ASSERT_TRUE(g.ok()) << g.status().message();
        ASSERT_FALSE(g->weight.empty());
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                if (x == w - 1) {
                    EXPECT_EQ(g->weight.at(x, y, 0), 0.0f);
                    EXPECT_EQ(g->target.at(x, y, 0), frame.at(x, y, 0));
                    continue;
                }
                EXPECT_EQ(g->weight.at(x, y, 0), 1.0f);
                const float expected =
                    frame.at(x, y, 0) + source.at(x + 3, y, 0) - prev.at(x + 1, y, 0);
                EXPECT_NEAR(g->target.at(x, y, 0), expected, 1e-6f) << x << "," << y;
            }
        }
    }
    // χ = 0 at (2, 3) and no neighbour match under (4, 1): weight 0 there, G_t = I_t.
    visible.at(2, 3, 0) = 0.0f;
    offsets.at(5, 1) = Match{-1, -1, 0.0f, 0.0f};
    {
        auto g = input_derivative_guide(frame, prev, offsets, source, flow, visible);
        ASSERT_TRUE(g.ok()) << g.status().message();
        for (auto [x, y] : {std::pair{2, 3}, std::pair{4, 1}}) {
            EXPECT_EQ(g->weight.at(x, y, 0), 0.0f) << x << "," << y;
            EXPECT_EQ(g->target.at(x, y, 0), frame.at(x, y, 0));
        }
        EXPECT_EQ(g->weight.at(3, 3, 0), 1.0f);
    }
    // No flow and every pixel matched and visible: no weight map at all.
    {
        visible.at(2, 3, 0) = 1.0f;
        offsets.at(5, 1) = Match{7, 1, 0.0f, 0.0f};
        auto g =
            input_derivative_guide(frame, prev, offsets, source, Image(w, h, 2, 0.0f), visible);
        ASSERT_TRUE(g.ok()) << g.status().message();
        EXPECT_TRUE(g->weight.empty());
    }
}

}  // namespace
}  // namespace exemplar::animate
