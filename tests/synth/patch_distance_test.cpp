#include "patch_distance.hpp"

#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <bit>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

#include "level_builder.hpp"
#include "patchmatch.hpp"
#include "ssd.hpp"
#include "test_images.hpp"

namespace exemplar::synth {
namespace {

std::vector<std::uint8_t> random_codes(std::size_t n, std::uint64_t seed) {
    std::vector<std::uint8_t> v(n);
    KeyedRng rng(seed, 0);
    for (std::uint8_t& x : v) x = static_cast<std::uint8_t>(rng.below(256));
    return v;
}

std::vector<float> random_weights(std::size_t n, std::uint64_t seed) {
    std::vector<float> v(n);
    KeyedRng rng(seed, 0);
    for (float& x : v) x = rng.uniform() * 1e-4f;
    return v;
}

Level make_level(int patch, bool weight_map, float falloff, bool rotated, int guide_channels = 2,
                 int orientation_steps = 0, bool turn_target = false) {
    SynthesisInput in;
    in.orientation_steps = orientation_steps;
    in.rotate_target_patches = turn_target;
    in.style = testing::texture(30, 26, 3, 1);
    GuidePair g;
    g.source = testing::texture(30, 26, guide_channels, 2);
    g.target = testing::texture(22, 20, guide_channels, 3);
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

// The rotated path without weight maps gathers the rotated source patch and runs the SIMD row
// kernel: the reference's value up to float summation order, at every position (inside, where it
// applies, and over the borders, where the general path takes over), for feature counts up to
// and over the 16 bytes it copies per pixel, and with early termination.
TEST(PatchDistance, RotatedGatherMatchesReference) {
    for (int guide_channels : {2, 9, 15}) {
        for (int patch : {3, 5, 7}) {
            const Level L = make_level(patch, false, 0.0f, true, guide_channels);
            for (int ty = 0; ty < L.th; ty += 2) {
                for (int tx = 0; tx < L.tw; tx += 2) {
                    for (const auto& [sx, sy] : {std::pair{12, 11}, {3, 4}, {27, 24}, {0, 13}}) {
                        const float angle = L.angle_for(L.target_index(tx, ty), sx, sy);
                        const float ref = patch_distance_reference(L, tx, ty, sx, sy, angle);
                        ASSERT_NEAR(patch_distance(L, tx, ty, sx, sy, angle), ref,
                                    1e-5f * (1.0f + ref))
                            << "F " << L.feature_channels() << " patch " << patch << " t " << tx
                            << "," << ty << " s " << sx << "," << sy;
                        if (ref > 0.0f) {
                            EXPECT_GT(patch_distance(L, tx, ty, sx, sy, angle, 0.5f * ref),
                                      0.5f * ref);
                        }
                    }
                }
            }
        }
    }
}

// Orientation steps: every pair's angle is the step nearest to its exact difference; the
// distance takes the step's precomputed offsets (the same as computing them), the reference's
// value; the search's one-pixel moves from the table are the computed ones.
TEST(PatchDistance, OrientationStepsRoundAnglesAndUseTheirTables) {
    for (int steps : {7, 32}) {
        const Level L = make_level(5, false, 0.0f, true, 9, steps);
        ASSERT_EQ(L.orientation_steps, steps);
        const float step = 6.28318531f / static_cast<float>(steps);
        for (int k = 0; k < steps; ++k) {
            const float angle = L.step_angle[static_cast<std::size_t>(k)];
            EXPECT_EQ(L.step_of(angle), k);
            EXPECT_GT(angle, -3.1415927f);
            EXPECT_LE(angle, 3.1415927f);
            int computed[25];
            rotated_offsets(L, angle, computed);
            for (int i = 0; i < 25; ++i) {
                EXPECT_EQ(L.step_offsets[static_cast<std::size_t>(k * 25 + i)], computed[i]);
            }
            for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
                const RotatedOffset table = rotated_step(L, angle, dx, dy);
                const RotatedOffset direct = rotated_step(angle, dx, dy);
                EXPECT_EQ(table.dx, direct.dx);
                EXPECT_EQ(table.dy, direct.dy);
            }
        }
        // Angles beyond a turn either way wrap to the nearest step.
        for (float angle : {-40.0f, -7.0f, -3.2f, -0.01f, 0.0f, 0.2f, 3.1f, 6.3f, 12.0f, 100.0f}) {
            const float rounded = L.step_angle[static_cast<std::size_t>(L.step_of(angle))];
            const double turns = (angle - rounded) / 6.283185307179586;
            EXPECT_NEAR(turns, std::round(turns), 0.5 * step / 6.28318531f + 1e-5) << angle;
        }
        for (int ty = 0; ty < L.th; ty += 2) {
            for (int tx = 0; tx < L.tw; tx += 2) {
                for (const auto& [sx, sy] : {std::pair{12, 11}, {3, 4}, {27, 24}, {8, 18}}) {
                    const std::size_t t = L.target_index(tx, ty);
                    const float angle = L.angle_for(t, sx, sy);
                    const float exact = L.source_angle[L.source_index(sx, sy)] - L.target_angle[t];
                    const double off = (exact - angle) / step;
                    ASSERT_LE(std::abs(off - steps * std::round(off / steps)), 0.5 + 1e-4);
                    const float ref = patch_distance_reference(L, tx, ty, sx, sy, angle);
                    ASSERT_NEAR(patch_distance(L, tx, ty, sx, sy, angle), ref, 1e-5f * (1.0f + ref))
                        << "steps " << steps << " t " << tx << "," << ty << " s " << sx << ","
                        << sy;
                }
            }
        }
    }
}

// Turned target patches (SynthesisInput::rotate_target_patches): where they apply (the turned
// target patch inside the target, the source patch inside the source, at most 16 channels, no
// weight maps or fall-off), the distance at every step is the weighted SSD of the plain source
// patch and the target pixels at the offsets turned back by the step (nearest pixel), computed
// here from scratch; the search's cached gather gives the same value to the bit, with the same
// early exit; elsewhere the distance is the turned source patch's (the reference's).
TEST(PatchDistance, TurnedTargetPatchesMatchTheirDefinition) {
    for (int guide_channels : {2, 9, 15}) {
        for (int patch : {3, 5, 7}) {
            const Level L = make_level(patch, false, 0.0f, true, guide_channels, 32, true);
            ASSERT_EQ(L.step_target_offsets.size(), static_cast<std::size_t>(32 * patch * patch));
            const int r = patch / 2;
            const int F = L.feature_channels();
            const std::uint8_t process = 1;
            std::vector<std::uint8_t> all(static_cast<std::size_t>(L.tw) * L.th, process);
            const ForwardProblem problem{L, all.data()};
            for (int ty = 0; ty < L.th; ty += 2) {
                for (int tx = 0; tx < L.tw; ++tx) {
                    for (int k = 0; k < 32; k += 3) {
                        const float angle = L.step_angle[static_cast<std::size_t>(k)];
                        const float c = std::cos(-angle), s = std::sin(-angle);
                        for (const auto& [sx, sy] : {std::pair{12, 11}, {3, 4}, {27, 24}, {1, 1}}) {
                            if (!turns_target(L, tx, ty, sx, sy) || angle == 0.0f) {
                                ASSERT_EQ(problem.cost(tx, ty, sx, sy, angle, 1e30f),
                                          patch_distance(L, tx, ty, sx, sy, angle));
                                ASSERT_NEAR(
                                    patch_distance(L, tx, ty, sx, sy, angle),
                                    patch_distance_reference(L, tx, ty, sx, sy, angle),
                                    1e-5f * (1.0f + patch_distance(L, tx, ty, sx, sy, angle)));
                                continue;
                            }
                            ASSERT_LE(F, 16);
                            float want = 0.0f;
                            for (int ey = -r; ey <= r; ++ey) {
                                for (int ex = -r; ex <= r; ++ex) {
                                    const RotatedOffset o = rotate_offset(ex, ey, c, s);
                                    const std::uint8_t* a =
                                        L.target_features.pixel(tx + o.dx, ty + o.dy);
                                    const std::uint8_t* b =
                                        L.source_features.pixel(sx + ex, sy + ey);
                                    for (int ch = 0; ch < F; ++ch) {
                                        const auto d = static_cast<float>(a[ch] - b[ch]);
                                        want +=
                                            L.channel_weight[static_cast<std::size_t>(ch)] * d * d;
                                    }
                                }
                            }
                            const float got = patch_distance(L, tx, ty, sx, sy, angle);
                            ASSERT_NEAR(got, want, 1e-5f * (1.0f + want))
                                << "F " << F << " patch " << patch << " t " << tx << "," << ty
                                << " s " << sx << "," << sy << " step " << k;
                            // The search's cost: the gathered patch kept for the next candidate.
                            ASSERT_EQ(problem.cost(tx, ty, sx, sy, angle, 1e30f), got);
                            if (got > 0.0f) {
                                EXPECT_GT(problem.cost(tx, ty, sx, sy, angle, 0.5f * got),
                                          0.5f * got);
                            }
                        }
                    }
                }
            }
        }
    }
}

// A new problem (a new search) reads the target as it is then, though the same thread's cache
// holds the patch gathered at the same pixel and step before the target changed.
TEST(PatchDistance, TurnedTargetCacheSeesTheNewTarget) {
    Level L = make_level(5, false, 0.0f, true, 2, 32, true);
    std::vector<std::uint8_t> all(static_cast<std::size_t>(L.tw) * L.th, 1);
    const float angle = L.step_angle[5];
    ASSERT_TRUE(turns_target(L, 10, 10, 12, 11));
    const float before = ForwardProblem{L, all.data()}.cost(10, 10, 12, 11, angle, 1e30f);
    set_target_style(L, testing::texture(22, 20, 3, 8));
    const float after = ForwardProblem{L, all.data()}.cost(10, 10, 12, 11, angle, 1e30f);
    EXPECT_NE(before, after);
    EXPECT_EQ(after, patch_distance(L, 10, 10, 12, 11, angle));
}

// Patches over a border, rotated ones with weight maps or fall-off and every weighted one take the
// gathered path: the reference's arithmetic in its order, so its value to the bit (the search
// chooses as it did with the reference's loop), and with a bound the same early exit.
TEST(PatchDistance, GatheredPathEqualsReferenceExactly) {
    struct Config {
        bool weight_map;
        float falloff;
        bool rotated;
        int guide_channels;
    };
    // With the SIMD terms kernel and with its scalar reference.
    for (bool simd : {true, false}) {
        set_simd_enabled(simd);
        for (const Config& config : {Config{false, 0.0f, false, 2}, Config{true, 0.0f, false, 2},
                                     Config{false, 1.5f, false, 2}, Config{true, 1.5f, true, 2},
                                     Config{true, 0.0f, true, 9}, Config{false, 0.0f, false, 13}}) {
            for (int patch : {3, 5, 7}) {
                const Level L = make_level(patch, config.weight_map, config.falloff, config.rotated,
                                           config.guide_channels);
                for (int ty = 0; ty < L.th; ++ty) {
                    for (int tx = 0; tx < L.tw; ++tx) {
                        for (const auto& [sx, sy] :
                             {std::pair{12, 11}, {0, 0}, {29, 25}, {1, 13}}) {
                            const float angle = L.angle_for(L.target_index(tx, ty), sx, sy);
                            const float ref = patch_distance_reference(L, tx, ty, sx, sy, angle);
                            ASSERT_EQ(
                                patch_distance_general(L, tx, ty, sx, sy, angle,
                                                       std::numeric_limits<float>::infinity()),
                                ref)
                                << "simd " << simd << " F " << L.feature_channels() << " patch "
                                << patch << " t " << tx << "," << ty << " s " << sx << "," << sy;
                            if (ref > 0.0f) {
                                EXPECT_GT(
                                    patch_distance_general(L, tx, ty, sx, sy, angle, 0.5f * ref),
                                    0.5f * ref);
                            }
                        }
                    }
                }
            }
        }
    }
    set_simd_enabled(true);
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
    // Guide weight 2 doubles the squared guide difference; style weight 1. The features are
    // 8-bit codes: every value moves by at most half a code step (1/510 here), which bounds the
    // difference to the float distance.
    const float d = patch_distance_reference(L, 10, 10, 11, 10, 0.0f);
    double expected = 0.0, tolerance = 0.0;
    const double half_step = 0.5 / 255.0;
    for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
            for (int c = 0; c < 3; ++c) {
                const double e =
                    in.style.at(10 + dx, 10 + dy, c) - in.style.at(11 + dx, 10 + dy, c);
                expected += e * e;
                tolerance += 4.0 * half_step * std::abs(e) + 4.0 * half_step * half_step;
            }
            const double gx = 1.0 / 19.0;  // ramp step in x
            expected += 2.0 * gx * gx;
            tolerance += 2.0 * (4.0 * half_step * gx + 4.0 * half_step * half_step);
        }
    }
    EXPECT_NEAR(d, expected, tolerance);
    EXPECT_LT(tolerance, 0.1 * expected);  // the bound is meaningful
}

TEST(Features, EightBitInputsAreCodedExactly) {
    // Values on the 1/255 grid (any 8-bit image) keep their exact differences.
    const ChannelQuantizer q = quantizer_for_range(10.0f / 255.0f, 200.0f / 255.0f);
    EXPECT_FLOAT_EQ(q.step, 1.0f / 255.0f);
    for (int k = 10; k <= 200; ++k) {
        EXPECT_EQ(static_cast<int>(q.code(static_cast<float>(k) / 255.0f)), k - 10);
    }
    // A wider (HDR) range is split into 255 steps; the ends map to 0 and 255, outside clamps.
    const ChannelQuantizer wide = quantizer_for_range(-2.0f, 6.0f);
    EXPECT_FLOAT_EQ(wide.step, 8.0f / 255.0f);
    EXPECT_EQ(wide.code(-2.0f), 0);
    EXPECT_EQ(wide.code(6.0f), 255);
    EXPECT_EQ(wide.code(100.0f), 255);
    EXPECT_EQ(wide.code(-100.0f), 0);
    // A constant channel has one code.
    const ChannelQuantizer flat = quantizer_for_range(0.3f, 0.3f);
    EXPECT_EQ(flat.code(0.3f), 0);
}

TEST(Features, CodeEqualsNearbyintReference) {
    // Every float of [-2, 258] step units around the grid (halves, their neighbouring floats,
    // the clamps) codes as std::nearbyint and std::clamp do, for the 8-bit grid and a wide range.
    for (const ChannelQuantizer q :
         {quantizer_for_range(0.0f, 1.0f), quantizer_for_range(-2.0f, 6.0f)}) {
        for (int k = -4; k <= 516; ++k) {
            const float centre = q.offset + q.step * (0.5f * static_cast<float>(k));
            float v = centre;
            for (int i = 0; i < 8; ++i) v = std::nextafter(v, -1e9f);
            for (int i = 0; i < 17; ++i, v = std::nextafter(v, 1e9f)) {
                ASSERT_EQ(q.code(v), q.code_reference(v)) << "value " << v;
            }
        }
        const float inf = std::numeric_limits<float>::infinity();
        for (float v : {-1e30f, -0.0f, 0.0f, 1e30f, inf, -inf}) {
            EXPECT_EQ(q.code(v), q.code_reference(v)) << "value " << v;
        }
    }
}

TEST(PatchDistance, EarlyTerminationExceedsBound) {
    const Level L = make_level(5, false, 0.0f, false);
    const float full = patch_distance(L, 10, 10, 8, 8, 0.0f);
    ASSERT_GT(full, 0.0f);
    EXPECT_GT(patch_distance(L, 10, 10, 8, 8, 0.0f, full * 0.1f), full * 0.1f);
}

TEST(SsdRows, SimdMatchesScalarForEveryShape) {
    // Rows of any byte length (patch width x channels, no padding), shared or per-row weights.
    const std::vector<std::uint8_t> a = random_codes(8192, 5), b = random_codes(8192, 6);
    const std::vector<float> w = random_weights(4096, 7);
    for (int row_bytes : {1, 3, 4, 9, 15, 16, 17, 27, 45, 48, 75, 80, 160}) {
        for (int rows : {1, 3, 5}) {
            for (std::size_t row_step : {std::size_t{0}, std::size_t{173}}) {
                const SsdWeights weights{w.data() + 3, row_step};
                const float scalar = ssd_rows_scalar(a.data(), 900, b.data() + 7, 901, rows,
                                                     row_bytes, weights, 1e30f);
                const float simd =
                    ssd_rows(a.data(), 900, b.data() + 7, 901, rows, row_bytes, weights, 1e30f);
                ASSERT_GT(scalar, 0.0f);
                ASSERT_NEAR(simd, scalar, 1e-5f * scalar)
                    << "row_bytes=" << row_bytes << " rows=" << rows << " step=" << row_step;
            }
        }
    }
    // Early termination: the result exceeds the bound, and is a partial sum.
    const float full = ssd_rows(a.data(), 100, b.data(), 100, 5, 80, SsdWeights{w.data()}, 1e30f);
    const float cut =
        ssd_rows(a.data(), 100, b.data(), 100, 5, 80, SsdWeights{w.data()}, full * 0.3f);
    EXPECT_GT(cut, full * 0.3f);
    EXPECT_LT(cut, full);
    EXPECT_NE(std::string(simd_target_name()), "");
}

// ssd_rows (on 512-bit targets: four rows' lane sums at once, the bound checked at the end) gives
// the per-row kernel's value to the bit, for any shape, weights and bound, including the partial
// sum returned when a bound is exceeded after any row.
TEST(SsdRows, EqualsThePerRowKernelExactly) {
    const std::vector<std::uint8_t> a = random_codes(16384, 31), b = random_codes(16384, 32);
    const std::vector<float> w = random_weights(8192, 33);
    ASSERT_TRUE(simd_enabled());
    int compared = 0;
    for (int64_t targets = hwy::SupportedTargets() & HWY_TARGETS; targets != 0;
         targets &= targets - 1) {
        const int64_t target = targets & -targets;
        hwy::SetSupportedTargetsForTest(target);
        set_simd_enabled(true);
        for (int row_bytes : {1, 3, 15, 16, 17, 20, 30, 32, 33, 40, 48, 75, 80, 160}) {
            for (int rows = 1; rows <= 17; ++rows) {
                for (std::size_t row_step : {std::size_t{0}, std::size_t{173}}) {
                    const SsdWeights weights{w.data() + 3, row_step};
                    const float full =
                        ssd_rows_per_row(a.data(), 900, b.data() + 7, 901, rows, row_bytes, weights,
                                         std::numeric_limits<float>::infinity());
                    ASSERT_GT(full, 0.0f);
                    // Bounds that stop the sum after every row, and none.
                    for (float f : {0.0f, 0.05f, 0.2f, 0.35f, 0.5f, 0.65f, 0.8f, 0.95f, 2.0f}) {
                        const float bound = full * f;
                        const float per_row = ssd_rows_per_row(a.data(), 900, b.data() + 7, 901,
                                                               rows, row_bytes, weights, bound);
                        const float batched = ssd_rows(a.data(), 900, b.data() + 7, 901, rows,
                                                       row_bytes, weights, bound);
                        ASSERT_EQ(std::bit_cast<std::uint32_t>(batched),
                                  std::bit_cast<std::uint32_t>(per_row))
                            << hwy::TargetName(target) << " row_bytes=" << row_bytes
                            << " rows=" << rows << " step=" << row_step << " bound=" << f;
                        ++compared;
                    }
                }
            }
        }
    }
    hwy::SetSupportedTargetsForTest(0);
    set_simd_enabled(true);
    EXPECT_GT(compared, 4000);
}

// The terms the gathered path adds in the reference's order: the same floats as the scalar
// expression (w * d) * d, for any length (whole vectors and a tail).
TEST(SsdTerms, SimdEqualsScalarExactly) {
    const std::vector<std::uint8_t> a = random_codes(512, 25), b = random_codes(512, 26);
    const std::vector<float> w = random_weights(512, 27);
    ASSERT_TRUE(simd_enabled());
    // Every SIMD target this CPU supports (the kernels are resolved again for each).
    for (int64_t targets = hwy::SupportedTargets() & HWY_TARGETS; targets != 0;
         targets &= targets - 1) {
        const int64_t target = targets & -targets;
        hwy::SetSupportedTargetsForTest(target);
        set_simd_enabled(true);
        for (int n : {1, 3, 6, 15, 16, 17, 30, 45, 75, 240}) {
            std::vector<float> simd(static_cast<std::size_t>(n) + kSsdSlack, -1.0f);
            std::vector<float> scalar(static_cast<std::size_t>(n), -1.0f);
            ssd_terms(a.data() + 5, b.data() + 9, w.data() + 3, n, simd.data());
            ssd_terms_scalar(a.data() + 5, b.data() + 9, w.data() + 3, n, scalar.data());
            for (int i = 0; i < n; ++i) {
                const auto ui = static_cast<std::size_t>(i);
                ASSERT_EQ(simd[ui], scalar[ui])
                    << hwy::TargetName(target) << " n=" << n << " i=" << i;
                const auto d = static_cast<float>(static_cast<int>(a[ui + 5]) - b[ui + 9]);
                ASSERT_EQ(scalar[ui], w[ui + 3] * d * d);
            }
        }
    }
    hwy::SetSupportedTargetsForTest(0);
    set_simd_enabled(true);
}

TEST(SsdRows, TailBytesPastTheRowAreIgnored) {
    // The SIMD kernel reads whole vectors; what lies past row_bytes must not count.
    std::vector<std::uint8_t> a = random_codes(512, 15), b = random_codes(512, 16);
    const std::vector<float> w = random_weights(512, 17);
    for (int row_bytes : {9, 45, 75}) {
        const float before =
            ssd_rows(a.data(), 128, b.data(), 128, 3, row_bytes, SsdWeights{w.data()}, 1e30f);
        for (int r = 0; r < 3; ++r) {
            for (int i = row_bytes; i < 128; ++i) a[static_cast<std::size_t>(r * 128 + i)] ^= 0xff;
        }
        EXPECT_EQ(ssd_rows(a.data(), 128, b.data(), 128, 3, row_bytes, SsdWeights{w.data()}, 1e30f),
                  before)
            << "row_bytes=" << row_bytes;
    }
}

TEST(PatchDistance, WeightMapFastPathMatchesReference) {
    // A guide weight map without fall-off or rotation takes the SIMD path with per-pixel weights.
    const Level L = make_level(5, true, 0.0f, false);
    ASSERT_FALSE(L.target_pixel_weight.empty());
    int compared = 0;
    for (int ty = 2; ty < L.th - 2; ty += 2) {
        for (int tx = 2; tx < L.tw - 2; tx += 3) {
            for (int sy = 2; sy < L.sh - 2; sy += 5) {
                for (int sx = 2; sx < L.sw - 2; sx += 4) {
                    const float ref = patch_distance_reference(L, tx, ty, sx, sy, 0.0f);
                    ASSERT_NEAR(patch_distance(L, tx, ty, sx, sy, 0.0f), ref, 1e-5f * (1.0f + ref))
                        << "t " << tx << "," << ty << " s " << sx << "," << sy;
                    ++compared;
                }
            }
        }
    }
    EXPECT_GT(compared, 500);
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
    const std::vector<std::uint8_t> a = random_codes(4096, 9), b = random_codes(4096, 10);
    const std::vector<float> w = random_weights(256, 11);
    int tested = 0;
    std::set<SsdRowsFn> kernels;
    for (int64_t targets = hwy::SupportedTargets() & HWY_TARGETS; targets != 0;
         targets &= targets - 1) {
        const int64_t target = targets & -targets;
        hwy::SetSupportedTargetsForTest(target);
        // The kernel is resolved once and cached: resolve it again for this target (without
        // this every round would test the first target's kernel).
        set_simd_enabled(true);
        EXPECT_STREQ(simd_target_name(), hwy::TargetName(target));
        kernels.insert(detail::g_ssd_kernel.load());
        for (int row_bytes : {4, 9, 20, 45, 75, 80}) {
            const float scalar = ssd_rows_scalar(a.data(), 400, b.data(), 400, 5, row_bytes,
                                                 SsdWeights{w.data()}, 1e30f);
            EXPECT_NEAR(
                ssd_rows(a.data(), 400, b.data(), 400, 5, row_bytes, SsdWeights{w.data()}, 1e30f),
                scalar, 1e-5f * scalar)
                << hwy::TargetName(target) << " row_bytes=" << row_bytes;
        }
        ++tested;
    }
    hwy::SetSupportedTargetsForTest(0);
    set_simd_enabled(true);
    EXPECT_GE(tested, 1);
    // Each target ran its own kernel.
    EXPECT_EQ(kernels.size(), static_cast<std::size_t>(tested));
}

}  // namespace
}  // namespace exemplar::synth
