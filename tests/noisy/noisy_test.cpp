// The per-frame synthesis of Color Me Noisy: level schedule, low-pass, options, determinism and
// input errors.

#include "exemplar/noisy/noisy.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <utility>

#include "procedural.hpp"

namespace exemplar::noisy {
namespace {

TEST(NoisySchedule, GoesFromTheStrengthToOneAtTheChaptersRatio) {
    const std::vector<double> s = level_strengths(8.0, 0.85);
    ASSERT_GE(s.size(), 2u);
    EXPECT_DOUBLE_EQ(s.front(), 8.0);
    EXPECT_DOUBLE_EQ(s.back(), 1.0);
    for (std::size_t i = 1; i < s.size(); ++i) {
        EXPECT_GE(s[i] / s[i - 1], 0.85 - 1e-12);
        EXPECT_LT(s[i], s[i - 1]);
    }
    // The fewest levels: one step fewer would need a ratio below 0.85.
    EXPECT_LT(std::pow(1.0 / 8.0, 1.0 / (static_cast<double>(s.size()) - 2.0)), 0.85);
    EXPECT_EQ(s.size(), 14u);  // 1 + ceil(ln 8 / ln(1/0.85)) = 1 + 13
    EXPECT_EQ(level_strengths(1.0, 0.85), std::vector<double>{1.0});
    EXPECT_EQ(level_strengths(0.0, 0.85), std::vector<double>{1.0});
    EXPECT_EQ(level_strengths(1.1, 0.85).size(), 2u);
}

TEST(NoisyLowPass, AveragesBoxesOfTheStrengthsWidth) {
    Image image(8, 4, 1);
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 8; ++x) image.at(x, y, 0) = static_cast<float>(x / 2 + 10 * (y / 2));
    }
    const Image low = low_pass(image, 2.0, LowPassFilter::Box, 1);
    ASSERT_EQ(low.width(), 4);
    ASSERT_EQ(low.height(), 2);
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 4; ++x) EXPECT_FLOAT_EQ(low.at(x, y, 0), x + 10.0f * y);
    }
    EXPECT_EQ(low_pass(image, 1.0, LowPassFilter::Lanczos3, 1).width(), 8);
    EXPECT_EQ(low_pass(image, 3.0, LowPassFilter::Lanczos3, 1).width(), 3);
}

TEST(NoisyOptions, DefaultsAreTheChaptersAndRangesAreChecked) {
    const NoisyOptions defaults;
    EXPECT_EQ(defaults.patch_size, 7);
    EXPECT_EQ(defaults.em_iterations, 4);
    EXPECT_EQ(defaults.search_iterations, 8);
    EXPECT_FLOAT_EQ(defaults.level_ratio, 0.85f);
    EXPECT_FLOAT_EQ(defaults.lattice_spacing_px, 50.0f);
    EXPECT_FLOAT_EQ(defaults.min_offset_px, 15.0f);
    EXPECT_FLOAT_EQ(defaults.max_offset_px, 25.0f);
    EXPECT_EQ(defaults.filter, LowPassFilter::Box);
    EXPECT_FLOAT_EQ(defaults.coarse_weight, 0.5f);  // ours (docs/noisy.md); 0 = the chapter's
    // Ours (docs/noisy.md, "Speed"); warm-search-iterations 0 = the chapter's schedule.
    EXPECT_EQ(defaults.warm_search_iterations, 2);
    EXPECT_EQ(defaults.warm_em_iterations, 1);
    EXPECT_TRUE(validate(defaults).ok());

    NoisyOptions options;
    const Status bad_noise = set_option(options, *find_noisy_option("noise"), -1.0);
    EXPECT_EQ(bad_noise.message(), "noise: -1 is invalid (must be 0..256)");
    const Status even = set_option(options, *find_noisy_option("patch_size"), 6.0);
    EXPECT_EQ(even.message(), "patch-size: 6 is invalid (must be odd, 3..31)");
    const Status bad_weight = set_option(options, *find_noisy_option("coarse-weight"), -0.5);
    EXPECT_EQ(bad_weight.message(), "coarse-weight: -0.5 is invalid (must be 0..100)");
    EXPECT_EQ(set_option(options, *find_noisy_option("warm-search-iterations"), -1.0).message(),
              "warm-search-iterations: -1 is invalid (must be an integer, 0..100)");
    EXPECT_EQ(set_option(options, *find_noisy_option("warm_em_iterations"), 0.0).message(),
              "warm-em-iterations: 0 is invalid (must be an integer, 1..100)");
    EXPECT_EQ(set_option(options, *find_noisy_option("warm-em-iterations"), 1.5).message(),
              "warm-em-iterations: 1.5 is invalid (must be an integer, 1..100)");
    options.min_offset_px = 30.0f;
    EXPECT_EQ(validate(options).message(),
              "min-offset: 30 is invalid (must be at most max-offset, 25)");
    EXPECT_EQ(parse_low_pass_filter("gauss").status().message(),
              "filter: 'gauss' is invalid (must be one of box, lanczos3)");
    EXPECT_EQ(parse_low_pass_filter("lanczos3").value(), LowPassFilter::Lanczos3);
    EXPECT_EQ(find_noisy_option("nope"), nullptr);
}

struct Fixture {
    Image source = testing::medium(128, 128);
    NoisyFrame frame{testing::cel(64, 64, 30, 28, 16), {}, {}, {}};
};

bool identical(const Image& a, const Image& b) {
    return a.same_size(b) && a.channels() == b.channels() &&
           std::equal(a.data().begin(), a.data().end(), b.data().begin());
}

TEST(NoisyFrame, IsAPureFunctionOfSeedAndFrameForAnyThreadCount) {
    const Fixture in;
    NoisyOptions options;
    options.noise = 6.0f;
    const auto start = std::chrono::steady_clock::now();
    const Result<Image> one = synthesize_frame(in.source, in.frame, options, 3, RunContext(1));
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("64x64 frame, 128x128 source, f = 6, one thread: %.3f s\n", seconds);
    ASSERT_TRUE(one.ok()) << one.status().message();
    EXPECT_EQ(one.value().width(), 64);
    EXPECT_EQ(one.value().height(), 64);
    EXPECT_EQ(one.value().channels(), 3);
    const Result<Image> many = synthesize_frame(in.source, in.frame, options, 3, RunContext(2));
    ASSERT_TRUE(many.ok());
    EXPECT_TRUE(identical(one.value(), many.value()));
    // Another frame, or another seed, gives another image.
    const Result<Image> next = synthesize_frame(in.source, in.frame, options, 4, RunContext(2));
    EXPECT_FALSE(identical(one.value(), next.value()));
    options.seed = 2;
    const Result<Image> reseeded = synthesize_frame(in.source, in.frame, options, 3, RunContext(2));
    EXPECT_FALSE(identical(one.value(), reseeded.value()));
}

TEST(NoisyFrame, EverySchedulesFrameIsTheSameForAnyThreadCount) {
    // The chapter's schedule (a random field on every level), and the default warm schedule
    // with a noise map, where pixels start on different levels (such levels run the full
    // schedule from the carried field).
    const Fixture in;
    NoisyOptions chapter;
    chapter.noise = 4.0f;
    chapter.warm_search_iterations = 0;
    NoisyFrame mapped = in.frame;
    mapped.noise_map = Image(64, 64, 1, 1.0f);
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 40; ++x) mapped.noise_map.at(x, y, 0) = x < 20 ? 0.0f : 0.5f;
    }
    NoisyOptions warm;
    warm.noise = 4.0f;
    for (const auto& [frame, options] : {std::pair{in.frame, chapter}, std::pair{mapped, warm}}) {
        const Result<Image> one = synthesize_frame(in.source, frame, options, 5, RunContext(1));
        ASSERT_TRUE(one.ok()) << one.status().message();
        const Result<Image> many = synthesize_frame(in.source, frame, options, 5, RunContext(2));
        ASSERT_TRUE(many.ok());
        EXPECT_TRUE(identical(one.value(), many.value()));
    }
}

// Mean over the frame's interior pixels of the distance (mean squared difference per channel)
// from its 5x5 patch to the nearest 5x5 patch of `source`, by brute force: fine consistency,
// eq. 4.1.
double nearest_patch_distance(const Image& frame, const Image& source) {
    constexpr int r = 2;
    double total = 0.0;
    long count = 0;
    for (int ty = r; ty < frame.height() - r; ++ty) {
        for (int tx = r; tx < frame.width() - r; ++tx) {
            double best = 1e30;
            for (int sy = r; sy < source.height() - r; ++sy) {
                for (int sx = r; sx < source.width() - r; ++sx) {
                    double d = 0.0;
                    for (int dy = -r; dy <= r && d < best; ++dy) {
                        const float* a = frame.pixel(tx - r, ty + dy);
                        const float* b = source.pixel(sx - r, sy + dy);
                        for (int i = 0; i < (2 * r + 1) * frame.channels(); ++i) {
                            d += (a[i] - b[i]) * (a[i] - b[i]);
                        }
                    }
                    best = std::min(best, d);
                }
            }
            total += best / ((2 * r + 1) * (2 * r + 1) * frame.channels());
            ++count;
        }
    }
    return total / static_cast<double>(count);
}

TEST(NoisyFrame, WarmLevelsKeepTheChaptersFineConsistency) {
    // The default schedule runs 1 EM iteration of 2 PatchMatch iterations on the levels after
    // the coarsest, starting from the level before's field. Its frames are as close to the
    // medium, patch by patch (eq. 4.1), as those of the chapter's 4 x 8 iterations from a random
    // field on every level (measured 1.12e-3 vs 1.17e-3). No pre-deformation here, so the
    // medium itself is the source the patches come from.
    const Image source = testing::medium(64, 64);
    const Image reference = testing::cel(40, 40, 18, 16, 10);
    NoisyOptions options;
    options.noise = 2.0f;
    options.patch_size = 5;
    options.min_offset_px = options.max_offset_px = 0.0f;
    auto distance = [&](const NoisyOptions& o) {
        double sum = 0.0;
        for (int i = 0; i < 3; ++i) {
            const Result<Image> frame =
                synthesize_frame(source, NoisyFrame{reference, {}, {}, {}}, o, i, RunContext(2));
            EXPECT_TRUE(frame.ok());
            sum += nearest_patch_distance(frame.value(), source) / 3.0;
        }
        return sum;
    };
    const double warm = distance(options);
    NoisyOptions chapter = options;
    chapter.warm_search_iterations = 0;
    const double full = distance(chapter);
    std::printf("nearest-patch distance: warm %.3e, chapter %.3e\n", warm, full);
    EXPECT_LT(warm, 1.15 * full);
}

TEST(NoisyFrame, RejectsBadInputsWithOneLineMessages) {
    const Fixture in;
    NoisyOptions options;
    options.noise = 10.0f;
    EXPECT_EQ(synthesize_frame(in.source, in.frame, options, 0).status().message(),
              "noise: 10 is too strong for the 64x64 reference and the 128x128 source with "
              "patch-size 7 (at most 9.14)");
    options.noise = 4.0f;
    NoisyFrame wrong = in.frame;
    wrong.noise_map = Image(32, 32, 1, 0.5f);
    EXPECT_EQ(synthesize_frame(in.source, wrong, options, 0).status().message(),
              "noise map: is 32x32 with 1 channels (must be 1 channel, 64x64 like the "
              "reference)");
    wrong.noise_map = Image(64, 64, 1, 1.5f);
    EXPECT_EQ(synthesize_frame(in.source, wrong, options, 0).status().message(),
              "noise map: value 1.5 is invalid (must be 0..1)");
    wrong = in.frame;
    wrong.reference = Image(64, 64, 5);
    EXPECT_EQ(synthesize_frame(in.source, wrong, options, 0).status().message(),
              "reference: has 5 channels but the source has 3 (give grey, RGB or RGBA frames "
              "for an RGB or RGBA source)");
    EXPECT_EQ(synthesize_frame(Image(), in.frame, options, 0).status().message(),
              "source: is empty");
    options.patch_size = 4;
    EXPECT_EQ(synthesize_frame(in.source, in.frame, options, 0).status().message(),
              "patch-size: 4 is invalid (must be odd, 3..31)");
}

TEST(NoisyFrame, GreyAndRgbaReferencesAreConverted) {
    const Fixture in;
    NoisyOptions options;
    options.noise = 2.0f;
    Image grey(64, 64, 1, 0.6f);
    const Result<Image> out =
        synthesize_frame(in.source, NoisyFrame{grey, {}, {}, {}}, options, 0, {});
    ASSERT_TRUE(out.ok()) << out.status().message();
    EXPECT_EQ(out.value().channels(), 3);
}

TEST(NoisyFrame, OrientationFieldsRotatePatchesDeterministically) {
    const Fixture in;
    NoisyOptions options;
    options.noise = 3.0f;
    NoisyFrame oriented = in.frame;
    oriented.orientation = Image(64, 64, 1, 1.5707964f);  // strokes turned by 90 degrees
    const Image source_orientation(128, 128, 1, 0.0f);
    const Result<Image> one =
        synthesize_frame(in.source, source_orientation, oriented, options, 2, RunContext(1));
    ASSERT_TRUE(one.ok()) << one.status().message();
    const Result<Image> many =
        synthesize_frame(in.source, source_orientation, oriented, options, 2, RunContext(2));
    ASSERT_TRUE(many.ok());
    EXPECT_TRUE(identical(one.value(), many.value()));
    const Result<Image> plain = synthesize_frame(in.source, in.frame, options, 2, RunContext(2));
    ASSERT_TRUE(plain.ok());
    EXPECT_FALSE(identical(one.value(), plain.value()));

    EXPECT_EQ(synthesize_frame(in.source, oriented, options, 0).status().message(),
              "orientation: give both the source's and the frame's orientation field, or neither");
    EXPECT_EQ(
        synthesize_frame(in.source, Image(64, 64, 1), oriented, options, 0).status().message(),
        "source orientation: is 64x64 with 1 channels (must be 1 channel, 128x128 like the "
        "source)");
    options.noise = 6.5f;
    EXPECT_EQ(
        synthesize_frame(in.source, source_orientation, oriented, options, 0).status().message(),
        "noise: 6.5 is too strong for the 64x64 reference and the 128x128 source with "
        "patch-size 7 and rotated patches (at most 5.81)");
}

}  // namespace
}  // namespace exemplar::noisy
