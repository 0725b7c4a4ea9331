// Pattern preprocessing: CLAHE, features, PCA appearance space, Gaussian stack.
#include "exemplar/npr/pattern.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "npr_patterns.hpp"

namespace exemplar::npr {
namespace {

float mean_of(const Image& image, int channel = 0) {
    double sum = 0.0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) sum += image.at(x, y, channel);
    return static_cast<float>(sum / static_cast<double>(image.pixel_count()));
}

float variance_of(const Image& image, int channel = 0) {
    const float m = mean_of(image, channel);
    double sum = 0.0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const double d = image.at(x, y, channel) - m;
            sum += d * d;
        }
    return static_cast<float>(sum / static_cast<double>(image.pixel_count()));
}

TEST(NprPattern, ClaheFlattensTheHistogramOfALowContrastPattern) {
    // A low-contrast halftone screen: values in [0.4, 0.6]
    Image pattern = testing::halftone_pattern(128, 16);
    for (float& v : pattern.data()) v = 0.4f + 0.2f * v;
    const PatternOptions defaults;
    const Image equalized =
        equalize_clahe(pattern, defaults.clahe_clip_limit, defaults.clahe_tiles).value();
    // Fraction of pixels per quarter of the range: far from flat before, close to flat after
    const auto quarters = [](const Image& image) {
        std::array<int, 4> bins{};
        for (float v : image.data())
            ++bins[static_cast<std::size_t>(std::clamp(v, 0.0f, 0.999f) * 4)];
        return bins;
    };
    const auto before = quarters(pattern), after = quarters(equalized);
    const int n = static_cast<int>(pattern.pixel_count());
    EXPECT_EQ(before[0] + before[3], 0);  // nothing below 0.25 or above 0.75
    for (int b = 0; b < 4; ++b) {
        EXPECT_GT(after[static_cast<std::size_t>(b)], n / 8) << "quarter " << b;
        EXPECT_LT(after[static_cast<std::size_t>(b)], n * 3 / 8) << "quarter " << b;
    }
    EXPECT_GT(variance_of(equalized), 4.0f * variance_of(pattern));
}

TEST(NprPattern, FeaturesAppearanceSpaceAndStackHaveTheRequestedShape) {
    const Image pattern = testing::stipple_pattern(64, 6.0f);
    PatternOptions options;
    options.edge_distance = options.gradients = options.structure_tensor = true;
    options.appearance_dims = 6;
    options.levels = 3;
    const Result<Pattern> prepared = prepare_pattern(pattern, options, 0, 2);
    ASSERT_TRUE(prepared.ok()) << prepared.status().message();
    EXPECT_EQ(prepared->features.channels(), 1 + 1 + 2 + 3);
    EXPECT_EQ(prepared->screen.channels(), 1);
    ASSERT_EQ(prepared->stack.size(), 3u);
    for (const Image& level : prepared->stack) {
        EXPECT_EQ(level.width(), 64);
        EXPECT_EQ(level.height(), 64);
        EXPECT_EQ(level.channels(), 6);
    }
    EXPECT_GT(prepared->explained_variance, 0.5f);
    EXPECT_LE(prepared->explained_variance, 1.0f);
    // PCA components: zero mean, decreasing variance
    const Image& sharp = prepared->stack[0];
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(mean_of(sharp, k), 0.0f, 0.02f) << "component " << k;
    for (int k = 1; k < 6; ++k)
        EXPECT_GE(variance_of(sharp, k - 1) * 1.05f, variance_of(sharp, k)) << "component " << k;
    // The stack blurs: each level has less variance in its first component
    EXPECT_LT(variance_of(prepared->stack[1], 0), variance_of(prepared->stack[0], 0));
    EXPECT_LT(variance_of(prepared->stack[2], 0), variance_of(prepared->stack[1], 0));
}

TEST(NprPattern, EdgeDistanceIsZeroOnEdgesAndSobelSeesAStep) {
    // Left half black, right half white (wraps: two vertical edges)
    Image pattern(32, 32, 1, 1.0f);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 16; ++x) pattern.at(x, y, 0) = 0.0f;
    PatternOptions options;
    options.equalize = false;
    options.edge_distance = options.gradients = true;
    const Result<Pattern> prepared = prepare_pattern(pattern, options, 0, 1);
    ASSERT_TRUE(prepared.ok()) << prepared.status().message();
    const Image& f = prepared->features;  // grey, distance, dx, dy
    ASSERT_EQ(f.channels(), 4);
    float min_near_edge = 1.0f;
    for (int x = 14; x <= 17; ++x) min_near_edge = std::min(min_near_edge, f.at(x, 10, 1));
    EXPECT_EQ(min_near_edge, 0.0f);
    EXPECT_GT(f.at(8, 10, 1), 0.2f);  // far from both edges
    EXPECT_GT(std::fabs(f.at(15, 10, 2)) + std::fabs(f.at(16, 10, 2)), 0.2f);
    EXPECT_EQ(f.at(15, 10, 3), 0.0f);
}

TEST(NprPattern, IsBitIdenticalForOneAndTwoThreads) {
    const Image pattern = testing::hatching_pattern(64, 8, 2.0f);
    PatternOptions options;
    options.structure_tensor = true;
    const Result<Pattern> one = prepare_pattern(pattern, options, 0, 1);
    const Result<Pattern> two = prepare_pattern(pattern, options, 0, 2);
    ASSERT_TRUE(one.ok() && two.ok());
    for (std::size_t l = 0; l < one->stack.size(); ++l)
        EXPECT_TRUE(std::equal(one->stack[l].data().begin(), one->stack[l].data().end(),
                               two->stack[l].data().begin()))
            << "level " << l;
}

TEST(NprPattern, RejectsBadOptionsAndTooSmallPatternsByName) {
    const Image pattern = testing::halftone_pattern(16, 8);
    PatternOptions options;
    options.appearance_dims = 9;
    Result<Pattern> bad = prepare_pattern(pattern, options);
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.status().message(), "appearance_dims: 9 is invalid (must be 1..8)");
    options = {};
    options.levels = 0;
    EXPECT_FALSE(prepare_pattern(pattern, options).ok());
    options = {};
    const Result<Pattern> small = prepare_pattern(pattern, options, 24);
    ASSERT_FALSE(small.ok());
    EXPECT_EQ(small.status().code(), ErrorCode::InvalidArgument);
    EXPECT_NE(small.status().message().find("16x16 is too small"), std::string::npos)
        << small.status().message();
}

}  // namespace
}  // namespace exemplar::npr
