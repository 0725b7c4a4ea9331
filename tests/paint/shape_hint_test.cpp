// Shape Hints (Brushables §3.3, Fig. 5-6): rotation through the direction field, boundary versus
// interior, and the boundary placement they give the synthesis.

#include "exemplar/paint/shape_hint.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "exemplar/paint/paint.hpp"

namespace exemplar::paint {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// An L-shaped mask: distinguishes corners, edges and the interior.
Image l_shape(int size) {
    Image m(size, size, 1);
    for (int y = 8; y < size - 8; ++y) {
        for (int x = 8; x < size - 8; ++x) {
            if (x < size / 2 || y > size / 2) m.at(x, y, 0) = 1.0f;
        }
    }
    return m;
}

// The image turned 90° counter-clockwise on screen: (x, y) -> (y, size - 1 - x).
Image turned(const Image& im) {
    const int n = im.width();
    Image out(n, n, im.channels());
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            for (int c = 0; c < im.channels(); ++c) out.at(y, n - 1 - x, c) = im.at(x, y, c);
        }
    }
    return out;
}

TEST(ShapeHint, TurningTheShapeAndItsDirectionsTurnsNothing) {
    // Comparing bins in each pixel's own frame is the rotation by α_pq of eq. 6: a shape turned
    // by 90° with its directions turned by 90° has the same descriptors at the turned pixels.
    const int n = 64;
    const Image mask = l_shape(n);
    Image angles(n, n, 1, 0.3f);
    const ShapeHintOptions options{10.0f, 8};
    const Image a = shape_hint(shape_edges(mask), angles, options, 1);
    Image turned_angles(n, n, 1, 0.3f + 0.5f * kPi);
    const Image b = shape_hint(shape_edges(turned(mask)), turned_angles, options, 2);
    const Image a_turned = turned(a);
    float worst = 0.0f;
    for (std::size_t i = 0; i < b.size(); ++i) {
        worst = std::max(worst, std::abs(a_turned.data()[i] - b.data()[i]));
    }
    EXPECT_LT(worst, 1e-4f);
    // Without turning the directions the descriptors differ at the boundary.
    const Image c = shape_hint(shape_edges(turned(mask)), angles, options, 1);
    float differs = 0.0f;
    for (std::size_t i = 0; i < c.size(); ++i) {
        differs = std::max(differs, std::abs(a_turned.data()[i] - c.data()[i]));
    }
    EXPECT_GT(differs, 0.2f);
}

TEST(ShapeHint, BoundaryPixelsSeeTheEdgeAndInteriorPixelsDoNot) {
    Image mask(80, 80, 1);
    for (int y = 10; y < 70; ++y) {
        for (int x = 10; x < 70; ++x) mask.at(x, y, 0) = 1.0f;
    }
    const Image hint = shape_hint(shape_edges(mask), Image(80, 80, 1), {8.0f, 8}, 1);
    auto total = [&](int x, int y) {
        float s = 0.0f;
        for (int b = 0; b < 8; ++b) s += hint.at(x, y, b);
        return s;
    };
    EXPECT_EQ(total(40, 40), 0.0f);  // 30 px from every edge, beyond ring + bin
    EXPECT_GT(total(40, 17), 0.5f);  // 7 px below the top edge (row 10)
    // Direction 0 (right): bin 2 looks up (π/2), its disc (radius 3 around row 9) on the edge;
    // bin 6 looks down into the interior.
    EXPECT_GT(hint.at(40, 17, 2), 0.3f);
    EXPECT_EQ(hint.at(40, 17, 6), 0.0f);
}

// shape_hint skips the pixels far from every edge (their descriptors are 0); compared bit for
// bit with the reference that computes every pixel: an L shape and a bar off-centre on a wide
// image (large parts far from any edge, edges near the borders), varying directions, ring radii
// 3, 8.5 and 16, 1 and 3 threads.
TEST(ShapeHint, SkippingPixelsFarFromEdgesChangesNoByte) {
    Image mask(150, 90, 1);
    const Image l = l_shape(64);
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 64; ++x) mask.at(x + 70, y + 20, 0) = l.at(x, y, 0);
    }
    for (int y = 30; y < 40; ++y) {
        for (int x = 0; x < 30; ++x) mask.at(x, y, 0) = 1.0f;
    }
    Image angles(150, 90, 1);
    for (int y = 0; y < 90; ++y) {
        for (int x = 0; x < 150; ++x) angles.at(x, y, 0) = 0.05f * static_cast<float>(x - y);
    }
    const Image edges = shape_edges(mask);
    for (const ShapeHintOptions options :
         {ShapeHintOptions{3.0f, 8}, ShapeHintOptions{8.5f, 6}, ShapeHintOptions{16.0f, 8}}) {
        const Image expected = shape_hint_reference(edges, angles, options, 1);
        std::size_t zero = 0;
        for (float v : expected.data()) zero += v == 0.0f ? 1 : 0;
        EXPECT_GT(zero, expected.data().size() / 4);  // the case the skipping is for
        for (int threads : {1, 3}) {
            const Image fast = shape_hint(edges, angles, options, threads);
            EXPECT_TRUE(std::ranges::equal(fast.data(), expected.data()))
                << "ring " << options.radius_px << ", " << threads << " threads";
        }
    }
}

// Distance from every pixel to the nearest edge pixel of a mask (brute force).
std::vector<float> edge_distance(const Image& mask) {
    const Image edges = shape_edges(mask);
    std::vector<std::pair<int, int>> list;
    for (int y = 0; y < edges.height(); ++y) {
        for (int x = 0; x < edges.width(); ++x) {
            if (edges.at(x, y, 0) > 0.0f) list.push_back({x, y});
        }
    }
    std::vector<float> d(mask.pixel_count(), 1e9f);
    for (int y = 0; y < mask.height(); ++y) {
        for (int x = 0; x < mask.width(); ++x) {
            float best = 1e9f;
            for (const auto& [u, v] : list) {
                best = std::min(best,
                                std::hypot(static_cast<float>(x - u), static_cast<float>(y - v)));
            }
            d[static_cast<std::size_t>(y) * mask.width() + x] = best;
        }
    }
    return d;
}

float hash01(int x, int y) {
    std::uint32_t h =
        static_cast<std::uint32_t>(x) * 73856093u ^ static_cast<std::uint32_t>(y) * 19349663u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return static_cast<float>(h & 0xffffu) / 65535.0f;
}

TEST(ShapeHint, PutsTheExemplarsBoundaryPatchesAtTheRegionsBoundary) {
    // Brushables Fig. 5, measured: the share of the painted region's boundary band whose
    // exemplar patch comes from the exemplar's own boundary band, with and without the hint. The
    // exemplar is an opaque blob with one texture throughout, so neither colour nor alpha tells
    // the boundary from the interior beyond the patch's reach; only the shape does.
    const int size = 72;
    PaintSource source;
    source.image = Image(size, size, 4);
    const float c = 0.5f * (size - 1);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            float* p = source.image.pixel(x, y);
            const float g = 0.3f + 0.4f * hash01(x / 2, y / 2) + 0.1f * hash01(x, y);
            p[0] = g;
            p[1] = 0.8f * g;
            p[2] = 0.5f * g;
            p[3] = std::hypot(x - c, y - c) < 32.0f ? 1.0f : 0.0f;
        }
    }
    source.directions = Image(size, size, 1);
    Image source_mask(size, size, 1);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) source_mask.at(x, y, 0) = source.image.at(x, y, 3);
    }
    const std::vector<float> source_distance = edge_distance(source_mask);

    PaintCanvas canvas(112, 72);
    Stroke s;
    s.points = {{16, 36}, {96, 36}};
    s.width_px = 40;
    ASSERT_TRUE(canvas.add_stroke(s).ok());
    const std::vector<float> target_distance = edge_distance(canvas.coverage());

    const float band = 6.0f;
    auto boundary_share = [&](float shape_weight) {
        double share = 0.0;
        for (std::uint64_t seed = 1; seed <= 2; ++seed) {
            PaintOptions options;
            options.shape_weight = shape_weight;
            options.edge_extent_px = 8.0f;
            options.seed = seed;
            const auto r = paint(source, canvas, options, RunContext(2));
            EXPECT_TRUE(r.ok()) << r.status().message();
            if (!r.ok()) return 0.0;
            int n = 0, near = 0;
            for (int y = 0; y < 72; ++y) {
                for (int x = 0; x < 112; ++x) {
                    if (canvas.coverage().at(x, y, 0) == 0.0f) continue;
                    if (target_distance[static_cast<std::size_t>(y) * 112 + x] > band) continue;
                    const Match& m = r->nnf.at(x, y);
                    if (m.x < 0) continue;
                    ++n;
                    const float d = source_distance[static_cast<std::size_t>(
                        static_cast<int>(m.y) * size + static_cast<int>(m.x))];
                    near += d <= band ? 1 : 0;
                }
            }
            share += 0.5 * near / std::max(n, 1);
        }
        return share;
    };
    const double with = boundary_share(25.0f);
    const double without = boundary_share(0.0f);
    std::printf(
        "boundary band (<= 6 px) matched to the exemplar's boundary band: with Shape Hint "
        "%.3f, without %.3f\n",
        with, without);
    EXPECT_GT(with, without + 0.15);
    EXPECT_GT(with, 0.6);
}

}  // namespace
}  // namespace exemplar::paint
