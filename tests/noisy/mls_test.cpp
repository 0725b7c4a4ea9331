// The rigid MLS deformation (Schaefer et al. 2006) and the lattice jitter of Color Me Noisy.

#include "exemplar/noisy/mls.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace exemplar::noisy {
namespace {

TEST(Mls, ZeroOffsetsGiveTheIdentity) {
    const ControlPoints points = jittered_lattice(200, 150, 50.0, 0.0, 0.0, 7);
    ASSERT_EQ(points.from.size(), 5u * 4u);
    for (double y = -10.0; y < 160.0; y += 3.7) {
        for (double x = -10.0; x < 210.0; x += 4.3) {
            for (double smoothing : {0.0, 20.0}) {
                const Point f = mls_rigid(points, {x, y}, smoothing);
                EXPECT_NEAR(f.x, x, 1e-9);
                EXPECT_NEAR(f.y, y, 1e-9);
            }
        }
    }
    Image image(40, 30, 3);
    for (std::size_t i = 0; i < image.size(); ++i) image.data()[i] = static_cast<float>(i % 17);
    const Image same = deform_rigid(image, jittered_lattice(40, 30, 10.0, 0.0, 0.0, 1), 4.0, 1);
    for (std::size_t i = 0; i < image.size(); ++i) {
        EXPECT_NEAR(same.data()[i], image.data()[i], 1e-4) << i;
    }
}

TEST(Mls, WithoutSmoothingControlPointsMapToTheirTargets) {
    const ControlPoints points = jittered_lattice(120, 120, 50.0, 15.0, 25.0, 3);
    for (std::size_t i = 0; i < points.from.size(); ++i) {
        const Point f = mls_rigid(points, points.from[i]);
        EXPECT_EQ(f.x, points.to[i].x);
        EXPECT_EQ(f.y, points.to[i].y);
        // Close to a control point the map is continuous.
        const Point g = mls_rigid(points, {points.from[i].x + 1e-4, points.from[i].y});
        EXPECT_NEAR(g.x, points.to[i].x, 1e-2);
        EXPECT_NEAR(g.y, points.to[i].y, 1e-2);
    }
}

TEST(Mls, RigidMotionsAreReproducedExactly) {
    const ControlPoints lattice = jittered_lattice(300, 200, 50.0, 0.0, 0.0, 1);
    for (double angle : {0.0, 0.3, -1.2, 2.9}) {
        const double c = std::cos(angle), s = std::sin(angle), tx = 7.5, ty = -3.25;
        ControlPoints moved{lattice.from, {}};
        for (const Point& p : lattice.from) {
            moved.to.push_back({c * p.x - s * p.y + tx, s * p.x + c * p.y + ty});
        }
        for (double y = -20.0; y < 220.0; y += 11.3) {
            for (double x = -20.0; x < 320.0; x += 9.1) {
                for (double smoothing : {0.0, 20.0}) {
                    const Point f = mls_rigid(moved, {x, y}, smoothing);
                    EXPECT_NEAR(f.x, c * x - s * y + tx, 1e-9) << angle;
                    EXPECT_NEAR(f.y, s * x + c * y + ty, 1e-9) << angle;
                }
            }
        }
    }
}

TEST(Mls, LatticeOffsetsHaveTheRequestedLengthsAndDependOnlyOnTheKey) {
    const ControlPoints a = jittered_lattice(256, 256, 50.0, 15.0, 25.0, 11);
    const ControlPoints b = jittered_lattice(256, 256, 50.0, 15.0, 25.0, 11);
    const ControlPoints c = jittered_lattice(256, 256, 50.0, 15.0, 25.0, 12);
    ASSERT_EQ(a.from.size(), 7u * 7u);  // 0, 50, ..., 300 ≥ 255 on each axis
    int differ = 0;
    for (std::size_t i = 0; i < a.from.size(); ++i) {
        const double length = std::hypot(a.to[i].x - a.from[i].x, a.to[i].y - a.from[i].y);
        EXPECT_GE(length, 15.0 - 1e-9);
        EXPECT_LE(length, 25.0 + 1e-9);
        EXPECT_EQ(a.to[i].x, b.to[i].x);
        EXPECT_EQ(a.to[i].y, b.to[i].y);
        differ += a.to[i].x != c.to[i].x;
    }
    EXPECT_GT(differ, 40);
}

// Smallest Jacobian determinant of a sampled map (forward differences between pixel centres).
double min_jacobian(const Image& map) {
    double lowest = std::numeric_limits<double>::infinity();
    for (int y = 0; y + 1 < map.height(); ++y) {
        for (int x = 0; x + 1 < map.width(); ++x) {
            const double xx = map.at(x + 1, y, 0) - map.at(x, y, 0);
            const double xy = map.at(x + 1, y, 1) - map.at(x, y, 1);
            const double yx = map.at(x, y + 1, 0) - map.at(x, y, 0);
            const double yy = map.at(x, y + 1, 1) - map.at(x, y, 1);
            lowest = std::min(lowest, xx * yy - xy * yx);
        }
    }
    return lowest;
}

// Smallest Jacobian determinant of the forward and the inverse map of many draws at the
// chapter's values (50 px lattice, points moved 15-25 px).
double min_jacobian_of_draws(double smoothing_px, int draws) {
    double lowest = std::numeric_limits<double>::infinity();
    for (int key = 0; key < draws; ++key) {
        const ControlPoints points =
            jittered_lattice(200, 200, 50.0, 15.0, 25.0, static_cast<std::uint64_t>(key));
        const ControlPoints inverse{points.to, points.from};
        lowest = std::min(lowest, min_jacobian(mls_rigid_map(points, 200, 200, smoothing_px)));
        lowest = std::min(lowest, min_jacobian(mls_rigid_map(inverse, 200, 200, smoothing_px)));
    }
    return lowest;
}

TEST(Mls, NoFoldOversAtTheChaptersOffsets) {
    // The smoothing the pre-deformation uses keeps every map of 32 draws (forward and the
    // inverse that deform_rigid samples) orientation-preserving everywhere.
    const double lowest = min_jacobian_of_draws(lattice_smoothing_px(50.0), 32);
    EXPECT_GT(lowest, 0.05);
    std::printf("smoothed MLS: smallest Jacobian determinant over 64 maps %.3f\n", lowest);
}

TEST(Mls, WithoutSmoothingThePapersMapFoldsAtTheseOffsets) {
    // Why the smoothing exists: the unsmoothed map of the same draws folds over (around the
    // control points, where each ray from a point is rotated by its own angle).
    const double lowest = min_jacobian_of_draws(0.0, 8);
    EXPECT_LT(lowest, 0.0);
    std::printf("unsmoothed MLS: smallest Jacobian determinant over 16 maps %.3f\n", lowest);
}

TEST(Mls, SmoothedLatticeStillMovesTheSourceFarEnough) {
    // Mean displacement of the pixels of a 200x200 source under the pre-deformation: about
    // half of the offsets' 20 px mean (the smoothing averages neighbouring offsets).
    double sum = 0.0;
    int count = 0;
    for (std::uint64_t key = 0; key < 8; ++key) {
        const ControlPoints points = jittered_lattice(200, 200, 50.0, 15.0, 25.0, key);
        const Image map = mls_rigid_map(points, 200, 200, lattice_smoothing_px(50.0));
        for (int y = 0; y < 200; y += 2) {
            for (int x = 0; x < 200; x += 2) {
                sum += std::hypot(map.at(x, y, 0) - x, map.at(x, y, 1) - y);
                ++count;
            }
        }
    }
    const double mean = sum / count;
    std::printf("mean displacement %.2f px\n", mean);
    EXPECT_GT(mean, 6.0);
    EXPECT_LT(mean, 20.0);
}

TEST(Mls, DeformationMovesFeaturesWithTheirControlPoints) {
    ControlPoints points = jittered_lattice(151, 151, 50.0, 0.0, 0.0, 1);
    // Move the centre point (100, 100) by (12, -9); the others stay (no smoothing: exact).
    for (std::size_t i = 0; i < points.from.size(); ++i) {
        if (points.from[i].x == 100.0 && points.from[i].y == 100.0) points.to[i] = {112.0, 91.0};
    }
    Image image(151, 151, 1, 0.0f);
    for (int y = 99; y <= 101; ++y) {
        for (int x = 99; x <= 101; ++x) image.at(x, y, 0) = 1.0f;
    }
    const Image out = deform_rigid(image, points, 0.0, 1);
    int best_x = 0, best_y = 0;
    for (int y = 0; y < 151; ++y) {
        for (int x = 0; x < 151; ++x) {
            if (out.at(x, y, 0) > out.at(best_x, best_y, 0)) best_x = x, best_y = y;
        }
    }
    EXPECT_NEAR(best_x, 112, 2);
    EXPECT_NEAR(best_y, 91, 2);
}

TEST(Mls, DeformationIsIdenticalForAnyThreadCount) {
    Image image(97, 61, 3);
    for (std::size_t i = 0; i < image.size(); ++i) {
        image.data()[i] = static_cast<float>((i * 2654435761u) % 1000) / 1000.0f;
    }
    const ControlPoints points = jittered_lattice(97, 61, 20.0, 6.0, 10.0, 5);
    const Image one = deform_rigid(image, points, 8.0, 1);
    const Image many = deform_rigid(image, points, 8.0, 3);
    ASSERT_EQ(one.size(), many.size());
    EXPECT_TRUE(std::equal(one.data().begin(), one.data().end(), many.data().begin()));
}

TEST(Mls, AnglesTurnWithTheDeformation) {
    // Every point rotated rigidly by 0.4 rad about the centre: a constant orientation field
    // (strokes at 0.3 rad) comes out at 0.7 rad, for any smoothing.
    const ControlPoints lattice = jittered_lattice(101, 101, 25.0, 0.0, 0.0, 1);
    const double angle = 0.4, c = std::cos(angle), s = std::sin(angle);
    ControlPoints turned{lattice.from, {}};
    for (const Point& p : lattice.from) {
        turned.to.push_back(
            {50 + c * (p.x - 50) - s * (p.y - 50), 50 + s * (p.x - 50) + c * (p.y - 50)});
    }
    const Image angles(101, 101, 1, 0.3f);
    for (double smoothing : {0.0, 10.0}) {
        const Image out = deform_rigid_angles(angles, turned, smoothing, 1);
        for (int y = 0; y < 101; y += 5) {
            for (int x = 0; x < 101; x += 5) EXPECT_NEAR(out.at(x, y, 0), 0.7, 1e-5);
        }
    }
    EXPECT_NEAR(mls_rigid_sample(turned, {20.0, 70.0}, 10.0).angle_rad, angle, 1e-9);
}

}  // namespace
}  // namespace exemplar::noisy
