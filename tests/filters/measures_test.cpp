#include "exemplar/filters/measures.hpp"

#include <gtest/gtest.h>

namespace exemplar {
namespace {

TEST(GradientEnergy, KnownAnswers) {
    // A horizontal grey ramp of step 0.1: every x difference is 0.1, every y difference 0.
    Image ramp(5, 4, 3);
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 5; ++x) {
            for (int c = 0; c < 3; ++c) ramp.at(x, y, c) = 0.1f * static_cast<float>(x);
        }
    }
    EXPECT_NEAR(gradient_energy(ramp), 0.01, 1e-9);
    // Luminance weights: a red-only step counts 0.299 of its size.
    Image red(2, 2, 3, 0.0f);
    red.at(1, 0, 0) = 1.0f;
    EXPECT_NEAR(gradient_energy(red), 0.299 * 0.299, 1e-9);  // one pair, (0, 0): dx only
    // Single channel: the channel itself. A 3x3 image whose middle row is 0.5: each of the 4
    // pairs sees a y difference of ±0.5. Flat images and single pixels have no energy.
    Image grey(3, 3, 1, 0.0f);
    for (int x = 0; x < 3; ++x) grey.at(x, 1, 0) = 0.5f;
    EXPECT_NEAR(gradient_energy(grey), 0.25, 1e-9);
    EXPECT_EQ(gradient_energy(Image(3, 3, 1, 0.5f)), 0.0);
    EXPECT_EQ(gradient_energy(Image(1, 1, 3, 1.0f)), 0.0);
}

// A region counts only the pairs whose three pixels are inside it: the ramp's right half
// (x >= 2) has steps of 0.1, its left half steps of 0.3; each half alone gives its own step.
TEST(GradientEnergy, RegionCountsOnlyItsPairs) {
    Image ramp(5, 4, 1);
    Image right(5, 4, 1, 0.0f), left(5, 4, 1, 0.0f);
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 5; ++x) {
            ramp.at(x, y, 0) = x <= 2 ? 0.3f * static_cast<float>(x) : 0.6f + 0.1f * (x - 2);
            (x >= 2 ? right : left).at(x, y, 0) = 1.0f;
        }
    }
    EXPECT_NEAR(gradient_energy(ramp, right), 0.01, 1e-6);  // float steps
    EXPECT_NEAR(gradient_energy(ramp, left), 0.09, 1e-6);
    EXPECT_EQ(gradient_energy(ramp, Image(5, 4, 1, 0.0f)), 0.0);  // nothing inside
    EXPECT_EQ(gradient_energy(ramp, Image(5, 4, 1, 1.0f)), gradient_energy(ramp));
}

}  // namespace
}  // namespace exemplar
