// Structure tensor orientation: stripes at known angles, coherence, thread independence.

#include "exemplar/filters/structure_tensor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>

namespace exemplar {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// Sinusoidal stripes running along the on-screen direction `angle_rad` (counter-clockwise, so
// in y-down pixel coordinates the stripe direction is (cos, -sin)). Period 16 px: at shorter
// periods the central differences are anisotropic enough to bias oblique angles by degrees.
Image stripes(int size, float angle_rad, int channels = 1) {
    Image image(size, size, channels);
    const float nx = std::sin(angle_rad), ny = std::cos(angle_rad);  // normal to the stripes
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const float v =
                0.5f + 0.5f * std::sin(2.0f * kPi / 16.0f *
                                       (nx * static_cast<float>(x) + ny * static_cast<float>(y)));
            for (int c = 0; c < channels; ++c) image.at(x, y, c) = v;
        }
    }
    return image;
}

// Smallest difference between two orientations (angles modulo π).
float orientation_difference(float a, float b) {
    float d = std::fmod(std::abs(a - b), kPi);
    return std::min(d, kPi - d);
}

TEST(StructureTensor, FindsTheStripeDirection) {
    for (float degrees : {0.0f, 30.0f, 45.0f, 90.0f, 120.0f, 160.0f}) {
        const float angle = degrees * kPi / 180.0f;
        const Image field = orientation_field(stripes(64, angle, 3), {}, 1);
        ASSERT_EQ(field.channels(), 1);
        EXPECT_EQ(field.channel_names()[0], "angle");
        // Away from the clamped border the estimate is within half a degree (measured: 0 at
        // 0/45/90 degrees, 0.32 at 30 and 120, 0.37 at 160).
        float worst = 0.0f;
        for (int y = 16; y < 48; ++y) {
            for (int x = 16; x < 48; ++x) {
                const float a = field.at(x, y, 0);
                ASSERT_GE(a, 0.0f);
                ASSERT_LT(a, kPi);
                worst = std::max(worst, orientation_difference(a, angle));
            }
        }
        EXPECT_LT(worst, 0.5f * kPi / 180.0f) << degrees << " degrees";
    }
}

TEST(StructureTensor, CoherenceSeparatesStripesFromFlat) {
    const Image tensor = structure_tensor(stripes(48, 0.7f), {}, 1);
    EXPECT_GT(coherence_from_tensor(tensor).at(24, 24, 0), 0.95f);
    const Image flat_tensor = structure_tensor(Image(48, 48, 1, 0.3f), {}, 1);
    EXPECT_EQ(coherence_from_tensor(flat_tensor).at(24, 24, 0), 0.0f);
    EXPECT_EQ(orientation_from_tensor(flat_tensor).at(24, 24, 0), 0.0f);
}

TEST(StructureTensor, SameBytesForAnyThreadCount) {
    const Image image = stripes(80, 1.1f, 3);
    const Image one = orientation_field(image, {}, 1);
    const Image all = orientation_field(image, {}, 0);
    ASSERT_EQ(one.size(), all.size());
    EXPECT_EQ(std::memcmp(one.data().data(), all.data().data(), one.size() * 4), 0);
}

}  // namespace
}  // namespace exemplar
