// The preview mode: half resolution, the buffers' 12 channels compressed by PCA to a few that
// keep most of the (weighted) variance, and distances in the kept space approximate the full
// weighted guide distance.

#include "exemplar/stylit/preview.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "exemplar/stylit/stylit.hpp"
#include "stylit_test_data.hpp"

namespace exemplar {
namespace {

using testing::load_example;

// The tests run on the bundled example shrunk to 300x228 (preview 150x114).
constexpr int kShrink = 2;

SynthesisInput example_input(int shrink) {
    SynthesisInput input;
    input.style = load_example("source_style.png", shrink);
    for (const char* name : {"fullgi", "dirdif", "dirspc", "indirb"}) {
        input.guides.push_back({name,
                                load_example(std::string("source_") + name + ".png", shrink),
                                load_example(std::string("target_") + name + ".png", shrink),
                                0.5f,
                                {}});
    }
    return input;
}

TEST(Preview, HalvesAndCompressesTheBuffersKeepingMostVariance) {
    const SynthesisInput full = example_input(2);  // 300x228
    auto preview = make_preview(full, 3);
    ASSERT_TRUE(preview.ok()) << preview.status().message();
    EXPECT_EQ(preview->channels_before, 12);
    EXPECT_EQ(preview->channels_after, 3);
    EXPECT_GT(preview->explained_variance, 0.9);  // measured 0.966 at 600x456
    ASSERT_EQ(preview->input.guides.size(), 1u);
    const GuidePair& guide = preview->input.guides.front();
    EXPECT_EQ(guide.source.channels(), 3);
    EXPECT_EQ(guide.source.width(), 150);
    EXPECT_EQ(guide.source.height(), 114);
    EXPECT_EQ(guide.target.width(), 150);
    EXPECT_EQ(preview->input.style.width(), 150);
    EXPECT_FLOAT_EQ(guide.weight, 1.0f);
    EXPECT_TRUE(validate_input(preview->input, SynthesisOptions{}).is_ok());

    // Weighted squared distance between two pixels: full channels vs the kept components.
    auto full_half = make_preview(full, 12);
    ASSERT_TRUE(full_half.ok());
    EXPECT_NEAR(full_half->explained_variance, 1.0, 1e-9);
    double full_sum = 0.0, kept_sum = 0.0;
    for (int x = 0; x + 7 < 150; x += 7) {
        const int y = 57;
        for (int c = 0; c < 12; ++c) {
            const double d = full_half->input.guides[0].source.at(x, y, c) -
                             full_half->input.guides[0].target.at(x + 7, y, c);
            full_sum += d * d;
        }
        for (int c = 0; c < 3; ++c) {
            const double d = guide.source.at(x, y, c) - guide.target.at(x + 7, y, c);
            kept_sum += d * d;
        }
    }
    EXPECT_GT(kept_sum, 0.8 * full_sum);
    EXPECT_LE(kept_sum, full_sum * (1.0 + 1e-6));
}

TEST(Preview, RejectsBadInput) {
    SynthesisInput none;
    none.style = Image(8, 8, 3);
    EXPECT_FALSE(make_preview(none, 3).ok());
    SynthesisInput input = example_input(8);
    EXPECT_FALSE(make_preview(input, 0).ok());
    input.target_mask = Image(75, 57, 1, 1.0f);
    EXPECT_FALSE(make_preview(input, 3).ok());
}

TEST(Preview, HalvesOddSizesByAveragingTheLastRowAndColumnWithThemselves) {
    SynthesisInput input;
    input.style = Image(5, 3, 1);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x) input.style.at(x, y, 0) = static_cast<float>(10 * y + x);
    input.guides.push_back({"g", input.style, input.style, 1.0f, {}});
    auto preview = make_preview(input, 1);
    ASSERT_TRUE(preview.ok()) << preview.status().message();
    const Image& half = preview->input.style;
    ASSERT_EQ(half.width(), 3);
    ASSERT_EQ(half.height(), 2);
    EXPECT_FLOAT_EQ(half.at(0, 0, 0), 5.5f);   // (0 + 1 + 10 + 11) / 4
    EXPECT_FLOAT_EQ(half.at(2, 0, 0), 9.0f);   // (4 + 4 + 14 + 14) / 4
    EXPECT_FLOAT_EQ(half.at(1, 1, 0), 22.5f);  // (22 + 23 + 22 + 23) / 4
    EXPECT_FLOAT_EQ(half.at(2, 1, 0), 24.0f);
}

TEST(Preview, EngineOptionsTradeTheErrorBudgetAndIterationsForSpeed) {
    SynthesisOptions full;
    full.patch_size = 7;
    full.seed = 42;
    const SynthesisOptions preview = preview_synthesis_options(full);
    EXPECT_EQ(preview.usage, UsageStrategy::None);
    EXPECT_EQ(preview.em_iterations, kPreviewEmIterations);
    EXPECT_EQ(preview.search_iterations, kPreviewSearchIterations);
    EXPECT_EQ(preview.patch_size, 7);
    EXPECT_EQ(preview.seed, 42u);
    EXPECT_EQ(preview.final_pass_iterations, full.final_pass_iterations);
    EXPECT_EQ(preview.finest_em_iterations, full.finest_em_iterations);
    EXPECT_TRUE(validate(preview).is_ok());

    // Other strategies and lower iteration counts are the user's choice and stay.
    full.usage = UsageStrategy::Uniform;
    full.em_iterations = 2;
    full.search_iterations = 1;
    const SynthesisOptions kept = preview_synthesis_options(full);
    EXPECT_EQ(kept.usage, UsageStrategy::Uniform);
    EXPECT_EQ(kept.em_iterations, 2);
    EXPECT_EQ(kept.search_iterations, 1);
}

Image mirrored(const Image& image) {
    Image out(image.width(), image.height(), image.channels());
    for (int y = 0; y < image.height(); ++y) {
        for (int x = 0; x < image.width(); ++x) {
            for (int c = 0; c < image.channels(); ++c)
                out.at(image.width() - 1 - x, y, c) = image.at(x, y, c);
        }
    }
    return out;
}

// The preview (half size, PCA buffers, nearest neighbours, fewer iterations) must look like the
// full result: the same colours in the same places, and about as much stroke texture.
TEST(Preview, LooksLikeTheFullResult) {
    std::vector<LpeBuffer> source, target;
    for (const char* name : {"fullgi", "dirdif", "dirspc", "indirb"}) {
        const std::string s = std::string("source_") + name + ".png";
        const std::string t = std::string("target_") + name + ".png";
        source.push_back({name, s, load_example(s, kShrink)});
        target.push_back({name, t, load_example(t, kShrink)});
    }
    const Image exemplar = load_example("source_style.png", kShrink);
    StylitOptions options;
    auto full = stylize_render(exemplar, source, target, options);
    ASSERT_TRUE(full.ok()) << full.status().message();
    options.preview = true;
    auto preview = stylize_render(exemplar, source, target, options);
    ASSERT_TRUE(preview.ok()) << preview.status().message();
    const Image& small = preview->synthesis.image;
    EXPECT_EQ(small.width(), full->synthesis.image.width() / 2);

    auto similarity = compare_preview(small, full->synthesis.image);
    ASSERT_TRUE(similarity.ok()) << similarity.status().message();
    // Scale of the colour difference: the full result against its mirror image has the same
    // colours and strokes, only in the wrong places.
    auto wrong = compare_preview(mirrored(small), full->synthesis.image);
    ASSERT_TRUE(wrong.ok());
    std::printf("preview vs full: colour difference %.4f (mirrored: %.4f), texture ratio %.3f\n",
                similarity->colour_difference, wrong->colour_difference, similarity->texture_ratio);
    // Measured 0.020 vs 0.075 mirrored here (0.026 vs 0.083 at 600x456; 0.033 at 1200x912 in
    // bench_stylit): a quarter of the mirror's, so strokes and shading sit where the full
    // result has them.
    EXPECT_LT(similarity->colour_difference, 0.4 * wrong->colour_difference);
    EXPECT_LT(similarity->colour_difference, 0.03);
    // Measured 0.82 here (0.92 at 600x456, 0.97 at 1200x912: the smaller the preview, the more
    // its 5x5 patches average). Washed out would be ~0.6 (plain averaging, docs/PERFORMANCE.md);
    // more than 1.3 would be noise the full result does not have.
    EXPECT_GT(similarity->texture_ratio, 0.7);
    EXPECT_LT(similarity->texture_ratio, 1.3);
}

TEST(Preview, CompareRejectsMismatchedImages) {
    EXPECT_FALSE(compare_preview(Image(4, 4, 3), Image(8, 8, 1)).ok());
    EXPECT_FALSE(compare_preview(Image(8, 8, 3), Image(4, 4, 3)).ok());
    EXPECT_FALSE(compare_preview(Image(4, 4, 3), Image(8, 8, 3), 0).ok());
    EXPECT_FALSE(compare_preview(Image(), Image(8, 8, 3)).ok());
    auto same = compare_preview(Image(4, 4, 3, 0.5f), Image(8, 8, 3, 0.5f));
    ASSERT_TRUE(same.ok());
    EXPECT_DOUBLE_EQ(same->colour_difference, 0.0);
}

}  // namespace
}  // namespace exemplar
