// Brushables synthesis (§3.3) on small procedural exemplars: direction awareness, alpha, the
// coherence-weighted vote (Fig. 7), incremental repainting, determinism and input errors.

#include "exemplar/paint/paint.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <vector>

#include "colour_histogram.hpp"
#include "exemplar/filters/resample.hpp"

namespace exemplar::paint {
namespace {

float hash01(int x, int y, int salt) {
    std::uint32_t h = static_cast<std::uint32_t>(x) * 73856093u ^
                      static_cast<std::uint32_t>(y) * 19349663u ^
                      static_cast<std::uint32_t>(salt) * 83492791u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return static_cast<float>(h & 0xffffu) / 65535.0f;
}

// Horizontal stripes (period 8 px) with grain, opaque inside a disc of radius `radius`, alpha
// fading to 0 over 3 px at its edge; directions: 0 (rightwards) everywhere.
PaintSource striped_blob(int size, float radius) {
    PaintSource s;
    s.image = Image(size, size, 4);
    const float c = 0.5f * static_cast<float>(size - 1);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const float stripe = 0.5f + 0.4f * std::sin(static_cast<float>(y) * 0.785398f);
            const float grain = 0.1f * (hash01(x, y, 1) - 0.5f);
            const float r = std::hypot(static_cast<float>(x) - c, static_cast<float>(y) - c);
            float* p = s.image.pixel(x, y);
            p[0] = stripe + grain;
            p[1] = 0.8f * stripe + grain;
            p[2] = 0.3f + grain;
            p[3] = std::clamp((radius - r) / 3.0f, 0.0f, 1.0f);
        }
    }
    s.directions = Image(size, size, 1);
    return s;
}

Stroke stroke(std::vector<StrokePoint> points, float width, bool comb = false) {
    Stroke s;
    s.points = std::move(points);
    s.width_px = width;
    s.comb = comb;
    return s;
}

// Mean absolute luma difference along x and along y over opaque interior pixels.
std::pair<double, double> variation(const Image& rgba) {
    double dx = 0.0, dy = 0.0;
    int n = 0;
    for (int y = 0; y + 1 < rgba.height(); ++y) {
        for (int x = 0; x + 1 < rgba.width(); ++x) {
            if (rgba.at(x, y, 3) < 0.99f || rgba.at(x + 1, y, 3) < 0.99f ||
                rgba.at(x, y + 1, 3) < 0.99f) {
                continue;
            }
            dx += std::abs(rgba.at(x + 1, y, 0) - rgba.at(x, y, 0));
            dy += std::abs(rgba.at(x, y + 1, 0) - rgba.at(x, y, 0));
            ++n;
        }
    }
    return {dx / n, dy / n};
}

TEST(Paint, StripesFollowTheStrokeDirection) {
    const PaintSource source = striped_blob(64, 30);
    PaintCanvas down(64, 96), across(96, 64);
    ASSERT_TRUE(down.add_stroke(stroke({{32, 8}, {32, 88}}, 36)).ok());
    ASSERT_TRUE(across.add_stroke(stroke({{8, 32}, {88, 32}}, 36)).ok());
    const auto a = paint(source, down, {}, RunContext(2));
    const auto b = paint(source, across, {}, RunContext(2));
    ASSERT_TRUE(a.ok()) << a.status().message();
    ASSERT_TRUE(b.ok()) << b.status().message();
    const auto [adx, ady] = variation(a->image);
    const auto [bdx, bdy] = variation(b->image);
    std::printf("stroke down: luma variation along x %.4f, along y %.4f; across: %.4f, %.4f\n", adx,
                ady, bdx, bdy);
    // A downward stroke turns the exemplar's horizontal stripes vertical: the colour changes
    // across x; a horizontal stroke keeps them horizontal.
    EXPECT_GT(adx, 2.0 * ady);
    EXPECT_GT(bdy, 2.0 * bdx);
}

TEST(Paint, AlphaIsSynthesizedAndZeroOutsideThePaintedRegion) {
    const PaintSource source = striped_blob(64, 30);
    PaintCanvas canvas(80, 80);
    ASSERT_TRUE(canvas.add_stroke(stroke({{10, 40}, {70, 40}}, 40)).ok());
    const auto r = paint(source, canvas, {}, RunContext(2));
    ASSERT_TRUE(r.ok()) << r.status().message();
    ASSERT_EQ(r->image.channels(), 4);
    int inside = 0, opaque = 0;
    for (int y = 0; y < 80; ++y) {
        for (int x = 0; x < 80; ++x) {
            const float a = r->image.at(x, y, 3);
            if (canvas.coverage().at(x, y, 0) == 0.0f) {
                EXPECT_EQ(a, 0.0f) << x << "," << y;
                continue;
            }
            // Deep inside the stroke (more than 8 px from its edge) the texture is opaque.
            if (std::abs(y + 0.5 - 40) < 12 && x > 20 && x < 60) {
                ++inside;
                opaque += a > 0.95f ? 1 : 0;
            }
        }
    }
    EXPECT_GT(opaque, inside * 95 / 100);
}

TEST(Paint, AnOpaqueExemplarLeavesNoDarkRim) {
    // An RGB exemplar has no boundary: the rim of the region must look like its interior. (This
    // small case does not show the dark rim that the transparent surroundings gave the stylit
    // pastel, a property check only: without the whole-canvas synthesis it measured 0.667
    // against 0.657 too.)
    PaintSource source;
    source.image = Image(48, 48, 3);
    for (int y = 0; y < 48; ++y) {
        for (int x = 0; x < 48; ++x) {
            const float v = hash01(x / 3, y / 3, 2) < 0.15f ? 0.05f : 0.6f + 0.2f * hash01(x, y, 3);
            for (int c = 0; c < 3; ++c) source.image.at(x, y, c) = v;
        }
    }
    PaintCanvas canvas(80, 48);
    ASSERT_TRUE(canvas.add_stroke(stroke({{10, 24}, {70, 24}}, 30)).ok());
    const auto r = paint(source, canvas, {}, RunContext(2));
    ASSERT_TRUE(r.ok()) << r.status().message();
    double rim = 0.0, inner = 0.0;
    int rim_n = 0, inner_n = 0;
    for (int y = 0; y < 48; ++y) {
        for (int x = 0; x < 80; ++x) {
            if (canvas.coverage().at(x, y, 0) == 0.0f) continue;
            EXPECT_EQ(r->image.at(x, y, 3), 1.0f) << x << "," << y;
            const double d = std::abs(y + 0.5 - 24.0);
            if (d > 12.0 && x > 16 && x < 64) {
                rim += r->image.at(x, y, 0);
                ++rim_n;
            } else if (d < 8.0 && x > 16 && x < 64) {
                inner += r->image.at(x, y, 0);
                ++inner_n;
            }
        }
    }
    rim /= rim_n;
    inner /= inner_n;
    std::printf("opaque exemplar: mean value on the rim %.3f, inside %.3f\n", rim, inner);
    EXPECT_GT(rim, 0.85 * inner);
}

TEST(Paint, SameBytesForOneAndTwoThreads) {
    const PaintSource source = striped_blob(48, 22);
    PaintCanvas canvas(64, 64);
    ASSERT_TRUE(canvas.add_stroke(stroke({{10, 50}, {30, 20}, {55, 30}}, 24)).ok());
    const auto a = paint(source, canvas, {}, RunContext(1));
    const auto b = paint(source, canvas, {}, RunContext(2));
    ASSERT_TRUE(a.ok() && b.ok());
    EXPECT_EQ(std::memcmp(a->image.data().data(), b->image.data().data(),
                          a->image.size() * sizeof(float)),
              0);
}

// Share of pixels (among those with a match) in coherent regions: 4-neighbours whose matches
// continue each other (within 0.5 px), joined by union-find; returns the pixel-weighted mean
// size of the region a pixel belongs to.
double mean_coherent_region(const Nnf& nnf, const Image& coverage) {
    const int w = nnf.width(), h = nnf.height();
    std::vector<int> parent(static_cast<std::size_t>(w) * h);
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    auto coherent = [&](int x, int y, int u, int v) {
        const Match& a = nnf.at(x, y);
        const Match& b = nnf.at(u, v);
        const float c = std::cos(a.angle_rad), s = std::sin(a.angle_rad);
        const float ox = static_cast<float>(u - x), oy = static_cast<float>(v - y);
        const float px = a.x + c * ox - s * oy, py = a.y + s * ox + c * oy;
        return std::hypot(px - b.x, py - b.y) <= 1.0f;
    };
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            if (coverage.at(x, y, 0) == 0.0f) continue;
            if (x + 1 < w && coverage.at(x + 1, y, 0) != 0.0f && coherent(x, y, x + 1, y)) {
                parent[find(y * w + x)] = find(y * w + x + 1);
            }
            if (y + 1 < h && coverage.at(x, y + 1, 0) != 0.0f && coherent(x, y, x, y + 1)) {
                parent[find(y * w + x)] = find((y + 1) * w + x);
            }
        }
    }
    std::vector<double> size(parent.size(), 0.0);
    double pixels = 0.0;
    for (int i = 0; i < w * h; ++i) {
        if (coverage.at(i % w, i / w, 0) == 0.0f) continue;
        size[find(i)] += 1.0;
        pixels += 1.0;
    }
    double weighted = 0.0;
    for (int i = 0; i < w * h; ++i) {
        if (coverage.at(i % w, i / w, 0) != 0.0f) weighted += size[find(i)];
    }
    return weighted / pixels;
}

TEST(Paint, CoherenceWeightGivesLargerCoherentRegions) {
    // Brushables Fig. 7: with rotations (a curved stroke) the coherence-weighted vote lets
    // larger coherently mapped areas form. Measured with the Shape Hint off: with it on (the
    // default) the regions are larger either way and the coherence weight made no measurable
    // difference (17.8 against 18.1 px on the first 3 seeds, before the turned target patches).
    // 12 seeds: the effect is smaller than the spread of 3 (with turned target patches seeds 1-3
    // gave 14.1 against 14.4 px).
    const PaintSource source = striped_blob(64, 30);
    PaintCanvas canvas(96, 96);
    ASSERT_TRUE(canvas.add_stroke(stroke({{10, 80}, {30, 30}, {70, 15}, {88, 60}}, 30)).ok());
    double with = 0.0, without = 0.0;
    constexpr int kSeeds = 12;
    for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
        PaintOptions options;
        options.seed = seed;
        options.shape_weight = 0.0f;
        options.vote_histogram = 0.0f;  // with it (the default): 13.0 against 12.2 px
        const auto a = paint(source, canvas, options, RunContext(2));
        options.vote_coherence = 0.0f;
        const auto b = paint(source, canvas, options, RunContext(2));
        ASSERT_TRUE(a.ok() && b.ok());
        with += mean_coherent_region(a->nnf, canvas.coverage()) / kSeeds;
        without += mean_coherent_region(b->nnf, canvas.coverage()) / kSeeds;
    }
    std::printf(
        "mean coherent NNF region (px, 12 seeds): with coherence weight %.1f, without %.1f\n", with,
        without);
    // Measured 18.4 against 16.0 px (whole-image search windows: 17.3 against 15.1; turned source
    // patches as well: 15.3 against 11.9).
    EXPECT_GT(with, 1.08 * without);
}

// An opaque 64x64 exemplar of 4x4 cells, each of one colour with grain: blue (70% of the
// cells), light blue (20%) or yellow (10%), or with `flecks` yellow cells alone on a flat blue.
PaintSource cells_exemplar(bool flecks) {
    PaintSource source;
    const int size = 64;
    source.image = Image(size, size, 4);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const float pick = hash01(x / 4, y / 4, 7);
            const float grain = 0.08f * (hash01(x, y, 2) - 0.5f);
            float* p = source.image.pixel(x, y);
            const bool yellow = pick < 0.1f, light = !flecks && pick >= 0.1f && pick < 0.3f;
            p[0] = (yellow ? 0.95f : light ? 0.45f : 0.15f) + grain;
            p[1] = (yellow ? 0.85f : light ? 0.70f : 0.25f) + grain;
            p[2] = (yellow ? 0.20f : light ? 0.95f : 0.60f) + grain;
            p[3] = 1.0f;
        }
    }
    source.directions = Image(size, size, 1);
    return source;
}

// Mean over R, G, B of the L1 distance between the 16-bin histograms of the exemplar and of the
// painted (alpha > 0.5) pixels: 0 = the same colour distribution, 2 = disjoint.
double histogram_distance(const Image& exemplar, const Image& painted) {
    return testing::histogram_distance({exemplar, exemplar, 3}, {painted, painted, 3});
}

Result<PaintResult> paint_curve(const PaintSource& source, PaintOptions options) {
    PaintCanvas canvas(112, 96);
    EXEMPLAR_RETURN_IF_ERROR(
        canvas.add_stroke(stroke({{10, 80}, {35, 25}, {75, 15}, {100, 70}}, 28)).status());
    return paint(source, canvas, options, RunContext(2));
}

// Brushables eq. 7's colour-histogram weight (after Kopf et al. 2007) along a curved stroke: the
// plain vote averages the exemplar's minority colours into its majority blue (rotated patches
// rarely agree on them); the weight favours what the painting lacks, so its colour
// distribution comes closer to the exemplar's.
TEST(Paint, HistogramWeightKeepsTheExemplarsColourDistribution) {
    const PaintSource source = cells_exemplar(false);
    double with = 0.0, without = 0.0;
    for (std::uint64_t seed = 1; seed <= 2; ++seed) {
        PaintOptions options;
        options.seed = seed;
        const auto a = paint_curve(source, options);
        options.vote_histogram = 0.0f;
        const auto b = paint_curve(source, options);
        ASSERT_TRUE(a.ok() && b.ok());
        with += histogram_distance(source.image, a->image) / 2.0;
        without += histogram_distance(source.image, b->image) / 2.0;
    }
    std::printf("histogram distance to the exemplar: weight 1 %.3f, off %.3f\n", with, without);
    EXPECT_LT(with, 0.85 * without);  // measured 0.47 against 0.72 (before: 0.53 against 0.77)
}

// A limit of the paper's plain EM that no vote weight lifts: sparse yellow flecks on a flat blue
// wash out to the blue (the search never picks a patch that disagrees with the blue estimate),
// with or without the histogram weight. Uniform usage (LazyFluids) keeps them.
TEST(Paint, UniformUsageKeepsSparseFlecksThatPlainEmWashesOut) {
    const PaintSource source = cells_exemplar(true);
    auto yellow_share = [](const Image& rgba) {
        int yellow = 0, n = 0;
        for (int y = 0; y < rgba.height(); ++y) {
            for (int x = 0; x < rgba.width(); ++x) {
                if (rgba.at(x, y, 3) <= 0.5f) continue;
                ++n;
                yellow += rgba.at(x, y, 0) > 0.55f;
            }
        }
        return static_cast<double>(yellow) / n;
    };
    PaintOptions options;
    const auto plain = paint_curve(source, options);
    options.usage = UsageStrategy::Uniform;
    const auto uniform = paint_curve(source, options);
    ASSERT_TRUE(plain.ok() && uniform.ok());
    const double exemplar = yellow_share(source.image);
    std::printf("yellow share: exemplar %.3f, plain EM %.3f, uniform usage %.3f\n", exemplar,
                yellow_share(plain->image), yellow_share(uniform->image));
    std::printf("histogram distance to the exemplar: plain EM %.3f, uniform usage %.3f\n",
                histogram_distance(source.image, plain->image),
                histogram_distance(source.image, uniform->image));
    EXPECT_LT(yellow_share(plain->image), 0.2 * exemplar);
    EXPECT_GT(yellow_share(uniform->image), 0.6 * exemplar);
    // Measured 0.171 against 0.336. Uniform usage keeps the exemplar patches turned (paint.cpp);
    // plain EM's turned target patches keep a few more flecks than before (yellow 0.000 ->
    // 0.012, its distance a little lower), so the ratio moved from under 0.5 to 0.51 while the
    // uniform output's own distance stayed 0.170-0.171: both are asserted.
    EXPECT_LT(histogram_distance(source.image, uniform->image), 0.18);
    EXPECT_LT(histogram_distance(source.image, uniform->image),
              0.55 * histogram_distance(source.image, plain->image));
}

// Checks that `after` keeps `before`'s bytes outside `changed` grown by the default patch size;
// returns the painted pixels within it that are mostly opaque in `after`.
int kept_outside(const Image& before, const Image& after, const PixelRect& changed,
                 const PaintCanvas& canvas) {
    int painted_new = 0;
    for (int y = 0; y < before.height(); ++y) {
        for (int x = 0; x < before.width(); ++x) {
            const bool near = x >= changed.x0 - 5 && x < changed.x1 + 5 && y >= changed.y0 - 5 &&
                              y < changed.y1 + 5;
            if (!near) {
                EXPECT_EQ(std::memcmp(before.pixel(x, y), after.pixel(x, y), 4 * sizeof(float)), 0)
                    << x << "," << y;
            } else if (canvas.coverage().at(x, y, 0) != 0.0f && after.at(x, y, 3) > 0.5f) {
                ++painted_new;
            }
        }
    }
    return painted_new;
}

TEST(Paint, RepaintChangesOnlyTheTouchedRegion) {
    const PaintSource source = striped_blob(48, 22);
    PaintCanvas canvas(96, 64);
    ASSERT_TRUE(canvas.add_stroke(stroke({{8, 16}, {88, 16}}, 20)).ok());
    const auto first = paint(source, canvas, {}, RunContext(2));
    ASSERT_TRUE(first.ok());
    const auto changed = canvas.add_stroke(stroke({{8, 50}, {40, 50}}, 16));
    ASSERT_TRUE(changed.ok());
    const auto second = repaint(source, canvas, first->image, *changed, {}, RunContext(2));
    ASSERT_TRUE(second.ok()) << second.status().message();
    EXPECT_GT(kept_outside(first->image, second->image, *changed, canvas), 300);
}

// Mean absolute RGB difference (alpha-weighted, so transparent pixels count as black) of two
// RGBA paintings reduced `factor` times per side (box filter), over the reduced pixels where
// either is painted.
double coarse_difference(const Image& a, const Image& b, int factor) {
    const auto small = [factor](const Image& rgba) {
        Image p = rgba;
        for (std::size_t i = 0; i < p.pixel_count(); ++i) {
            for (int c = 0; c < 3; ++c) p.data()[4 * i + c] *= p.data()[4 * i + 3];
        }
        return resize(p, p.width() / factor, p.height() / factor, ResampleFilter::Box, 1);
    };
    const Image sa = small(a), sb = small(b);
    double sum = 0.0;
    int count = 0;
    for (std::size_t i = 0; i < sa.pixel_count(); ++i) {
        if (sa.data()[4 * i + 3] <= 0.0f && sb.data()[4 * i + 3] <= 0.0f) continue;
        for (int c = 0; c < 3; ++c) sum += std::fabs(sa.data()[4 * i + c] - sb.data()[4 * i + c]);
        ++count;
    }
    return count > 0 ? sum / (3.0 * count) : 0.0;
}

TEST(Paint, PreviewIsDeterministicKeepsTheRestAndIsCloseToTheRepaintAtCoarseScale) {
    const PaintSource source = striped_blob(96, 44);
    PaintCanvas canvas(128, 96);
    ASSERT_TRUE(canvas.add_stroke(stroke({{8, 20}, {120, 24}}, 24)).ok());
    const auto first = paint(source, canvas, {}, RunContext(2));
    ASSERT_TRUE(first.ok());
    const auto changed = canvas.add_stroke(stroke({{10, 70}, {60, 60}, {118, 72}}, 28));
    ASSERT_TRUE(changed.ok());
    const auto final_ = repaint(source, canvas, first->image, *changed, {}, RunContext(2));
    const auto preview =
        preview_repaint(source, canvas, first->image, *changed, {}, 4, RunContext(2));
    const auto inline_ =
        preview_repaint(source, canvas, first->image, *changed, {}, 4, RunContext(1));
    ASSERT_TRUE(final_.ok() && preview.ok() && inline_.ok()) << preview.status().message();
    ASSERT_EQ(preview->image.data().size(), inline_->image.data().size());
    EXPECT_EQ(std::memcmp(preview->image.data().data(), inline_->image.data().data(),
                          preview->image.data().size() * sizeof(float)),
              0);
    // Outside the rectangle a repaint synthesizes, the previous painting's bytes.
    EXPECT_GT(kept_outside(first->image, preview->image, *changed, canvas), 2000);
    // At 1/8 scale (a stripe period, so the texture's detail averages out) the preview's colours
    // are the repaint's: measured 0.027 (7/255), against 0.16 for the painting without the new
    // stroke; the bound leaves room for other compilers' rounding, not for a misplaced or
    // mis-coloured stroke.
    const double close = coarse_difference(preview->image, final_->image, 8);
    const double blank = coarse_difference(first->image, final_->image, 8);
    std::printf("coarse difference: preview %.4f, previous painting %.4f\n", close, blank);
    EXPECT_LT(close, 0.04);
    EXPECT_LT(close, 0.25 * blank);
    // A factor the exemplar cannot take falls back to the repaint itself.
    const auto full = preview_repaint(source, canvas, first->image, *changed, {}, 1, RunContext(2));
    ASSERT_TRUE(full.ok());
    EXPECT_EQ(std::memcmp(full->image.data().data(), final_->image.data().data(),
                          full->image.data().size() * sizeof(float)),
              0);
    EXPECT_EQ(preview_repaint(source, canvas, first->image, *changed, {}, 17).status().message(),
              "reduction: 17 is invalid (must be 1..16)");
}

// Two textures side by side (Brushables Fig. 9): warm horizontal stripes on the left (label 1),
// cool vertical stripes on the right (label 2); `transparent_rim` fades alpha out over the outer
// 6 px, so the exemplar has a shape boundary besides the segment boundary.
PaintSource two_textures(bool transparent_rim) {
    PaintSource s;
    const int w = 64, h = 40;
    s.image = Image(w, h, 4);
    s.labels = Image(w, h, 1);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const bool left = x < w / 2;
            const float grain = 0.1f * (hash01(x, y, 3) - 0.5f);
            const float stripe =
                0.5f + 0.4f * std::sin(static_cast<float>(left ? y : x) * 0.785398f);
            float* p = s.image.pixel(x, y);
            p[0] = left ? 0.6f + 0.3f * stripe + grain : 0.1f + grain;
            p[1] = left ? 0.4f * stripe + grain : 0.3f * stripe + grain;
            p[2] = left ? 0.1f + grain : 0.5f + 0.4f * stripe + grain;
            const int rim = std::min({x, y, w - 1 - x, h - 1 - y});
            p[3] =
                transparent_rim ? std::clamp(static_cast<float>(rim - 2) / 4.0f, 0.0f, 1.0f) : 1.0f;
            s.labels.at(x, y, 0) = left ? 1.0f : 2.0f;
        }
    }
    s.directions = Image(w, h, 1);
    return s;
}

// Share of the painted pixels whose exemplar patch lies in the segment their stroke painted.
double own_segment_share(const PaintSource& source, const PaintCanvas& canvas, const Nnf& nnf) {
    int own = 0, painted = 0;
    for (int y = 0; y < canvas.height(); ++y) {
        for (int x = 0; x < canvas.width(); ++x) {
            if (canvas.coverage().at(x, y, 0) == 0.0f) continue;
            const Match& m = nnf.at(x, y);
            if (m.x < 0) continue;
            ++painted;
            own += source.labels.at(m.x, m.y, 0) == canvas.labels().at(x, y, 0) ? 1 : 0;
        }
    }
    return painted > 0 ? static_cast<double>(own) / painted : 0.0;
}

TEST(Paint, LabelledStrokesTakeSourcesOnlyFromTheirSegment) {
    for (const bool rim : {false, true}) {
        const PaintSource source = two_textures(rim);
        // Stroke 1 across the top with label 2, stroke 2 across the bottom with label 1; they
        // touch in the middle, where the later one wins.
        PaintCanvas canvas(96, 64);
        Stroke top = stroke({{8, 20}, {88, 22}}, 26), bottom = stroke({{8, 44}, {88, 40}}, 26);
        top.label = 2;
        bottom.label = 1;
        ASSERT_TRUE(canvas.add_stroke(top).ok());
        ASSERT_TRUE(canvas.add_stroke(bottom).ok());
        EXPECT_EQ(canvas.labels().at(48, 18, 0), 2.0f);
        EXPECT_EQ(canvas.labels().at(48, 42, 0), 1.0f);
        const auto labelled = paint(source, canvas, {}, RunContext(2));
        ASSERT_TRUE(labelled.ok()) << labelled.status().message();
        PaintSource unlabelled = source;
        unlabelled.labels = Image();
        PaintCanvas plain(96, 64);
        top.label = bottom.label = 0;
        ASSERT_TRUE(plain.add_stroke(top).ok() && plain.add_stroke(bottom).ok());
        const auto free = paint(unlabelled, plain, {}, RunContext(2));
        ASSERT_TRUE(free.ok());
        const double with = own_segment_share(source, canvas, labelled->nnf);
        const double without = own_segment_share(source, canvas, free->nnf);
        std::printf("own-segment share (%s exemplar): labelled %.3f, unlabelled %.3f\n",
                    rim ? "transparent-rim" : "opaque", with, without);
        EXPECT_EQ(with, 1.0);
        EXPECT_LT(without, 0.8);
        // The colours follow: the top stroke is blue-dominant, the bottom one red-dominant.
        const float* t = labelled->image.pixel(48, 16);
        const float* b = labelled->image.pixel(48, 46);
        EXPECT_GT(t[2], t[0]);
        EXPECT_GT(b[0], b[2]);
    }
}

TEST(Paint, LabelledRepaintKeepsTheSegments) {
    const PaintSource source = two_textures(true);
    PaintCanvas canvas(96, 64);
    Stroke first = stroke({{8, 18}, {88, 18}}, 22);
    first.label = 1;
    ASSERT_TRUE(canvas.add_stroke(first).ok());
    const auto before = paint(source, canvas, {}, RunContext(2));
    ASSERT_TRUE(before.ok());
    Stroke second = stroke({{8, 48}, {60, 44}}, 20);
    second.label = 2;
    const auto changed = canvas.add_stroke(second);
    ASSERT_TRUE(changed.ok());
    const auto after = repaint(source, canvas, before->image, *changed, {}, RunContext(2));
    ASSERT_TRUE(after.ok()) << after.status().message();
    // The repainted pixels (within the changed rectangle) come from their own segment.
    int own = 0, painted = 0;
    for (int y = changed->y0; y < changed->y1; ++y) {
        for (int x = changed->x0; x < changed->x1; ++x) {
            const Match& m = after->nnf.at(x, y);
            if (canvas.coverage().at(x, y, 0) == 0.0f || m.x < 0) continue;
            ++painted;
            own += source.labels.at(m.x, m.y, 0) == canvas.labels().at(x, y, 0) ? 1 : 0;
        }
    }
    EXPECT_GT(painted, 500);
    EXPECT_EQ(own, painted);
}

TEST(Paint, LabelsWithoutASegmentAreRejectedByName) {
    PaintSource source = two_textures(false);
    PaintCanvas canvas(48, 32);
    Stroke s = stroke({{4, 16}, {44, 16}}, 12);
    s.label = 3;
    ASSERT_TRUE(canvas.add_stroke(s).ok());
    auto r = paint(source, canvas);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.status().message(),
              "labels: label 3 is painted but the source labels have no such segment inside the "
              "exemplar's shape");
    source.labels = Image();
    r = paint(source, canvas);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.status().message(), "labels: label 3 is painted but the source has no labels");
    source = two_textures(false);
    source.labels = Image(8, 8, 1);
    r = paint(source, canvas);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.status().message().find("source labels: 8x8"), std::string::npos);
    // A combing stroke paints no segment; labels outside 24 bits do not survive a float.
    Stroke comb = stroke({{4, 16}, {44, 16}}, 12, true);
    comb.label = 1;
    EXPECT_EQ(canvas.add_stroke(comb).status().message(),
              "label: 1 on a combing stroke (it paints no segment; must be 0)");
    s.label = 1 << 24;
    EXPECT_FALSE(canvas.add_stroke(s).ok());
}

TEST(Paint, BadInputsAreRejectedByName) {
    PaintCanvas canvas(32, 32);
    ASSERT_TRUE(canvas.add_stroke(stroke({{4, 16}, {28, 16}}, 10)).ok());
    PaintSource grey;
    grey.image = Image(16, 16, 2);
    auto r = paint(grey, canvas);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.status().message().find("channels"), std::string::npos);

    PaintSource masked = striped_blob(32, 14);
    masked.mask = Image(8, 8, 1);
    r = paint(masked, canvas);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.status().message().find("source mask"), std::string::npos);

    PaintSource transparent = striped_blob(32, 14);
    for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 32; ++x) transparent.image.at(x, y, 3) = 0.0f;
    }
    r = paint(transparent, canvas);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.status().message().find("empty"), std::string::npos);

    PaintOptions options;
    options.patch_size = 4;
    r = paint(striped_blob(32, 14), canvas, options);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.status().message().find("patch-size"), std::string::npos);
    options = PaintOptions{};
    options.vote_histogram = 101.0f;
    r = paint(striped_blob(32, 14), canvas, options);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.status().message(), "vote-histogram: 101.000000 is invalid (must be 0..100)");

    // Nothing painted: a transparent result.
    const auto empty = paint(striped_blob(32, 14), PaintCanvas(8, 8));
    ASSERT_TRUE(empty.ok());
    EXPECT_EQ(empty->image.at(3, 3, 3), 0.0f);
}

}  // namespace
}  // namespace exemplar::paint
