// The line-feature brush of Painting by Feature (thesis §3.3.1), tested against the chapter's
// claims (Fig. 3.3 and the text): the randomized walk has no period where looping has one, its
// discontinuity cost stays within a bounded factor of the optimal (dynamic programming) walk's,
// a longer stroke never changes what is already drawn, blending lowers the colour jump at the
// walk's discontinuities, and the snapped path lies on the palette's edge (a known one, and the
// Canny edge of the bundled painting). Synthetic palettes otherwise.

#include "exemplar/paint/feature_brush.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "exemplar/core/rng.hpp"
#include "exemplar/filters/resample.hpp"
#include "exemplar/io/image_io.hpp"

namespace exemplar::paint {
namespace {

float noise(int x, int y, std::uint64_t salt) {
    return static_cast<float>(
               hash_keys(salt, static_cast<std::uint64_t>(x), static_cast<std::uint64_t>(y)) >>
               40) /
           16777216.0f;
}

// Smooth 1D value noise in [0, 1): random values every `cell` px, smoothstep in between.
float value_noise(float x, float cell, std::uint64_t salt) {
    const float t = x / cell;
    const int i = static_cast<int>(std::floor(t));
    const float f = t - static_cast<float>(i), s = f * f * (3.0f - 2.0f * f);
    return noise(i, 0, salt) + s * (noise(i + 1, 0, salt) - noise(i, 0, salt));
}

// A horizontal line feature along y = 32 of a 400 × 64 palette: a dark band whose thickness and
// darkness vary along x without a period (smooth random noise), on a light textured ground, with
// a colour drift along x of strength `drift` (a base-layer change the walk's jumps expose).
Image line_palette(float drift = 0.0f) {
    Image image(400, 64, 3);
    for (int y = 0; y < image.height(); ++y) {
        for (int x = 0; x < image.width(); ++x) {
            const float fx = static_cast<float>(x);
            const float half =
                3.0f + 6.0f * value_noise(fx, 24.0f, 1) + 3.0f * value_noise(fx, 7.0f, 2);
            const float dark =
                0.3f + 0.4f * value_noise(fx, 30.0f, 4) + 0.2f * value_noise(fx, 5.0f, 5);
            const float inside = std::clamp(
                half + 0.5f - std::abs(static_cast<float>(y) + 0.5f - 32.0f), 0.0f, 1.0f);
            const float grain = 0.15f * (noise(x, y, 7) - 0.5f);
            const float shift = drift * (fx / 400.0f - 0.5f);
            const float luma = 0.85f + grain - inside * dark;
            image.at(x, y, 0) = std::clamp(luma + shift, 0.0f, 1.0f);
            image.at(x, y, 1) = std::clamp(luma, 0.0f, 1.0f);
            image.at(x, y, 2) = std::clamp(luma - shift, 0.0f, 1.0f);
        }
    }
    return image;
}

Stroke selection() {
    return Stroke{{{8.0f, 32.0f}, {392.0f, 32.0f}}, 32.0f, false};
}

FeatureBrushOptions with_walk(WalkMode mode) {
    FeatureBrushOptions options;
    options.walk = mode;
    return options;
}

// Mean luma of each column of the stroke's layer over rows [y0, y1): the output along the path.
std::vector<double> column_profile(const Image& layer, int y0, int y1, int x0, int x1) {
    std::vector<double> profile;
    for (int x = x0; x < x1; ++x) {
        double sum = 0.0;
        for (int y = y0; y < y1; ++y) {
            const float* p = layer.pixel(x, y);
            sum += (p[0] + p[1] + p[2]) / 3.0;
        }
        profile.push_back(sum / (y1 - y0));
    }
    return profile;
}

// Largest normalized autocorrelation of `signal` over lags [min_lag, max_lag].
double autocorrelation_peak(const std::vector<double>& signal, int min_lag, int max_lag) {
    double mean = 0.0;
    for (double v : signal) mean += v;
    mean /= static_cast<double>(signal.size());
    double variance = 0.0;
    for (double v : signal) variance += (v - mean) * (v - mean);
    double peak = -1.0;
    for (int lag = min_lag; lag <= max_lag; ++lag) {
        double sum = 0.0;
        for (std::size_t i = 0; i + lag < signal.size(); ++i)
            sum += (signal[i] - mean) * (signal[i + lag] - mean);
        // Normalized by the overlap so that long lags are not favoured or penalized.
        const double r = sum / variance * static_cast<double>(signal.size()) /
                         static_cast<double>(signal.size() - lag);
        peak = std::max(peak, r);
    }
    return peak;
}

// A long straight stroke (4000 px) from a 384 px feature, profile of its central rows.
std::vector<double> long_stroke_profile(WalkMode mode) {
    auto feature = LineFeature::create(line_palette(), selection(), with_walk(mode), 2);
    EXPECT_TRUE(feature.ok()) << feature.status().message();
    BrushStroke stroke(*feature, 4040, 48, 32.0f, 0, 2);
    EXPECT_TRUE(stroke.add_points(std::vector<StrokePoint>{{20.0f, 24.0f}, {4020.0f, 24.0f}}).ok());
    return column_profile(stroke.layer(), 12, 36, 24, 4016);
}

// Measured: looping 1.00, randomized 0.29 (the chapter's walk without the shift memory: 0.996).
TEST(FeatureWalk, RandomizedHasNoPeriodWhereLoopingHasOne) {
    // Lags from a patch width up to a fifth of the stroke (many repeats of any period).
    const double looping = autocorrelation_peak(long_stroke_profile(WalkMode::Looping), 32, 800);
    const double randomized =
        autocorrelation_peak(long_stroke_profile(WalkMode::Randomized), 32, 800);
    EXPECT_GT(looping, 0.9);
    EXPECT_LT(randomized, 0.5);
}

// Measured: 0.89.
TEST(FeatureWalk, DynamicProgrammingCyclesTheCheapestLoop) {
    const double dp =
        autocorrelation_peak(long_stroke_profile(WalkMode::DynamicProgramming), 32, 800);
    EXPECT_GT(dp, 0.8);
}

// Measured over 2000 samples: 1.8-2.4 times the optimum for seeds 1-3.
TEST(FeatureWalk, RandomizedCostStaysWithinAFactorOfTheOptimum) {
    auto feature = LineFeature::create(line_palette(), selection(), {}, 2);
    ASSERT_TRUE(feature.ok());
    const int length = 2000;
    const double optimum =
        walk_cost(*feature, feature_walk(*feature, WalkMode::DynamicProgramming, length, 1));
    const double looping =
        walk_cost(*feature, feature_walk(*feature, WalkMode::Looping, length, 1));
    EXPECT_LE(optimum, looping + 1e-9);
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        const std::vector<int> walk = feature_walk(*feature, WalkMode::Randomized, length, seed);
        ASSERT_EQ(walk.size(), static_cast<std::size_t>(length));
        // Every step is an edge of the graph (finite cost).
        const double cost = walk_cost(*feature, walk);
        EXPECT_TRUE(std::isfinite(cost));
        EXPECT_GE(cost, optimum - 1e-9);
        EXPECT_LE(cost, 3.0 * optimum) << "seed " << seed << ": " << cost << " vs " << optimum;
    }
}

TEST(FeatureWalk, GraphStepsAlongTheSourceForFree) {
    auto feature = LineFeature::create(line_palette(), selection(), {}, 1);
    ASSERT_TRUE(feature.ok());
    const int n = feature->size();
    EXPECT_EQ(n, 193);  // 384 px every 2 px, both ends
    for (int i = 0; i + 1 < n; ++i) EXPECT_EQ(feature->cost(i, i + 1), 0.0f);
    for (int i = 0; i < n; ++i) EXPECT_TRUE(std::isinf(feature->cost(i, 0)));
    // w(i, j) = SSD(p(i), p(j − 1)) is the patch distance of i and j − 1, which is symmetric.
    EXPECT_FLOAT_EQ(feature->cost(10, 101), feature->cost(100, 11));
    EXPECT_GT(feature->cost(10, 101), 0.0f);
}

TEST(FeatureWalk, RandomizedWalkIsPrefixStable) {
    auto feature = LineFeature::create(line_palette(), selection(), {}, 1);
    ASSERT_TRUE(feature.ok());
    const std::vector<int> shorter = feature_walk(*feature, WalkMode::Randomized, 300, 5);
    const std::vector<int> longer = feature_walk(*feature, WalkMode::Randomized, 1200, 5);
    EXPECT_TRUE(std::equal(shorter.begin(), shorter.end(), longer.begin()));
    EXPECT_NE(feature_walk(*feature, WalkMode::Randomized, 300, 6), shorter);
}

// A sine-shaped path along x from x = 20 to `x_end`, a point every 4 px.
std::vector<StrokePoint> wave(float x_from, float x_to) {
    std::vector<StrokePoint> points;
    for (float x = x_from; x <= x_to + 1e-3f; x += 4.0f)
        points.push_back({x, 70.0f + 25.0f * std::sin(x / 70.0f)});
    return points;
}

TEST(BrushStroke, ExtendingTheStrokeChangesNoSettledPixel) {
    auto feature = LineFeature::create(line_palette(), selection(), {}, 2);
    ASSERT_TRUE(feature.ok());
    BrushStroke stroke(*feature, 1060, 140, 32.0f, 0, 2);
    // About 500 px of path, then extended to about 1000 px a few points at a time.
    ASSERT_TRUE(stroke.add_points(wave(20.0f, 480.0f)).ok());
    const Image first = stroke.layer();
    const int settled = stroke.settled_samples();
    std::vector<int> owners;
    for (int y = 0; y < first.height(); ++y)
        for (int x = 0; x < first.width(); ++x) owners.push_back(stroke.nearest_sample(x, y));
    // Everything but the last brush width or so is settled.
    EXPECT_GE(settled, stroke.samples() - 20);
    const std::vector<StrokePoint> rest = wave(484.0f, 940.0f);
    for (std::size_t i = 0; i < rest.size(); i += 7) {
        const std::size_t end = std::min(rest.size(), i + 7);
        ASSERT_TRUE(stroke.add_points({rest.data() + i, end - i}).ok());
    }
    int compared = 0;
    for (int y = 0; y < first.height(); ++y) {
        for (int x = 0; x < first.width(); ++x) {
            const int owner = owners[static_cast<std::size_t>(y) * first.width() + x];
            if (owner < 0 || owner >= settled) continue;
            ++compared;
            ASSERT_EQ(std::memcmp(first.pixel(x, y), stroke.layer().pixel(x, y), 4 * sizeof(float)),
                      0)
                << "pixel " << x << ", " << y;
        }
    }
    EXPECT_GT(compared, 400 * 30);

    // Growing it point by point gives the same bytes as drawing it at once, on any threads.
    std::vector<StrokePoint> all = wave(20.0f, 940.0f);
    BrushStroke at_once(*feature, 1060, 140, 32.0f, 0, 1);
    ASSERT_TRUE(at_once.add_points(all).ok());
    EXPECT_EQ(std::memcmp(at_once.layer().data().data(), stroke.layer().data().data(),
                          at_once.layer().size() * sizeof(float)),
              0);
}

TEST(BrushStroke, ACancelTokenStopsItAndLeavesTheBytesAloneUnset) {
    auto feature = LineFeature::create(line_palette(), selection(), {}, 2);
    ASSERT_TRUE(feature.ok());
    const std::vector<StrokePoint> points = wave(20.0f, 940.0f);
    BrushStroke plain(*feature, 1060, 140, 32.0f, 0, 2),
        with_token(*feature, 1060, 140, 32.0f, 0, 2);
    CancelToken token;
    auto a = plain.add_points(points);
    auto b = with_token.add_points(points, &token);
    ASSERT_TRUE(a.ok() && b.ok());
    EXPECT_EQ(std::memcmp(plain.layer().data().data(), with_token.layer().data().data(),
                          plain.layer().size() * sizeof(float)),
              0);
    token.cancel();
    BrushStroke stopped(*feature, 1060, 140, 32.0f, 0, 2);
    EXPECT_EQ(stopped.add_points(points, &token).status().code(), ErrorCode::Cancelled);
}

TEST(BrushStroke, ChangedRectangleHoldsEveryChange) {
    auto feature = LineFeature::create(line_palette(), selection(), {}, 1);
    ASSERT_TRUE(feature.ok());
    BrushStroke stroke(*feature, 600, 140, 24.0f, 3, 1);
    const std::vector<StrokePoint> points = wave(20.0f, 560.0f);
    Image before = stroke.layer();
    for (std::size_t i = 0; i < points.size(); i += 5) {
        const std::size_t end = std::min(points.size(), i + 5);
        auto changed = stroke.add_points({points.data() + i, end - i});
        ASSERT_TRUE(changed.ok());
        for (int y = 0; y < before.height(); ++y) {
            for (int x = 0; x < before.width(); ++x) {
                const bool inside =
                    x >= changed->x0 && x < changed->x1 && y >= changed->y0 && y < changed->y1;
                if (!inside) {
                    ASSERT_EQ(std::memcmp(before.pixel(x, y), stroke.layer().pixel(x, y),
                                          4 * sizeof(float)),
                              0);
                }
            }
        }
        before = stroke.layer();
    }
}

// Mean colour difference between the pixel columns on both sides of each interior jump of the
// walk, over the stroke's central rows (a straight stroke along y = 24 from x = 20).
double mean_jump_step(const BrushStroke& stroke, float spacing) {
    const std::span<const int> walk = stroke.walk();
    double total = 0.0;
    int jumps = 0;
    for (int b = 8; b + 8 < stroke.samples(); ++b) {
        if (walk[static_cast<std::size_t>(b)] == walk[static_cast<std::size_t>(b - 1)] + 1)
            continue;
        const int x =
            static_cast<int>(std::lround(20.0f + (static_cast<float>(b) - 0.5f) * spacing));
        double step = 0.0;
        for (int y = 14; y < 34; ++y) {
            for (int c = 0; c < 3; ++c)
                step += std::abs(stroke.layer().at(x, y, c) - stroke.layer().at(x - 1, y, c));
        }
        total += step / (20 * 3);
        ++jumps;
    }
    EXPECT_GT(jumps, 5);
    return total / std::max(jumps, 1);
}

// Measured: mean step 0.050 with blending, 0.138 without.
TEST(BrushStroke, BlendingLowersTheColourJumpAtDiscontinuities) {
    const Image palette = line_palette(0.5f);
    FeatureBrushOptions sharp;
    sharp.blend_radius_px = 0.0f;
    auto blended = LineFeature::create(palette, selection(), {}, 1);
    auto unblended = LineFeature::create(palette, selection(), sharp, 1);
    ASSERT_TRUE(blended.ok() && unblended.ok());
    const std::vector<StrokePoint> path{{20.0f, 24.0f}, {2020.0f, 24.0f}};
    BrushStroke a(*blended, 2040, 48, 32.0f, 0, 1), b(*unblended, 2040, 48, 32.0f, 0, 1);
    ASSERT_TRUE(a.add_points(path).ok() && b.add_points(path).ok());
    ASSERT_TRUE(std::equal(a.walk().begin(), a.walk().end(), b.walk().begin()));
    const double with = mean_jump_step(a, 2.0f), without = mean_jump_step(b, 2.0f);
    EXPECT_LT(with, 0.6 * without) << with << " vs " << without;
}

// A dark-over-light edge along y = 60 + 12 sin(2πx / 160) with grain.
float edge_y(float x) {
    return 60.0f + 12.0f * std::sin(2.0f * std::numbers::pi_v<float> * x / 160.0f);
}

double distance_to_edge(StrokePoint p) {
    double best = 1e9;
    for (float x = p.x - 20.0f; x <= p.x + 20.0f; x += 0.05f)
        best = std::min(best, std::hypot(static_cast<double>(x - p.x), edge_y(x) - p.y));
    return best;
}

// Measured: the rough path 4.25 px from the edge on average, the snapped one 0.32 (at most 1.12).
TEST(SnapToEdges, SnappedPathLiesOnThePalettesEdge) {
    Image palette(200, 120, 3);
    for (int y = 0; y < palette.height(); ++y) {
        for (int x = 0; x < palette.width(); ++x) {
            const float fy = static_cast<float>(y) + 0.5f;
            const float side =
                std::clamp(fy - edge_y(static_cast<float>(x) + 0.5f) + 0.5f, 0.0f, 1.0f);
            const float v = 0.2f + 0.6f * side + 0.1f * (noise(x, y, 3) - 0.5f);
            for (int c = 0; c < 3; ++c) palette.at(x, y, c) = v;
        }
    }
    std::vector<StrokePoint> rough;
    for (int i = 0; i <= 16; ++i) {
        const float x = 20.0f + 10.0f * static_cast<float>(i);
        rough.push_back({x, edge_y(x) + (i % 2 == 0 ? 4.0f : 5.0f)});
    }
    auto snapped = snap_to_edges(palette, rough);
    ASSERT_TRUE(snapped.ok()) << snapped.status().message();
    ASSERT_GE(snapped->size(), 30u);
    double mean = 0.0, worst = 0.0, rough_mean = 0.0;
    for (StrokePoint p : *snapped) {
        const double d = distance_to_edge(p);
        mean += d;
        worst = std::max(worst, d);
    }
    mean /= static_cast<double>(snapped->size());
    for (StrokePoint p : rough)
        rough_mean += distance_to_edge(p) / static_cast<double>(rough.size());
    EXPECT_GT(rough_mean, 3.5);
    EXPECT_LT(mean, 1.0);
    EXPECT_LT(worst, 2.0);
}

// Canny's edge pixels (Canny 1986) of an image's mean colour: Gaussian blur (σ = 2 px), Sobel
// gradient, non-maximum suppression across the edge (four directions), hysteresis between 10% and
// 25% of the largest gradient magnitude. 1 on the edge, 0 elsewhere.
std::vector<std::uint8_t> canny_edges(const Image& image) {
    const int w = image.width(), h = image.height();
    Image luma(w, h, 1);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const int colours = std::min(3, image.channels());
            for (int c = 0; c < colours; ++c) luma.at(x, y, 0) += image.at(x, y, c) / colours;
        }
    }
    const Image blurred = gaussian_blur(luma, 2.0f, 1);
    auto at = [&](int x, int y) {
        return blurred.at(std::clamp(x, 0, w - 1), std::clamp(y, 0, h - 1), 0);
    };
    std::vector<float> gx(static_cast<std::size_t>(w) * h), gy(gx.size()), mag(gx.size());
    float largest = 0.0f;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * w + x;
            gx[i] = at(x + 1, y - 1) + 2 * at(x + 1, y) + at(x + 1, y + 1) - at(x - 1, y - 1) -
                    2 * at(x - 1, y) - at(x - 1, y + 1);
            gy[i] = at(x - 1, y + 1) + 2 * at(x, y + 1) + at(x + 1, y + 1) - at(x - 1, y - 1) -
                    2 * at(x, y - 1) - at(x + 1, y - 1);
            mag[i] = std::hypot(gx[i], gy[i]);
            largest = std::max(largest, mag[i]);
        }
    }
    // 0 = suppressed, 1 = weak, 2 = strong.
    std::vector<std::uint8_t> kind(gx.size(), 0);
    for (int y = 1; y + 1 < h; ++y) {
        for (int x = 1; x + 1 < w; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * w + x;
            const float angle = std::atan2(gy[i], gx[i]) * 180.0f / std::numbers::pi_v<float>;
            const int sector = static_cast<int>(std::lround((angle + 180.0f) / 45.0f)) % 4;
            const int dx = sector == 0 ? 1 : sector == 2 ? 0 : sector == 1 ? 1 : -1;
            const int dy = sector == 0 ? 0 : 1;
            const float m = mag[i];
            if (m < mag[i + dx + static_cast<std::size_t>(dy) * w] ||
                m < mag[i - dx - static_cast<std::size_t>(dy) * w])
                continue;
            kind[i] = m >= 0.25f * largest ? 2 : m >= 0.10f * largest ? 1 : 0;
        }
    }
    std::vector<std::uint8_t> edge(gx.size(), 0);
    std::vector<std::size_t> stack;
    for (std::size_t i = 0; i < kind.size(); ++i) {
        if (kind[i] == 2) stack.push_back(i);
    }
    while (!stack.empty()) {
        const std::size_t i = stack.back();
        stack.pop_back();
        if (edge[i]) continue;
        edge[i] = 1;
        const int x = static_cast<int>(i % w), y = static_cast<int>(i / w);
        for (int ny = std::max(0, y - 1); ny <= std::min(h - 1, y + 1); ++ny) {
            for (int nx = std::max(0, x - 1); nx <= std::min(w - 1, x + 1); ++nx) {
                const std::size_t j = static_cast<std::size_t>(ny) * w + nx;
                if (kind[j] > 0 && !edge[j]) stack.push_back(j);
            }
        }
    }
    return edge;
}

// Distance from p to the nearest edge pixel's centre.
double distance_to_canny(const std::vector<std::uint8_t>& edge, int w, StrokePoint p) {
    double best = 1e9;
    for (std::size_t i = 0; i < edge.size(); ++i) {
        if (!edge[i]) continue;
        best = std::min(best, std::hypot(static_cast<double>(i % w) + 0.5 - p.x,
                                         static_cast<double>(i / w) + 0.5 - p.y));
    }
    return best;
}

// The bundled Scream crop and the example's rough path along its railing (examples/feature):
// snapped, the path lies on the Canny edge of the painting. Measured: the rough path 1.52 px from
// the nearest edge pixel on average (a painting has edges everywhere), the snapped one 0.48 px,
// none of its 41 points more than 2 px off.
TEST(SnapToEdges, SnappedPathLiesOnTheCannyEdgeOfAPainting) {
    auto palette =
        load_image(std::string(EXEMPLAR_SOURCE_DIR) + "/examples/feature/scream_railing.png");
    ASSERT_TRUE(palette.ok()) << palette.status().message();
    const std::vector<StrokePoint> rough = {{25, 39}, {90, 84}, {155, 130}};  // railing.json
    auto snapped = snap_to_edges(*palette, rough);
    ASSERT_TRUE(snapped.ok()) << snapped.status().message();
    const std::vector<std::uint8_t> edge = canny_edges(*palette);
    const int w = palette->width();
    double snapped_mean = 0.0, rough_mean = 0.0;
    int far = 0;
    for (StrokePoint p : *snapped) {
        const double d = distance_to_canny(edge, w, p);
        snapped_mean += d / static_cast<double>(snapped->size());
        far += d > 2.0 ? 1 : 0;
    }
    // The rough path as the contour starts from it (resampled every snap spacing).
    int samples = 0;
    for (std::size_t k = 0; k + 1 < rough.size(); ++k) {
        for (int t = 0; t < 20; ++t) {
            const float f = static_cast<float>(t) / 20.0f;
            rough_mean += distance_to_canny(edge, w,
                                            {rough[k].x + f * (rough[k + 1].x - rough[k].x),
                                             rough[k].y + f * (rough[k + 1].y - rough[k].y)});
            ++samples;
        }
    }
    rough_mean /= samples;
    std::printf("distance to the Canny edge: rough %.2f px, snapped %.2f px (%d of %zu > 2 px)\n",
                rough_mean, snapped_mean, far, snapped->size());
    EXPECT_LT(snapped_mean, 1.0);
    EXPECT_LT(snapped_mean, 0.5 * rough_mean);
    EXPECT_LE(far, static_cast<int>(snapped->size()) / 10);
}

TEST(LineFeature, RejectsBadSelections) {
    const Image palette = line_palette();
    auto one_point = LineFeature::create(palette, Stroke{{{10.0f, 10.0f}}, 20.0f, false});
    ASSERT_FALSE(one_point.ok());
    EXPECT_NE(one_point.status().message().find("needs at least 2"), std::string::npos);
    auto outside =
        LineFeature::create(palette, Stroke{{{10.0f, 10.0f}, {500.0f, 10.0f}}, 20.0f, false});
    ASSERT_FALSE(outside.ok());
    EXPECT_EQ(outside.status().message(),
              "feature: point (500, 10) lies outside the palette (400x64)");
    auto short_path =
        LineFeature::create(palette, Stroke{{{10.0f, 10.0f}, {11.0f, 10.0f}}, 20.0f, false});
    ASSERT_FALSE(short_path.ok());
    EXPECT_NE(short_path.status().message().find("shorter than the sample spacing"),
              std::string::npos);
    FeatureBrushOptions bad;
    bad.sample_spacing_px = 0.0f;
    auto bad_options = LineFeature::create(palette, selection(), bad);
    ASSERT_FALSE(bad_options.ok());
    EXPECT_EQ(bad_options.status().message(), "sample-spacing: 0 is invalid (must be 0.5..64)");
    EXPECT_FALSE(parse_walk_mode("zigzag").ok());
    EXPECT_EQ(*parse_walk_mode("dp"), WalkMode::DynamicProgramming);
}

TEST(PaintFeature, GreyAndRgbaPalettesKeepTheirChannels) {
    // Grey: replicated to RGB. RGBA: the palette's alpha times the coverage.
    const Image rgb = line_palette();
    Image grey(rgb.width(), rgb.height(), 1), rgba(rgb.width(), rgb.height(), 4);
    for (int y = 0; y < rgb.height(); ++y) {
        for (int x = 0; x < rgb.width(); ++x) {
            grey.at(x, y, 0) = rgb.at(x, y, 1);
            for (int c = 0; c < 3; ++c) rgba.at(x, y, c) = rgb.at(x, y, c);
            rgba.at(x, y, 3) = 0.5f;
        }
    }
    const std::vector<Stroke> path{Stroke{{{10.0f, 30.0f}, {290.0f, 30.0f}}, 32.0f, false}};
    auto from_grey = LineFeature::create(grey, selection(), {}, 1);
    auto from_rgba = LineFeature::create(rgba, selection(), {}, 1);
    ASSERT_TRUE(from_grey.ok() && from_rgba.ok());
    auto a = paint_feature(*from_grey, path, 300, 60, 0.0f, 1);
    auto b = paint_feature(*from_rgba, path, 300, 60, 0.0f, 1);
    ASSERT_TRUE(a.ok() && b.ok());
    EXPECT_EQ(a->at(150, 30, 3), 1.0f);
    EXPECT_EQ(a->at(150, 30, 0), a->at(150, 30, 2));
    EXPECT_NEAR(b->at(150, 30, 3), 0.5f, 1e-6f);
    EXPECT_EQ(b->at(150, 5, 3), 0.0f);  // outside the 32 px brush
}

TEST(PaintFeature, SameBytesForAnyThreadCount) {
    auto feature = LineFeature::create(line_palette(0.3f), selection(), {}, 0);
    ASSERT_TRUE(feature.ok());
    const std::vector<Stroke> paths{Stroke{wave(20.0f, 300.0f), 24.0f, false},
                                    Stroke{{{30.0f, 20.0f}, {280.0f, 120.0f}}, 40.0f, false}};
    auto one = paint_feature(*feature, paths, 320, 140, 0.0f, 1);
    auto two = paint_feature(*feature, paths, 320, 140, 0.0f, 2);
    ASSERT_TRUE(one.ok() && two.ok());
    EXPECT_EQ(std::memcmp(one->data().data(), two->data().data(), one->size() * sizeof(float)), 0);
    // Something was painted, and the second path (over the first) shows its own walk.
    double alpha = 0.0;
    for (int y = 0; y < 140; ++y)
        for (int x = 0; x < 320; ++x) alpha += one->at(x, y, 3);
    EXPECT_GT(alpha, 0.8 * (280.0 * 24.0 + 270.0 * 40.0) * 0.8);
}

TEST(PaintFeature, PickLineFeatureSnapsThenCreates) {
    const Image palette = line_palette();
    auto unsnapped = pick_line_feature(palette, selection(), {}, false, 1);
    auto created = LineFeature::create(palette, selection(), {}, 1);
    ASSERT_TRUE(unsnapped.ok() && created.ok());
    ASSERT_EQ(unsnapped->size(), created->size());
    EXPECT_EQ(unsnapped->samples()[0].y, created->samples()[0].y);
    Stroke snapped_selection = selection();
    auto snapped_points = snap_to_edges(palette, snapped_selection.points);
    ASSERT_TRUE(snapped_points.ok());
    snapped_selection.points = *snapped_points;
    auto snapped = pick_line_feature(palette, selection(), {}, true, 1);
    auto expected = LineFeature::create(palette, snapped_selection, {}, 1);
    ASSERT_TRUE(snapped.ok() && expected.ok());
    ASSERT_EQ(snapped->size(), expected->size());
    EXPECT_EQ(snapped->samples()[1].x, expected->samples()[1].x);
    EXPECT_EQ(snapped->samples()[1].y, expected->samples()[1].y);
    EXPECT_EQ(paint_feature(*created, {}, 10, 10).status().message(),
              "paths: none given (must be at least one)");
    const std::vector<Stroke> path{Stroke{{{1.0f, 5.0f}, {9.0f, 5.0f}}, 4.0f, false}};
    EXPECT_FALSE(paint_feature(*created, path, 10, 10, -1.0f).ok());
}

}  // namespace
}  // namespace exemplar::paint
