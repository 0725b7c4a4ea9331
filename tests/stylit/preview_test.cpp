// The preview mode: half resolution, the buffers' 12 channels compressed by PCA to a few that
// keep most of the (weighted) variance, and distances in the kept space approximate the full
// weighted guide distance.

#include "exemplar/stylit/preview.hpp"

#include <gtest/gtest.h>

#include "stylit_test_data.hpp"

namespace exemplar {
namespace {

using testing::load_example;

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

}  // namespace
}  // namespace exemplar
