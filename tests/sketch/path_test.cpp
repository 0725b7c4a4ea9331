// Paths: sampling, arc length, tangents, simplification, Fréchet distance, similarity fits.

#include "exemplar/sketch/path.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace exemplar::sketch {
namespace {

TEST(SketchPath, ArcLengthOfLineAndCircle) {
    EXPECT_NEAR(arc_length(polyline_path({{0, 0}, {30, 40}})), 50.0, 1e-9);
    const Path circle = arc_path({10, 10}, 20, 0.0, 2 * std::numbers::pi);
    EXPECT_TRUE(circle.closed);
    EXPECT_NEAR(arc_length(circle), 2 * std::numbers::pi * 20, 0.05);
    // Every point of the cubic approximation is within 0.03% of the radius.
    for (Vec2 p : flatten(circle, 0.5)) EXPECT_NEAR(distance(p, {10, 10}), 20.0, 20 * 3e-4);
}

TEST(SketchPath, ResampleIsEquallySpaced) {
    const std::vector<Vec2> pts = resample({{0, 0}, {10, 0}, {10, 10}}, 5);
    ASSERT_EQ(pts.size(), 5u);
    for (std::size_t i = 1; i < pts.size(); ++i)
        EXPECT_NEAR(distance(pts[i - 1], pts[i]), 5.0, 1e-9);
    EXPECT_EQ(pts.back(), (Vec2{10, 10}));
}

TEST(SketchPath, TangentsPointAlongThePath) {
    const Path p = polyline_path({{0, 0}, {10, 0}, {10, 10}});
    EXPECT_NEAR(start_tangent(p).x, 1.0, 1e-12);
    EXPECT_NEAR(end_tangent(p).y, 1.0, 1e-12);
    EXPECT_NEAR(end_tangent(reversed(p)).x, -1.0, 1e-12);
}

TEST(SketchPath, RdpKeepsCornersDropsCollinearPoints) {
    const std::vector<Vec2> line{{0, 0}, {1, 0.1}, {2, 0}, {3, 0.1}, {4, 0}, {4, 5}};
    const std::vector<Vec2> simple = simplify_rdp(line, 0.5);
    ASSERT_EQ(simple.size(), 3u);
    EXPECT_EQ(simple[1], (Vec2{4, 0}));
}

TEST(SketchPath, FrechetKnownValues) {
    const std::vector<Vec2> a{{0, 0}, {1, 0}, {2, 0}};
    const std::vector<Vec2> b{{0, 1}, {1, 1}, {2, 1}};
    EXPECT_DOUBLE_EQ(discrete_frechet(a, b), 1.0);
    EXPECT_DOUBLE_EQ(discrete_frechet(a, a), 0.0);
    // Walking backwards is not allowed: the reversed path is far.
    std::vector<Vec2> r(a.rbegin(), a.rend());
    EXPECT_DOUBLE_EQ(discrete_frechet(a, r), 2.0);
    // A detour: 3 away at its tip.
    EXPECT_DOUBLE_EQ(discrete_frechet(a, {{0, 0}, {1, 3}, {2, 0}}), 3.0);
}

TEST(SketchPath, SimilarityFitRecoversTheTransform) {
    const std::vector<Vec2> from{{0, 0}, {3, 1}, {5, -2}, {1, 4}};
    const Affine truth = Affine::similarity(0.7, 1.8, {2, 3});
    std::vector<Vec2> to;
    for (Vec2 p : from) to.push_back(truth.apply(p));
    const Affine fit = fit_similarity(from, to);
    for (Vec2 p : from) EXPECT_NEAR(distance(fit.apply(p), truth.apply(p)), 0.0, 1e-9);
    const SimilarityParts parts = decompose_similarity(fit);
    EXPECT_NEAR(parts.rotation_rad, 0.7, 1e-9);
    EXPECT_NEAR(parts.scale, 1.8, 1e-9);
    EXPECT_FALSE(parts.reflected);
    EXPECT_TRUE(decompose_similarity(Affine::reflection({0, 0}, {1, 1})).reflected);
}

TEST(SketchPath, CircleFitOnExactPoints) {
    std::vector<Vec2> pts;
    for (int i = 0; i < 12; ++i)
        pts.push_back(Vec2{5, -3} + Vec2{std::cos(0.2 * i), std::sin(0.2 * i)} * 7.0);
    const Circle c = fit_circle(pts);
    EXPECT_NEAR(c.center.x, 5, 1e-9);
    EXPECT_NEAR(c.center.y, -3, 1e-9);
    EXPECT_NEAR(c.radius, 7, 1e-9);
    EXPECT_EQ(fit_circle({{0, 0}, {1, 1}, {2, 2}}).radius, 0.0);  // collinear
}

TEST(SketchPath, AffineComposeAndInverse) {
    const Affine a = Affine::similarity(0.3, 2.0, {1, 2});
    const Affine b = Affine::reflection({3, 0}, {0, 1});
    const Vec2 p{4, -1};
    EXPECT_NEAR(distance(compose(a, b).apply(p), a.apply(b.apply(p))), 0.0, 1e-12);
    EXPECT_NEAR(distance(a.inverse().apply(a.apply(p)), p), 0.0, 1e-12);
    EXPECT_NEAR(distance(b.apply(p), Vec2{2, -1}), 0.0, 1e-12);  // mirror across x = 3
}

}  // namespace
}  // namespace exemplar::sketch
