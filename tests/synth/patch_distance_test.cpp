#include "patch_distance.hpp"

#include <gtest/gtest.h>
#include <hwy/targets.h>

#include "level_builder.hpp"
#include "ssd.hpp"
#include "test_images.hpp"

namespace exemplar::synth {
namespace {

std::vector<float> random_floats(std::size_t n, std::uint64_t seed) {
    std::vector<float> v(n);
    KeyedRng rng(seed, 0);
    for (float& x : v) x = rng.uniform();
    return v;
}

Level make_level(int patch, bool weight_map, float falloff, bool rotated) {
    SynthesisInput in;
    in.style = testing::texture(30, 26, 3, 1);
    GuidePair g;
    g.source = testing::texture(30, 26, 2, 2);
    g.target = testing::texture(22, 20, 2, 3);
    g.weight = 0.7f;
    if (weight_map) g.target_weight_map = testing::texture(22, 20, 1, 4);
    in.guides.push_back(g);
    if (rotated) {
        in.source_orientation = testing::texture(30, 26, 1, 5);
        in.target_orientation = testing::texture(22, 20, 1, 6);
    }
    SynthesisOptions opt;
    opt.patch_size = patch;
    opt.falloff_sigma_px = falloff;
    LevelBuilder builder(in, opt, 1, 1);
    Level L = builder.build(0);
    set_target_style(L, testing::texture(22, 20, 3, 7));
    return L;
}

TEST(PatchDistance, FastPathMatchesReference) {
    for (int patch : {3, 5, 7}) {
        const Level L = make_level(patch, false, 0.0f, false);
        const int r = patch / 2;
        for (int ty = 0; ty < L.th; ty += 3) {
            for (int tx = 0; tx < L.tw; tx += 2) {
                for (int sy = r; sy < L.sh - r; sy += 5) {
                    for (int sx = r; sx < L.sw - r; sx += 4) {
                        const float ref = patch_distance_reference(L, tx, ty, sx, sy, 0.0f);
                        const float fast = patch_distance(L, tx, ty, sx, sy, 0.0f);
                        ASSERT_NEAR(fast, ref, 1e-5f * (1.0f + ref))
                            << "patch " << patch << " t " << tx << "," << ty;
                    }
                }
            }
        }
    }
}

TEST(PatchDistance, WeightedAndRotatedPathsMatchReference) {
    const Level L = make_level(5, true, 1.5f, true);
    for (int ty = 0; ty < L.th; ty += 3) {
        for (int tx = 0; tx < L.tw; tx += 3) {
            const float angle = L.angle_for(L.target_index(tx, ty), 12, 11);
            EXPECT_FLOAT_EQ(patch_distance(L, tx, ty, 12, 11, angle),
                            patch_distance_reference(L, tx, ty, 12, 11, angle));
        }
    }
}

TEST(PatchDistance, IdenticalPatchesHaveZeroDistanceAndWeightsScale) {
    // Target = source: the distance at the same position is exactly 0.
    SynthesisInput in;
    in.style = testing::texture(20, 20, 3, 9);
    GuidePair g{"g", testing::ramp(20, 20), testing::ramp(20, 20), 2.0f, {}};
    in.guides.push_back(g);
    SynthesisOptions opt;
    LevelBuilder builder(in, opt, 1, 1);
    Level L = builder.build(0);
    set_target_style(L, in.style);
    EXPECT_EQ(patch_distance(L, 10, 10, 10, 10, 0.0f), 0.0f);
    // Guide weight 2 doubles the squared guide difference; style weight 1.
    const float d = patch_distance_reference(L, 10, 10, 11, 10, 0.0f);
    double expected = 0.0;
    for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
            for (int c = 0; c < 3; ++c) {
                const double e =
                    in.style.at(10 + dx, 10 + dy, c) - in.style.at(11 + dx, 10 + dy, c);
                expected += e * e;
            }
            const double gx = 1.0 / 19.0;  // ramp step in x
            expected += 2.0 * gx * gx;
        }
    }
    EXPECT_NEAR(d, expected, 1e-4);
}

TEST(PatchDistance, EarlyTerminationExceedsBound) {
    const Level L = make_level(5, false, 0.0f, false);
    const float full = patch_distance(L, 10, 10, 8, 8, 0.0f);
    ASSERT_GT(full, 0.0f);
    EXPECT_GT(patch_distance(L, 10, 10, 8, 8, 0.0f, full * 0.1f), full * 0.1f);
}

TEST(SsdRows, SimdMatchesScalarForEveryLength) {
    const std::vector<float> a = random_floats(4096, 5), b = random_floats(4096, 6);
    for (int n = 1; n <= 130; ++n) {
        for (int rows : {1, 3, 5}) {
            const float scalar = ssd_rows_scalar(a.data(), 300, b.data() + 7, 301, rows, n, 1e30f);
            const float simd = ssd_rows(a.data(), 300, b.data() + 7, 301, rows, n, 1e30f);
            ASSERT_NEAR(simd, scalar, 1e-5f * scalar) << "n=" << n << " rows=" << rows;
        }
    }
    // Early termination: the result exceeds the bound, and is a partial sum.
    const float full = ssd_rows(a.data(), 100, b.data(), 100, 5, 100, 1e30f);
    const float cut = ssd_rows(a.data(), 100, b.data(), 100, 5, 100, full * 0.3f);
    EXPECT_GT(cut, full * 0.3f);
    EXPECT_LT(cut, full);
    EXPECT_NE(std::string(simd_target_name()), "");
}

TEST(SsdRows, ScalarSwitchGivesTheSameDistances) {
    const Level L = make_level(5, false, 0.0f, false);
    ASSERT_TRUE(simd_enabled());
    for (int ty = 2; ty < L.th - 2; ty += 3) {
        const float simd = patch_distance(L, 10, ty, 9, 12, 0.0f);
        set_simd_enabled(false);
        const float scalar = patch_distance(L, 10, ty, 9, 12, 0.0f);
        set_simd_enabled(true);
        EXPECT_NEAR(simd, scalar, 1e-5f * (1.0f + scalar));
    }
}

TEST(SsdRows, EverySupportedSimdTargetMatchesScalar) {
    const std::vector<float> a = random_floats(2048, 9), b = random_floats(2048, 10);
    int tested = 0;
    for (int64_t targets = hwy::SupportedTargets() & HWY_TARGETS; targets != 0;
         targets &= targets - 1) {
        const int64_t target = targets & -targets;
        hwy::SetSupportedTargetsForTest(target);
        for (int n : {3, 15, 25, 75, 97}) {
            const float scalar = ssd_rows_scalar(a.data(), 200, b.data(), 200, 5, n, 1e30f);
            EXPECT_NEAR(ssd_rows(a.data(), 200, b.data(), 200, 5, n, 1e30f), scalar, 1e-5f * scalar)
                << hwy::TargetName(target) << " n=" << n;
        }
        ++tested;
    }
    hwy::SetSupportedTargetsForTest(0);
    EXPECT_GE(tested, 1);
}

}  // namespace
}  // namespace exemplar::synth
