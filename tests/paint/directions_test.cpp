// Direction analysis (Brushables §3.1, Fig. 3): sign-harmonized edge tangent flow.

#include "exemplar/paint/directions.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>

namespace exemplar::paint {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// Stripes radiating from the centre (Brushables Fig. 3a): 0.5 + 0.5 sin(k θ).
Image radial_stripes(int size, int periods) {
    Image image(size, size, 3);
    const float c = 0.5f * static_cast<float>(size - 1);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const float theta = std::atan2(static_cast<float>(y) - c, static_cast<float>(x) - c);
            const float v = 0.5f + 0.5f * std::sin(static_cast<float>(periods) * theta);
            for (int ch = 0; ch < 3; ++ch) image.at(x, y, ch) = v;
        }
    }
    return image;
}

struct RadialStats {
    double flipped_pairs = 0.0;  // share of 4-neighbour pairs more than 90° apart
    double outward = 0.0;        // share of pixels pointing away from the centre
    double radial = 0.0;         // share of pixels within 25° of the radial line
};

// Measured on the annulus 16 <= r <= 56 px around the centre of a 129 px image.
RadialStats radial_stats(const Image& field) {
    const int size = field.width();
    const float c = 0.5f * static_cast<float>(size - 1);
    auto inside = [&](int x, int y) {
        const float r = std::hypot(static_cast<float>(x) - c, static_cast<float>(y) - c);
        return r >= 16.0f && r <= 56.0f;
    };
    RadialStats s;
    double pairs = 0.0, pixels = 0.0;
    for (int y = 0; y + 1 < size; ++y) {
        for (int x = 0; x + 1 < size; ++x) {
            if (!inside(x, y)) continue;
            const float* d = field.pixel(x, y);
            const float rx = static_cast<float>(x) - c, ry = static_cast<float>(y) - c;
            const float rl = std::hypot(rx, ry);
            const float cosine = (d[0] * rx + d[1] * ry) / rl;
            pixels += 1.0;
            if (cosine > 0.0f) s.outward += 1.0;
            if (std::abs(cosine) > std::cos(25.0f * kPi / 180.0f)) s.radial += 1.0;
            for (const auto& [u, v] : {std::pair{x + 1, y}, std::pair{x, y + 1}}) {
                if (!inside(u, v)) continue;
                const float* n = field.pixel(u, v);
                pairs += 1.0;
                if (d[0] * n[0] + d[1] * n[1] < 0.0f) s.flipped_pairs += 1.0;
            }
        }
    }
    s.flipped_pairs /= pairs;
    s.outward /= pixels;
    s.radial /= pixels;
    return s;
}

TEST(Directions, SignHarmonizationRemovesTheFlipsOnRadialStripes) {
    const Image stripes = radial_stripes(129, 12);
    DirectionAnalysisOptions options;
    options.radius_px = 5.0f;
    const Image harmonized = analyze_directions(stripes, options, 2).value();
    options.harmonize_signs = false;
    const Image plain = analyze_directions(stripes, options, 2).value();

    const RadialStats h = radial_stats(harmonized);
    const RadialStats p = radial_stats(plain);
    std::printf(
        "radial stripes: harmonized flipped pairs %.4f, outward %.3f; plain ETF %.4f, %.3f\n",
        h.flipped_pairs, h.outward, p.flipped_pairs, p.outward);
    // Both follow the stripes (the absolute direction does not depend on the signs) ...
    EXPECT_GT(h.radial, 0.95) << "harmonized";
    EXPECT_GT(p.radial, 0.95) << "plain";
    // ... but only the harmonized field points one way: outward everywhere or inward everywhere.
    EXPECT_GT(std::max(h.outward, 1.0 - h.outward), 0.99);
    EXPECT_LT(h.flipped_pairs, 0.002);
    // Plain ETF keeps the gradient's sign, which alternates from stripe to stripe (Fig. 3c).
    EXPECT_LT(std::max(p.outward, 1.0 - p.outward), 0.8);
    EXPECT_GT(p.flipped_pairs, 0.02);
}

TEST(Directions, HorizontalStripesGiveHorizontalDirections) {
    Image stripes(64, 48, 1);
    for (int y = 0; y < 48; ++y) {
        for (int x = 0; x < 64; ++x) stripes.at(x, y, 0) = (y / 4) % 2 == 0 ? 0.2f : 0.8f;
    }
    const Image field = analyze_directions(stripes, {}, 1).value();
    ASSERT_EQ(field.channels(), 2);
    const float first_x = field.at(0, 0, 0);
    for (int y = 0; y < 48; ++y) {
        for (int x = 0; x < 64; ++x) {
            EXPECT_NEAR(std::abs(field.at(x, y, 0)), 1.0f, 1e-3f) << x << "," << y;
            // One sign everywhere (including the flat stripe centres).
            EXPECT_GT(field.at(x, y, 0) * first_x, 0.0f) << x << "," << y;
        }
    }
    const Image angles = direction_angles(field);
    EXPECT_NEAR(std::abs(angles.at(10, 10, 0)), first_x > 0 ? 0.0f : kPi, 1e-3f);
}

TEST(Directions, SameBytesForOneAndTwoThreads) {
    const Image stripes = radial_stripes(65, 7);
    const Image a = analyze_directions(stripes, {}, 1).value();
    const Image b = analyze_directions(stripes, {}, 2).value();
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data().data(), b.data().data(), a.size() * sizeof(float)), 0);
}

TEST(Directions, InvalidOptionsAreRejectedByName) {
    DirectionAnalysisOptions options;
    options.radius_px = 0.5f;
    const auto r = analyze_directions(Image(8, 8, 3), options, 1);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.status().message().find("radius"), std::string::npos);
    options = {};
    options.iterations = 11;
    EXPECT_FALSE(analyze_directions(Image(8, 8, 3), options, 1).ok());
    EXPECT_TRUE(analyze_directions(Image{}, {}, 1).value().empty());
}

TEST(Directions, AnglesRoundTripAndWheelColours) {
    Image angles(4, 1, 1);
    const float values[4] = {0.0f, kPi / 2, kPi, -kPi / 2};
    for (int x = 0; x < 4; ++x) angles.at(x, 0, 0) = values[x];
    const Image field = directions_from_angles(angles);
    EXPECT_NEAR(field.at(1, 0, 1), -1.0f, 1e-6f);  // π/2 points up on screen (y down)
    const Image back = direction_angles(field);
    for (int x = 0; x < 4; ++x) {
        EXPECT_NEAR(std::cos(back.at(x, 0, 0) - values[x]), 1.0f, 1e-6f) << x;
    }
    const Image wheel = direction_wheel(field);
    EXPECT_NEAR(wheel.at(0, 0, 0), 1.0f, 1e-5f);  // right: red
    EXPECT_NEAR(wheel.at(0, 0, 1), 0.0f, 1e-5f);
    EXPECT_NEAR(wheel.at(2, 0, 0), 0.0f, 1e-5f);  // left: cyan
    EXPECT_NEAR(wheel.at(2, 0, 1), 1.0f, 1e-5f);
    EXPECT_NEAR(wheel.at(2, 0, 2), 1.0f, 1e-5f);
    const Image none = direction_wheel(Image(1, 1, 2));
    EXPECT_EQ(none.at(0, 0, 0) + none.at(0, 0, 1) + none.at(0, 0, 2), 0.0f);
}

}  // namespace
}  // namespace exemplar::paint
