// The bilateral filter: constants stay, strong edges are kept where a Gaussian blurs them, noise
// within a side is smoothed, and the result does not depend on the thread count.

#include "exemplar/filters/bilateral.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "exemplar/core/rng.hpp"
#include "exemplar/filters/resample.hpp"

namespace exemplar {
namespace {

// A vertical step from 0.2 to 0.8 at x = 20 with ±0.05 noise, 3 channels.
Image noisy_step() {
    Image image(40, 30, 3);
    for (int y = 0; y < 30; ++y) {
        for (int x = 0; x < 40; ++x) {
            const float grain =
                0.1f * (KeyedRng(9, static_cast<std::uint64_t>(x), static_cast<std::uint64_t>(y))
                            .uniform() -
                        0.5f);
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = (x < 20 ? 0.2f : 0.8f) + grain;
        }
    }
    return image;
}

TEST(Bilateral, KeepsConstantsAndEdgesAndSmoothsNoise) {
    const Image flat(16, 16, 2, 0.3f);
    const Image same = bilateral_filter(flat, 3.0f, 0.1f, 1);
    for (float v : same.data()) EXPECT_NEAR(v, 0.3f, 1e-6f);

    const Image step = noisy_step();
    const Image base = bilateral_filter(step, 3.0f, 0.1f, 1);
    const Image blurred = gaussian_blur(step, 3.0f, 1);
    // Next to the edge the bilateral base stays on its side; the Gaussian mixes both.
    EXPECT_NEAR(base.at(19, 15, 0), 0.2f, 0.03f);
    EXPECT_NEAR(base.at(20, 15, 0), 0.8f, 0.03f);
    EXPECT_GT(blurred.at(19, 15, 0), 0.35f);
    // Within a side, the noise is smoothed.
    double raw = 0.0, filtered = 0.0;
    for (int y = 5; y < 25; ++y) {
        for (int x = 3; x < 16; ++x) {
            raw += std::abs(step.at(x, y, 0) - 0.2f);
            filtered += std::abs(base.at(x, y, 0) - 0.2f);
        }
    }
    EXPECT_LT(filtered, 0.3 * raw);
}

TEST(Bilateral, SameBytesForAnyThreadCount) {
    const Image step = noisy_step();
    const Image one = bilateral_filter(step, 2.5f, 0.2f, 1);
    const Image two = bilateral_filter(step, 2.5f, 0.2f, 2);
    EXPECT_EQ(std::memcmp(one.data().data(), two.data().data(), one.size() * sizeof(float)), 0);
}

}  // namespace
}  // namespace exemplar
