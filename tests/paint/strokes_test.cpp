// Direction diffusion from strokes (Brushables §3.2, eq. 1-3): the closed-form polyline integral
// against numerical integration, locality, blending and combing.

#include "exemplar/paint/strokes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

namespace exemplar::paint {
namespace {

// Eq. 1-2 by dense sampling of the centre line (the oracle of the closed form).
std::array<double, 3> numeric_diffusion(const std::vector<Stroke>& strokes, double px, double py) {
    double nx = 0.0, ny = 0.0, rel = 0.0;
    for (const Stroke& s : strokes) {
        const double sigma = 0.5 * s.width_px, support = 2.0 * sigma;
        const double cut = std::exp(-0.5 * support * support / (sigma * sigma));
        const double step = 1e-3;
        double line = 0.0;
        for (double t = -support; t <= support; t += step) {
            line += std::max(0.0, std::exp(-0.5 * t * t / (sigma * sigma)) - cut) * step;
        }
        for (std::size_t i = 1; i < s.points.size(); ++i) {
            const double ax = s.points[i - 1].x, ay = s.points[i - 1].y;
            const double dx = s.points[i].x - ax, dy = s.points[i].y - ay;
            const double len = std::hypot(dx, dy);
            for (double t = 0.5 * step; t < len; t += step) {
                const double kx = ax + dx * t / len, ky = ay + dy * t / len;
                const double d2 = (px - kx) * (px - kx) + (py - ky) * (py - ky);
                if (d2 >= support * support) continue;
                const double g = std::exp(-0.5 * d2 / (sigma * sigma)) - cut;
                nx += g * step * dx / len;
                ny += g * step * dy / len;
                rel += g * step / line;
            }
        }
    }
    const double n = std::hypot(nx, ny);
    return {n > 0 ? nx / n : 0.0, n > 0 ? ny / n : 0.0, std::min(1.0, rel)};
}

Stroke stroke(std::vector<StrokePoint> points, float width, bool comb = false) {
    Stroke s;
    s.points = std::move(points);
    s.width_px = width;
    s.comb = comb;
    return s;
}

TEST(Strokes, ClosedFormEqualsNumericalIntegration) {
    const std::vector<Stroke> strokes = {
        stroke({{10, 30}, {40, 22}, {60, 40}, {62, 70}}, 20),
        stroke({{20, 60}, {50, 58}}, 12),
    };
    const Image d = diffuse_strokes(strokes, 80, 80);
    int checked = 0;
    for (int y = 2; y < 80; y += 7) {
        for (int x = 3; x < 80; x += 7) {
            const auto ref = numeric_diffusion(strokes, x + 0.5, y + 0.5);
            const float* v = d.pixel(x, y);
            EXPECT_NEAR(v[2], ref[2], 2e-3) << x << "," << y;
            if (ref[2] > 1e-3) {
                EXPECT_NEAR(v[0], ref[0], 2e-3) << x << "," << y;
                EXPECT_NEAR(v[1], ref[1], 2e-3) << x << "," << y;
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 30);
}

// The fast diffusion (collinear points merged into chords, tabulated erf and exp) against the
// reference (every segment, libm): a densely sampled wide wave, where most points merge, a
// narrow one, and a zigzag, where none do. The fast path reaches no pixel the reference does not
// (a chord is cut off by its deviation: strictly local) and misses only a fringe at the support
// where the weight is nearly 0; the weights and the weighted directions (what the blend adds)
// differ by less than 3e-3 (measured: up to 2.2e-3, at the cut-off fringe; 1e-7 from the
// tables alone, in the zigzag).
TEST(Strokes, MergedChordsAndTablesMatchTheReference) {
    auto wave = [](float step, float width, float amplitude) {
        Stroke s;
        s.width_px = width;
        for (float x = 20.0f; x <= 380.0f; x += step) {
            s.points.push_back({x, 150.0f + amplitude * std::sin(x / 40.0f)});
        }
        return s;
    };
    const std::vector<std::vector<Stroke>> cases = {
        {wave(1.0f, 120.0f, 50.0f)},
        {wave(4.0f, 120.0f, 35.0f)},
        {wave(1.0f, 9.0f, 60.0f)},
        {stroke({{30, 30}, {60, 80}, {90, 30}, {120, 80}, {150, 30}}, 30)},
    };
    for (std::size_t c = 0; c < cases.size(); ++c) {
        const Image fast = diffuse_strokes(cases[c], 400, 300);
        const Image ref = diffuse_strokes_reference(cases[c], 400, 300);
        double worst_direction = 0.0, worst_weight = 0.0;
        int reached = 0;
        for (int y = 0; y < 300; ++y) {
            for (int x = 0; x < 400; ++x) {
                const float* f = fast.pixel(x, y);
                const float* r = ref.pixel(x, y);
                if (r[2] <= 0.0f) {
                    ASSERT_EQ(f[2], 0.0f) << "case " << c << " at " << x << "," << y;
                    continue;
                }
                ++reached;
                worst_weight = std::max(worst_weight, std::abs(double(f[2]) - r[2]));
                // What the blend (eq. 3) adds to the field: w_s times the direction (where w_s
                // is tiny the direction is a ratio of tiny sums and matters as little).
                worst_direction = std::max(worst_direction,
                                           std::hypot(double(f[2]) * f[0] - double(r[2]) * r[0],
                                                      double(f[2]) * f[1] - double(r[2]) * r[1]));
            }
        }
        EXPECT_GT(reached, 3000) << "case " << c;
        EXPECT_LT(worst_weight, 3e-3) << "case " << c;
        EXPECT_LT(worst_direction, 3e-3) << "case " << c;
    }
}

TEST(Strokes, DiffusionIsTheSameForAnyThreadCount) {
    std::vector<Stroke> strokes = {stroke({{20, 40}, {60, 70}, {140, 50}, {180, 120}}, 60),
                                   stroke({{30, 130}, {170, 20}}, 24)};
    for (float x = 10.0f; x < 190.0f; x += 1.0f) {
        strokes[0].points.push_back({x, 100.0f + 20.0f * std::sin(x / 25.0f)});
    }
    const Image one = diffuse_strokes(strokes, 200, 150, 1);
    for (int threads : {2, 3, 0}) {
        const Image many = diffuse_strokes(strokes, 200, 150, threads);
        EXPECT_EQ(std::memcmp(one.data().data(), many.data().data(), one.size() * sizeof(float)), 0)
            << threads << " threads";
    }
    PaintCanvas a(200, 150), b(200, 150);
    ASSERT_TRUE(a.add_strokes(strokes, 1).ok());
    ASSERT_TRUE(b.add_strokes(strokes, 2).ok());
    EXPECT_EQ(std::memcmp(a.directions().data().data(), b.directions().data().data(),
                          a.directions().size() * sizeof(float)),
              0);
}

TEST(Strokes, StraightStrokeGivesItsDirectionAndFullWeightOnItsCentreLine) {
    PaintCanvas canvas(100, 60);
    ASSERT_TRUE(canvas.add_stroke(stroke({{10, 30}, {90, 30}}, 20)).ok());
    // Painted: the swept disc of radius 10 around the centre line y = 30.
    EXPECT_EQ(canvas.coverage().at(50, 29, 0), 1.0f);
    EXPECT_EQ(canvas.coverage().at(50, 38, 0), 1.0f);
    EXPECT_EQ(canvas.coverage().at(50, 41, 0), 0.0f);
    EXPECT_EQ(canvas.coverage().at(2, 30, 0), 1.0f);  // the round cap
    EXPECT_NEAR(canvas.directions().at(50, 35, 0), 1.0f, 1e-6f);
    const Image d = diffuse_strokes(std::vector<Stroke>{stroke({{10, 30}, {90, 30}}, 20)}, 100, 60);
    EXPECT_NEAR(d.at(50, 29, 2), 1.0f, 2e-3f);  // 0.5 px from the centre line: w_s ~ 1
    EXPECT_GT(d.at(50, 40, 2), 0.3f);           // at the brush's edge (10.5 px)
    EXPECT_LT(d.at(50, 49, 2), 0.01f);          // 19.5 px: fading out towards the support
    EXPECT_EQ(d.at(50, 50, 2), 0.0f);           // 20.5 px, beyond the 20 px support: nothing
}

TEST(Strokes, PaintingIsStrictlyLocal) {
    PaintCanvas canvas(160, 120);
    ASSERT_TRUE(canvas.add_stroke(stroke({{20, 20}, {140, 30}, {150, 100}}, 30)).ok());
    const Image coverage = canvas.coverage(), directions = canvas.directions();
    const Stroke added = stroke({{30, 90}, {80, 70}}, 16);
    const auto changed = canvas.add_stroke(added);
    ASSERT_TRUE(changed.ok());
    int unchanged_far = 0, changed_near = 0;
    for (int y = 0; y < 120; ++y) {
        for (int x = 0; x < 160; ++x) {
            // Distance to the new stroke's segment.
            const double ax = 30, ay = 90, dx = 50, dy = -20;
            const double px = x + 0.5, py = y + 0.5;
            double t = ((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy);
            t = std::clamp(t, 0.0, 1.0);
            const double dist = std::hypot(px - ax - t * dx, py - ay - t * dy);
            const bool same = std::memcmp(directions.pixel(x, y), canvas.directions().pixel(x, y),
                                          2 * sizeof(float)) == 0 &&
                              coverage.at(x, y, 0) == canvas.coverage().at(x, y, 0);
            if (dist > added.width_px) {
                EXPECT_TRUE(same) << x << "," << y;
                unchanged_far += same ? 1 : 0;
            } else if (!same) {
                ++changed_near;
            }
            const bool in_rect =
                x >= changed->x0 && x < changed->x1 && y >= changed->y0 && y < changed->y1;
            if (!in_rect) {
                EXPECT_TRUE(same) << "outside the returned rectangle: " << x << "," << y;
            }
        }
    }
    EXPECT_GT(unchanged_far, 10000);
    EXPECT_GT(changed_near, 1000);
}

TEST(Strokes, CombingTurnsOnlyPaintedPixelsAndPaintsNothing) {
    PaintCanvas canvas(120, 80);
    ASSERT_TRUE(canvas.add_stroke(stroke({{10, 40}, {110, 40}}, 30)).ok());  // rightwards
    const Image coverage = canvas.coverage(), before = canvas.directions();
    // Comb upwards across the middle, wider than the painted band.
    ASSERT_TRUE(canvas.add_stroke(stroke({{60, 79}, {60, 1}}, 20, /*comb=*/true)).ok());
    EXPECT_EQ(std::memcmp(coverage.data().data(), canvas.coverage().data().data(),
                          coverage.size() * sizeof(float)),
              0);
    // On the comb's centre line the painted direction now points up (y down on screen).
    EXPECT_NEAR(canvas.directions().at(59, 40, 1), -1.0f, 1e-3f);
    // Halfway out of the comb's support it is a blend of right and up.
    const float* blend = canvas.directions().pixel(69, 40);
    EXPECT_GT(blend[0], 0.2f);
    EXPECT_LT(blend[1], -0.2f);
    // Unpainted pixels under the comb keep their (painting-kernel) directions.
    for (int y = 0; y < 80; ++y) {
        for (int x = 40; x < 80; ++x) {
            if (coverage.at(x, y, 0) != 0.0f) continue;
            EXPECT_EQ(
                std::memcmp(before.pixel(x, y), canvas.directions().pixel(x, y), 2 * sizeof(float)),
                0)
                << x << "," << y;
        }
    }
}

TEST(Strokes, SimultaneousStrokesAreSummedBeforeTheBlend) {
    // A rightward and a downward stroke crossing: at the crossing the sum points diagonally.
    const std::vector<Stroke> both = {stroke({{10, 50}, {90, 50}}, 30),
                                      stroke({{50, 10}, {50, 90}}, 30)};
    const Image d = diffuse_strokes(both, 100, 100);
    EXPECT_NEAR(d.at(49, 49, 0), std::numbers::sqrt2_v<float> / 2, 2e-2f);
    EXPECT_NEAR(d.at(49, 49, 1), std::numbers::sqrt2_v<float> / 2, 2e-2f);
    PaintCanvas canvas(100, 100);
    ASSERT_TRUE(canvas.add_strokes(both).ok());
    EXPECT_NEAR(canvas.directions().at(49, 49, 0), d.at(49, 49, 0), 1e-6f);
}

TEST(Strokes, InvalidStrokesAreRejectedByField) {
    PaintCanvas canvas(10, 10);
    auto r = canvas.add_stroke(stroke({}, 10));
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.status().message().find("points"), std::string::npos);
    r = canvas.add_stroke(stroke({{1, 1}}, 0));
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.status().message().find("width"), std::string::npos);
    r = canvas.add_stroke(stroke({{1, NAN}}, 3));
    EXPECT_FALSE(r.ok());
    const std::vector<Stroke> mixed = {stroke({{1, 1}}, 3), stroke({{2, 2}}, 3, true)};
    EXPECT_FALSE(canvas.add_strokes(mixed).ok());
    // A single dab paints a disc and gives no direction.
    ASSERT_TRUE(canvas.add_stroke(stroke({{5, 5}}, 4)).ok());
    EXPECT_EQ(canvas.coverage().at(5, 5, 0), 1.0f);
    EXPECT_EQ(canvas.directions().at(5, 5, 0), 0.0f);
}

}  // namespace
}  // namespace exemplar::paint
