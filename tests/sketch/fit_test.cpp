// Schneider fitting: error bound, corners kept, closed strokes, degenerate input.

#include "exemplar/sketch/fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace exemplar::sketch {
namespace {

double max_distance_to(const Path& path, const std::vector<Vec2>& samples) {
    const std::vector<Vec2> dense = flatten(path, 0.05);
    double worst = 0.0;
    for (Vec2 s : samples) worst = std::max(worst, closest_point(dense, s).distance);
    return worst;
}

TEST(SketchFit, SmoothSamplesWithinTolerance) {
    std::vector<Vec2> samples;
    for (int i = 0; i <= 200; ++i) {
        const double t = i / 200.0;
        samples.push_back({100 * t, 20 * std::sin(6 * t)});
    }
    FitOptions options;
    options.tolerance = 0.5;
    const Path path = fit_path(samples, options);
    ASSERT_FALSE(path.empty());
    EXPECT_LT(path.segments.size(), 12u);
    EXPECT_LE(max_distance_to(path, samples), 0.5 + 1e-6);
    EXPECT_EQ(path.start(), samples.front());
    EXPECT_EQ(path.end(), samples.back());
}

TEST(SketchFit, CornerStaysSharp) {
    std::vector<Vec2> samples;
    for (int i = 0; i <= 50; ++i) samples.push_back({static_cast<double>(i), 0});
    for (int i = 1; i <= 50; ++i) samples.push_back({50, static_cast<double>(i)});
    const Path path = fit_path(samples);
    // A segment ends exactly at the corner.
    bool corner_is_joint = false;
    for (const Cubic& c : path.segments) corner_is_joint |= c.p3 == Vec2{50, 0};
    EXPECT_TRUE(corner_is_joint);
    EXPECT_LE(max_distance_to(path, samples), 1.0 + 1e-6);
}

TEST(SketchFit, ClosedLoopAndDegenerateInput) {
    std::vector<Vec2> samples;
    for (int i = 0; i <= 64; ++i) {
        const double a = 2 * std::numbers::pi * i / 64;
        samples.push_back({30 * std::cos(a), 30 * std::sin(a)});
    }
    const Path loop = fit_path(samples);
    EXPECT_TRUE(loop.closed);
    EXPECT_EQ(loop.start(), loop.end());
    EXPECT_TRUE(fit_path({{1, 1}, {1, 1}, {1, 1}}).empty());
    EXPECT_TRUE(fit_path({}).empty());
}

// Pen samples stored as a polyline become a few smooth cubics within the tolerance; paths
// with curves, short polylines and closed loops keep what they are.
TEST(SketchFit, RefitPolylineOnlyRefitsPenSamples) {
    std::vector<Vec2> samples;
    for (int i = 0; i <= 60; ++i) samples.push_back({2.0 * i, 15 * std::sin(i / 10.0)});
    const Path pen = polyline_path(samples);
    const Path smooth = refit_polyline(pen, 0.5);
    EXPECT_LT(smooth.segments.size(), 10u);
    EXPECT_LE(max_distance_to(smooth, samples), 0.5 + 1e-6);

    EXPECT_EQ(refit_polyline(smooth, 0.5).segments.size(), smooth.segments.size());
    const Path two = polyline_path({{0, 0}, {10, 0}, {10, 10}});
    EXPECT_EQ(refit_polyline(two, 0.5).segments.size(), two.segments.size());

    std::vector<Vec2> ring;
    for (int i = 0; i < 40; ++i) {
        const double a = 2 * std::numbers::pi * i / 40;
        ring.push_back({20 * std::cos(a), 20 * std::sin(a)});
    }
    EXPECT_TRUE(refit_polyline(polyline_path(ring, /*closed=*/true), 0.5).closed);
}

}  // namespace
}  // namespace exemplar::sketch
