#include "vote.hpp"

#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "test_images.hpp"

namespace exemplar::synth {
namespace {

// A field mapping every pixel of a 20x20 target to the source shifted by (5, 3), all errors
// equal, with one stray match at (10, 10).
Nnf shifted_field_with_stray() {
    Nnf nnf(20, 20);
    for (int y = 0; y < 20; ++y) {
        for (int x = 0; x < 20; ++x) nnf.at(x, y) = Match{x + 5, y + 3, 0.0f, 0.5f};
    }
    nnf.at(10, 10) = Match{40, 2, 0.0f, 0.5f};
    return nnf;
}

// Coherence (Brushables eq. 6.8): inside a coherent region every patch of the 5x5 neighbourhood
// agrees (weight 25 x the error weight); the stray agrees only with itself, and its neighbours
// lose its vote. Without coherence, equal errors give equal weights. Thread counts agree.
TEST(VoteWeights, CoherenceCountsConsistentNeighbours) {
    const Nnf nnf = shifted_field_with_stray();
    const std::vector<float> plain = vote_weights(nnf, nullptr, 5, 0.0f, 1);
    const float error_weight = plain[0];
    EXPECT_NEAR(error_weight, 1.0f / 1.01f, 1e-6f);
    for (float w : plain) EXPECT_EQ(w, error_weight);
    const std::vector<float> coherent = vote_weights(nnf, nullptr, 5, 2.0f, 1);
    auto at = [&](int x, int y) {
        return coherent[static_cast<std::size_t>(y) * 20 + x] / error_weight;
    };
    EXPECT_NEAR(at(4, 4), 25.0f, 1e-4f);
    EXPECT_NEAR(at(10, 10), 1.0f, 1e-4f);   // the stray: only itself
    EXPECT_NEAR(at(11, 10), 24.0f, 1e-4f);  // its neighbours lose one vote
    EXPECT_NEAR(at(0, 0), 9.0f, 1e-4f);     // a corner sees 3x3 entries
    // A neighbour one pixel off counts exp(-1 / (2 sigma^2)).
    Nnf off = nnf;
    off.at(4, 5) = Match{4 + 5 + 1, 5 + 3, 0.0f, 0.5f};
    const std::vector<float> near = vote_weights(off, nullptr, 5, 2.0f, 1);
    EXPECT_NEAR(near[4 * 20 + 4] / error_weight, 24.0f + std::exp(-0.25f), 1e-4f);
    EXPECT_EQ(vote_weights(nnf, nullptr, 5, 2.0f, 2), coherent);
}

// The tabulated coherence weights against the reference, compared bit for bit: a field of
// pieces (coherent inside, matches one or a few pixels off and far apart across their borders),
// no-match and inactive entries (or no mask); unrotated (the SIMD kernel of coherence.hpp, rows
// of 41: whole vectors and a padded tail on every target), 32 steps and a few other angles, one
// angle per pixel (more than the tables hold); σ² of 0.5, 2 and 100 (wide tables); 3x3 and 5x5
// patches; 1 and 3 threads.
TEST(VoteWeights, TabulatedCoherenceEqualsReferenceExactly) {
    const int w = 41, h = 27;
    Nnf nnf(w, h);
    std::vector<std::uint8_t> active(static_cast<std::size_t>(w) * h, 1);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * w + x;
            const int piece = (x / 7 + y / 6 * 3) % 5;
            const int jitter = (x * 7 + y * 3) % 9 == 0 ? (x + y) % 3 - 1 : 0;
            const float error = 0.02f + 0.1f * static_cast<float>((x * 5 + y * 11) % 7);
            nnf[i] = Match{x + piece * 13 + jitter, y + piece * 4, 0.0f, error};
            if ((x * 3 + y * 5) % 37 == 0) nnf[i] = Match{-1, -1, 0.0f, 0.0f};
            active[i] = (x + 3 * y) % 19 == 0 ? 0 : 1;
        }
    }
    for (int rotation = 0; rotation < 3; ++rotation) {
        Nnf field = nnf;
        for (int y = 0; y < h && rotation > 0; ++y) {
            for (int x = 0; x < w; ++x) {
                const int piece = (x / 7 + y / 6 * 3) % 5;
                float& angle = field[static_cast<std::size_t>(y) * w + x].angle_rad;
                angle = rotation == 2 ? 0.001f * static_cast<float>(y * w + x) - 0.5f
                        : piece == 2  ? 0.7f + 0.01f * static_cast<float>(x % 3)
                                      : 6.28318531f * static_cast<float>(piece * 7 - 14) / 32.0f;
            }
        }
        for (float coherence : {0.5f, 2.0f, 100.0f}) {
            for (int patch_size : {3, 5}) {
                for (const std::uint8_t* mask : {static_cast<const std::uint8_t*>(active.data()),
                                                 static_cast<const std::uint8_t*>(nullptr)}) {
                    const std::vector<float> expected =
                        vote_weights_reference(field, mask, patch_size, coherence, 1);
                    // Every SIMD target this CPU supports.
                    for (int64_t targets = hwy::SupportedTargets() & HWY_TARGETS; targets != 0;
                         targets &= targets - 1) {
                        hwy::SetSupportedTargetsForTest(targets & -targets);
                        for (int threads : {1, 3}) {
                            EXPECT_EQ(vote_weights(field, mask, patch_size, coherence, threads),
                                      expected)
                                << "rotation " << rotation << ", sigma^2 " << coherence
                                << ", patch " << patch_size << ", " << threads << " threads, mask "
                                << (mask != nullptr) << ", " << hwy::TargetName(targets & -targets);
                        }
                    }
                    hwy::SetSupportedTargetsForTest(0);
                }
            }
        }
    }
}

// Colour histogram (Kopf et al. 2007, Brushables' w_h): a source half 0 and half 1 against a
// target that is all 0. Bin 0 holds density 16 in the source (half of 32 bins' worth) and 32 in
// the target, an excess of 16, so with strength k a 0-pixel weighs 1 / (1 + 16 k); the absent 1s
// keep weight 1. The histograms count only the given target pixels; thread counts agree.
TEST(VoteWeights, HistogramFavoursValuesTheTargetLacks) {
    Image source(8, 4, 1, 0.0f);
    for (int y = 0; y < 4; ++y) {
        for (int x = 4; x < 8; ++x) source.at(x, y, 0) = 1.0f;
    }
    Image target(6, 6, 1, 0.0f);
    const std::vector<float> w = histogram_weights(source, target, nullptr, 0.5f, 1);
    ASSERT_EQ(w.size(), 32u);
    EXPECT_NEAR(w[0], 1.0f / 9.0f, 1e-6f);  // 1 / (1 + 0.5 * 16)
    EXPECT_EQ(w[4], 1.0f);
    EXPECT_EQ(histogram_weights(source, target, nullptr, 0.5f, 2), w);
    // Only the marked target pixels count: marking just the half at 1 turns it around.
    for (int y = 0; y < 6; ++y) {
        for (int x = 3; x < 6; ++x) target.at(x, y, 0) = 1.0f;
    }
    std::vector<std::uint8_t> right(36, 0);
    for (int y = 0; y < 6; ++y) {
        for (int x = 3; x < 6; ++x) right[static_cast<std::size_t>(y) * 6 + x] = 1;
    }
    const std::vector<float> flipped = histogram_weights(source, target, right.data(), 0.5f, 1);
    EXPECT_EQ(flipped[0], 1.0f);
    EXPECT_NEAR(flipped[4], 1.0f / 9.0f, 1e-6f);
    // Matching histograms: no excess anywhere, every weight 1.
    for (float v : histogram_weights(source, target, nullptr, 3.0f, 1)) EXPECT_EQ(v, 1.0f);
}

// The source weights enter every vote that reads the pixel: a target pixel covered by patches
// reading 0s and 1s averages to the share of the 1s' weight.
TEST(Vote, SourceWeightsScaleEachCandidate) {
    Image source(2, 1, 1, 0.0f);
    source.at(1, 0, 0) = 1.0f;
    Nnf nnf(3, 1);
    nnf.at(0, 0) = Match{0, 0, 0.0f, 0.0f};
    nnf.at(1, 0) = Match{1, 0, 0.0f, 0.0f};
    nnf.at(2, 0) = Match{0, 0, 0.0f, 0.0f};
    VoteParams params;
    params.patch_size = 1;
    Image plain(3, 1, 1, 0.5f), weighted(3, 1, 1, 0.5f);
    vote(nnf, source, params, plain, 1);
    EXPECT_EQ(plain.at(1, 0, 0), 1.0f);
    const std::vector<float> weights{0.25f, 1.0f};
    params.patch_size = 3;
    params.clamp_source = true;
    vote(nnf, source, params, plain, 1);
    params.source_weights = weights;
    vote(nnf, source, params, weighted, 1);
    // Pixel 1 gathers the patches centred at 0, 1, 2: they read source 1, 1 and 0 (clamped
    // and shifted reads); unweighted 2/3, weighted (1 + 1) / (1 + 1 + 0.25).
    EXPECT_NEAR(plain.at(1, 0, 0), 2.0f / 3.0f, 1e-6f);
    EXPECT_NEAR(weighted.at(1, 0, 0), 2.0f / 2.25f, 1e-6f);
}

// Seam blending: a field of two pieces (columns < 12 read the source shifted by (5, 3), the rest
// by (30, 3)) with unequal errors. Pixels 11 and 12, where the central 3x3 patches disagree on the
// source pixel, take the plain average of the whole 5x5 patches over them; every other pixel keeps
// the narrow weighted vote, including pixels 9, 10, 13 and 14 whose whole patches straddle the
// seam. Whole-patch votes ignore the flag; thread counts agree.
TEST(Vote, BlendSeamsAveragesWholePatchesOnlyAcrossSeams) {
    Image source(64, 24, 1);
    for (int y = 0; y < 24; ++y) {
        for (int x = 0; x < 64; ++x) source.at(x, y, 0) = static_cast<float>((x * 7 + y * 13) % 17);
    }
    Nnf nnf(24, 16);
    for (int y = 0; y < 16; ++y) {
        for (int x = 0; x < 24; ++x) {
            nnf.at(x, y) = Match{x + (x < 12 ? 5 : 30), y + 3, 0.0f, 0.1f + 0.05f * ((x + y) % 5)};
        }
    }
    const std::vector<float> weights = vote_weights(nnf, nullptr, 5, 0.0f, 1);
    VoteParams params;
    params.patch_size = 5;
    params.clamp_source = true;
    Image whole_plain(24, 16, 1, 0.0f), narrow(24, 16, 1, 0.0f), blended(24, 16, 1, 0.0f);
    vote(nnf, source, params, whole_plain, 1);
    params.patch_weights = weights;
    params.footprint = 3;
    vote(nnf, source, params, narrow, 1);
    params.blend_seams = true;
    vote(nnf, source, params, blended, 1);
    int differing = 0;
    for (int y = 1; y < 15; ++y) {
        for (int x = 1; x < 23; ++x) {
            const bool seam = x == 11 || x == 12;
            const float expected = seam ? whole_plain.at(x, y, 0) : narrow.at(x, y, 0);
            EXPECT_EQ(blended.at(x, y, 0), expected) << x << "," << y;
            differing += blended.at(x, y, 0) != narrow.at(x, y, 0) ? 1 : 0;
        }
    }
    EXPECT_GT(differing, 14);  // the seam columns do change
    Image again(24, 16, 1, 0.0f);
    vote(nnf, source, params, again, 2);
    EXPECT_TRUE(std::ranges::equal(again.data(), blended.data()));
    // With whole patches voting there is no narrower footprint to fall back from.
    Image whole(24, 16, 1, 0.0f), whole_flagged(24, 16, 1, 0.0f);
    params.footprint = 0;
    params.blend_seams = false;
    vote(nnf, source, params, whole, 1);
    params.blend_seams = true;
    vote(nnf, source, params, whole_flagged, 1);
    EXPECT_TRUE(std::ranges::equal(whole.data(), whole_flagged.data()));
}

// The row-by-row vote against the per-pixel reference, compared bit for bit: a field of pieces
// with matches over the source border (clamped reads), no-match entries, inactive and fixed
// pixels, weighted and unweighted votes, narrow footprints with and without seam blending,
// 1, 3, 4 and 5 channels, 1 and 3 threads; unrotated and rotated fields (angles of 32 steps and
// a few others, as Brushables' fields, and one angle per pixel, more than the row vote's
// tables hold), with and without source weights.
TEST(Vote, RowVoteEqualsPerPixelReferenceExactly) {
    const int w = 37, h = 29, sw = 31, sh = 23;
    Nnf nnf(w, h);
    std::vector<std::uint8_t> active(static_cast<std::size_t>(w) * h, 1), fixed(active.size(), 0);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * w + x;
            const int piece = (x / 6 + y / 5 * 3) % 7;
            const float error = 0.01f + 0.3f * static_cast<float>((x * 13 + y * 7) % 11);
            nnf[i] = Match{(x + piece * 5) % sw, (y + piece * 3) % sh, 0.0f, error};
            if ((x * 5 + y * 3) % 41 == 0) nnf[i] = Match{-1, -1, 0.0f, 0.0f};
            active[i] = (x + 2 * y) % 17 == 0 ? 0 : 1;
            fixed[i] = (x * 3 + y) % 23 == 0 ? 1 : 0;
        }
    }
    // Entire pieces without a patch centre, so the narrow footprint falls back to whole patches.
    for (int y = 10; y < 14; ++y) {
        for (int x = 20; x < 24; ++x) nnf[static_cast<std::size_t>(y) * w + x].x = -1;
    }
    std::vector<float> source_weights(static_cast<std::size_t>(sw) * sh);
    for (std::size_t i = 0; i < source_weights.size(); ++i) {
        source_weights[i] = 0.25f + 0.05f * static_cast<float>((i * 7) % 13);
    }
    // Rotations: none; per piece one of 32 steps or, in a few pieces, another angle; a
    // different angle per pixel.
    auto turn = [&](Nnf field, int rotation) {
        for (int y = 0; y < h && rotation > 0; ++y) {
            for (int x = 0; x < w; ++x) {
                const int piece = (x / 6 + y / 5 * 3) % 7;
                float& angle = field[static_cast<std::size_t>(y) * w + x].angle_rad;
                if (rotation == 1) {
                    angle = piece == 3 ? 0.3f + 0.1f * static_cast<float>(x % 2)
                                       : 6.28318531f * static_cast<float>(piece * 5 - 16) / 32.0f;
                } else {
                    angle = 0.001f * static_cast<float>(y * w + x) - 0.5f;
                }
            }
        }
        return field;
    };
    for (int channels : {1, 3, 4, 5}) {
        const Image source = testing::texture(sw, sh, channels, 40 + channels);
        const std::vector<float> weights = vote_weights(nnf, active.data(), 5, 0.0f, 1);
        for (int variant = 0; variant < 8; ++variant) {
            VoteParams params;
            params.patch_size = variant == 7 ? 7 : 5;
            params.clamp_source = variant != 1;
            params.active = variant == 2 ? nullptr : active.data();
            params.fixed = variant % 2 == 0 ? fixed.data() : nullptr;
            if (variant >= 3) params.patch_weights = weights;
            if (variant >= 4) params.footprint = variant == 4 ? 1 : 3;
            params.blend_seams = variant == 6 || variant == 7;
            Nnf field = nnf;
            if (variant == 1) {  // without clamping, matches keep their patches inside
                for (Match& m : field.matches()) {
                    if (m.x >= 0) m = Match{std::clamp(m.x, 5, sw - 6), std::clamp(m.y, 5, sh - 6)};
                }
            }
            for (int rotation = 0; rotation < 3; ++rotation) {
                const Nnf turned = turn(field, rotation);
                for (bool weighted : {false, true}) {
                    params.source_weights = {};
                    if (weighted) params.source_weights = source_weights;
                    Image expected(w, h, channels, 0.25f);
                    vote_reference(turned, source, params, expected, 1);
                    for (int threads : {1, 3}) {
                        Image fast(w, h, channels, 0.25f);
                        vote(turned, source, params, fast, threads);
                        ASSERT_TRUE(std::ranges::equal(fast.data(), expected.data()))
                            << channels << " channels, variant " << variant << ", rotation "
                            << rotation << (weighted ? ", source weights, " : ", ") << threads
                            << " threads";
                    }
                }
            }
        }
    }
}

}  // namespace
}  // namespace exemplar::synth
