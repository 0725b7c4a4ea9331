#include "exemplar/filters/resample.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <set>
#include <vector>

#include "exemplar/core/rng.hpp"

namespace exemplar {
namespace {

constexpr ResampleFilter kAllFilters[] = {ResampleFilter::Box, ResampleFilter::Gaussian,
                                          ResampleFilter::Lanczos3, ResampleFilter::Nearest};

Image random_image(int width, int height, int channels, std::uint64_t seed) {
    Image im(width, height, channels);
    KeyedRng rng(seed);
    for (float& v : im.data()) v = rng.uniform();
    return im;
}

bool identical(const Image& a, const Image& b) {
    return a.width() == b.width() && a.height() == b.height() && a.channels() == b.channels() &&
           std::memcmp(a.data().data(), b.data().data(), a.size() * sizeof(float)) == 0;
}

double mean(const Image& im) {
    double sum = 0.0;
    for (float v : im.data()) sum += v;
    return sum / static_cast<double>(im.size());
}

TEST(Resize, ConstantImageStaysConstantForEveryFilterAndSize) {
    const Image constant(23, 17, 3, 0.7f);
    const int sizes[][2] = {{11, 8}, {7, 16}, {46, 34}, {1, 1}, {23, 5}, {40, 17}, {19, 13}};
    for (ResampleFilter filter : kAllFilters) {
        for (const auto& size : sizes) {
            const Image out = resize(constant, size[0], size[1], filter, 1);
            ASSERT_EQ(out.width(), size[0]);
            ASSERT_EQ(out.height(), size[1]);
            ASSERT_EQ(out.channels(), 3);
            for (float v : out.data()) {
                ASSERT_FLOAT_EQ(v, 0.7f)
                    << "filter " << static_cast<int>(filter) << " to " << size[0] << "x" << size[1];
            }
        }
    }
}

TEST(Resize, SameSizeIsTheIdentity) {
    Image im = random_image(19, 12, 4, 1);
    im.set_channel_names({"a", "b", "c", "d"});
    for (ResampleFilter filter : kAllFilters) {
        const Image out = resize(im, 19, 12, filter, 1);
        EXPECT_TRUE(identical(im, out)) << static_cast<int>(filter);
        EXPECT_EQ(out.channel_names(), im.channel_names());
    }
}

TEST(Resize, BoxHalvesCheckerboardToMidGray) {
    Image checker(16, 10, 1);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 16; ++x) checker.at(x, y, 0) = static_cast<float>((x + y) % 2);
    const Image out = resize(checker, 8, 5, ResampleFilter::Box, 1);
    for (float v : out.data()) EXPECT_FLOAT_EQ(v, 0.5f);
}

TEST(Resize, BoxIsTheAreaAverageForNonIntegerRatios) {
    // 3 -> 2 pixels: footprints [0, 1.5) and [1.5, 3).
    Image row(3, 1, 1);
    row.at(0, 0, 0) = 0.0f;
    row.at(1, 0, 0) = 1.0f;
    row.at(2, 0, 0) = 4.0f;
    const Image out = resize(row, 2, 1, ResampleFilter::Box, 1);
    EXPECT_FLOAT_EQ(out.at(0, 0, 0), (0.0f + 0.5f * 1.0f) / 1.5f);
    EXPECT_FLOAT_EQ(out.at(1, 0, 0), (0.5f * 1.0f + 4.0f) / 1.5f);
}

TEST(Resize, SmoothFiltersRemoveCheckerboardWhenHalving) {
    // A checkerboard is pure Nyquist frequency: a prefiltering downsampler must flatten it, while
    // point sampling would alias it into a solid colour.
    Image checker(32, 32, 1);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) checker.at(x, y, 0) = static_cast<float>((x + y) % 2);
    for (ResampleFilter filter : {ResampleFilter::Gaussian, ResampleFilter::Lanczos3}) {
        const Image out = resize(checker, 16, 16, filter, 1);
        for (int y = 2; y < 14; ++y)
            for (int x = 2; x < 14; ++x) {
                EXPECT_NEAR(out.at(x, y, 0), 0.5f, 0.02f) << static_cast<int>(filter);
            }
    }
}

TEST(Resize, NearestReturnsExactInputLabels) {
    Image labels(13, 9, 1);
    KeyedRng rng(7);
    for (float& v : labels.data()) v = static_cast<float>(rng.below(6)) * 1.25f;
    const std::set<float> allowed(labels.data().begin(), labels.data().end());
    const int sizes[][2] = {{5, 4}, {26, 18}, {31, 7}, {13, 9}, {1, 1}};
    for (const auto& size : sizes) {
        const Image out = resize(labels, size[0], size[1], ResampleFilter::Nearest, 1);
        for (int y = 0; y < out.height(); ++y)
            for (int x = 0; x < out.width(); ++x) {
                const float v = out.at(x, y, 0);
                EXPECT_TRUE(allowed.count(v) == 1) << v;
                // Point sampling of the input pixel under the output pixel's centre.
                const int sx = (2 * x + 1) * labels.width() / (2 * out.width());
                const int sy = (2 * y + 1) * labels.height() / (2 * out.height());
                EXPECT_EQ(v, labels.at(sx, sy, 0));
            }
    }
    // Doubling repeats every pixel 2x2.
    const Image doubled = resize(labels, 26, 18, ResampleFilter::Nearest, 1);
    for (int y = 0; y < 18; ++y)
        for (int x = 0; x < 26; ++x) EXPECT_EQ(doubled.at(x, y, 0), labels.at(x / 2, y / 2, 0));
}

TEST(Resize, ResultsDoNotDependOnThreadCount) {
    const Image im = random_image(57, 41, 3, 3);
    for (ResampleFilter filter : kAllFilters) {
        for (const auto& size : {std::pair{23, 30}, std::pair{101, 77}}) {
            const Image one = resize(im, size.first, size.second, filter, 1);
            const Image two = resize(im, size.first, size.second, filter, 2);
            const Image all = resize(im, size.first, size.second, filter, 0);
            EXPECT_TRUE(identical(one, two)) << static_cast<int>(filter);
            EXPECT_TRUE(identical(one, all)) << static_cast<int>(filter);
        }
    }
}

TEST(Resize, EmptyImageGivesEmptyImage) {
    EXPECT_TRUE(resize(Image(), 4, 4, ResampleFilter::Gaussian, 1).empty());
}

TEST(GaussianBlur, PreservesMeanAwayFromBorders) {
    // Content sits more than 3 sigma from the borders, so clamping never changes the sum.
    Image im(40, 30, 2, 0.25f);
    KeyedRng rng(11);
    for (int y = 12; y < 18; ++y)
        for (int x = 12; x < 28; ++x)
            for (int c = 0; c < 2; ++c) im.at(x, y, c) = rng.uniform();
    const Image blurred = gaussian_blur(im, 2.0f, 1);
    ASSERT_TRUE(blurred.same_size(im));
    EXPECT_NEAR(mean(blurred), mean(im), 1e-6);
    // It does blur: the spread of values shrinks.
    float lo = 1.0f;
    float hi = 0.0f;
    for (float v : blurred.data()) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    EXPECT_LT(hi - lo, 0.5f);
}

TEST(GaussianBlur, ConstantStaysConstantAndZeroSigmaIsIdentity) {
    const Image constant(9, 7, 3, 0.3f);
    const Image blurred = gaussian_blur(constant, 5.0f, 1);  // sigma wider than the image
    for (float v : blurred.data()) EXPECT_FLOAT_EQ(v, 0.3f);
    const Image im = random_image(9, 7, 3, 5);
    EXPECT_TRUE(identical(gaussian_blur(im, 0.0f, 1), im));
}

TEST(GaussianBlur, ResultsDoNotDependOnThreadCount) {
    const Image im = random_image(64, 48, 3, 9);
    EXPECT_TRUE(identical(gaussian_blur(im, 1.7f, 1), gaussian_blur(im, 1.7f, 2)));
}

TEST(Pyramid, LevelSizes) {
    EXPECT_EQ(pyramid_level_size(1200, 0.5f, 0), 1200);
    EXPECT_EQ(pyramid_level_size(1200, 0.5f, 1), 600);
    EXPECT_EQ(pyramid_level_size(912, 0.5f, 4), 57);
    EXPECT_EQ(pyramid_level_size(1200, 0.5f, 5), 38);  // 37.5 rounds up
    EXPECT_EQ(pyramid_level_size(912, 0.5f, 5), 29);   // 28.5 rounds up
    EXPECT_EQ(pyramid_level_size(100, 0.85f, 1), 85);
    EXPECT_EQ(pyramid_level_size(100, 0.85f, 2), 72);  // 72.25
    EXPECT_EQ(pyramid_level_size(100, 0.85f, 3), 61);  // 61.41
    EXPECT_EQ(pyramid_level_size(60, 0.85f, 3), 37);   // 36.85
    EXPECT_EQ(pyramid_level_size(7, 0.5f, 10), 1);     // never below one pixel
}

TEST(Pyramid, LevelsHaveTheDocumentedSizes) {
    const Image im = random_image(100, 60, 3, 13);
    for (float ratio : {0.5f, 0.85f}) {
        const std::vector<Image> pyramid = gaussian_pyramid(im, 5, ratio);
        ASSERT_EQ(pyramid.size(), 5u);
        EXPECT_TRUE(identical(pyramid[0], im));
        for (int level = 0; level < 5; ++level) {
            const Image& L = pyramid[static_cast<std::size_t>(level)];
            EXPECT_EQ(L.width(), pyramid_level_size(100, ratio, level)) << ratio;
            EXPECT_EQ(L.height(), pyramid_level_size(60, ratio, level)) << ratio;
            EXPECT_EQ(L.channels(), 3);
            EXPECT_NEAR(mean(L), mean(im), 0.02) << ratio << " level " << level;
        }
    }
    EXPECT_EQ(gaussian_pyramid(im, 5, 0.5f)[4].width(), 6);  // 6.25
}

TEST(Pyramid, NearestPyramidKeepsLabelsAndEmptyStaysEmpty) {
    Image labels(30, 20, 1);
    for (int y = 0; y < 20; ++y)
        for (int x = 0; x < 30; ++x) labels.at(x, y, 0) = static_cast<float>((x / 7 + y / 5) % 3);
    for (const Image& level : gaussian_pyramid(labels, 4, 0.85f, ResampleFilter::Nearest, 1)) {
        for (float v : level.data()) EXPECT_TRUE(v == 0.0f || v == 1.0f || v == 2.0f) << v;
    }
    const std::vector<Image> empty = gaussian_pyramid(Image(), 3, 0.5f);
    ASSERT_EQ(empty.size(), 3u);
    for (const Image& level : empty) EXPECT_TRUE(level.empty());
}

TEST(Pyramid, ResultsDoNotDependOnThreadCount) {
    const Image im = random_image(80, 50, 2, 17);
    const auto one = gaussian_pyramid(im, 6, 0.85f, ResampleFilter::Gaussian, 1);
    const auto two = gaussian_pyramid(im, 6, 0.85f, ResampleFilter::Gaussian, 2);
    ASSERT_EQ(one.size(), two.size());
    for (std::size_t i = 0; i < one.size(); ++i) EXPECT_TRUE(identical(one[i], two[i])) << i;
}

}  // namespace
}  // namespace exemplar
