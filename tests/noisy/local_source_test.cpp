// Local choice of source (thesis §4.3.3): several media, one chosen per pixel by a source map.
// Each region's pixels must come from its own medium; the run stays deterministic; bad maps and
// mismatched sources are refused with one-line messages.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "exemplar/noisy/noisy.hpp"
#include "procedural.hpp"

namespace exemplar::noisy {
namespace {

// The procedural medium tinted so that every pixel tells its source: red dominates in the
// first, blue in the second (a vote averages pixels of one source, which keeps the order).
Image tinted_medium(bool red, std::uint64_t key) {
    const Image grey = testing::medium(96, 96, key);
    Image out(grey.width(), grey.height(), 3);
    for (int y = 0; y < grey.height(); ++y) {
        for (int x = 0; x < grey.width(); ++x) {
            const float v = 0.2f + 0.8f * std::clamp(grey.at(x, y, 1), 0.0f, 1.0f);
            out.at(x, y, 0) = red ? v : 0.3f * v;
            out.at(x, y, 1) = 0.5f * v;
            out.at(x, y, 2) = red ? 0.3f * v : v;
        }
    }
    return out;
}

struct TwoMedia {
    std::vector<NoisySource> sources{{tinted_medium(true, 11), {}}, {tinted_medium(false, 21), {}}};
    NoisyFrame frame;
    TwoMedia() {
        frame.reference = testing::cel(64, 64, 30, 26, 12);
        // A wavy boundary: source 0 left of it, source 1 right.
        frame.source_map = Image(64, 64, 1);
        for (int y = 0; y < 64; ++y) {
            for (int x = 0; x < 64; ++x) {
                frame.source_map.at(x, y, 0) = x >= 32 + 8 * std::sin(y / 6.0) ? 1.0f : 0.0f;
            }
        }
    }
};

struct Share {
    double interior = 0.0;  // pixels whose 3x3 neighbourhood has one source
    double all = 0.0;
};

// The share of pixels whose colour says they come from the source their map value names.
Share own_source_share(const Image& image, const Image& map) {
    long interior = 0, interior_own = 0, own = 0;
    for (int y = 0; y < image.height(); ++y) {
        for (int x = 0; x < image.width(); ++x) {
            const bool second = map.at(x, y, 0) > 0.5f;
            const bool from_second = image.at(x, y, 2) > image.at(x, y, 0);
            own += second == from_second;
            bool uniform = true;
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = std::clamp(x + dx, 0, image.width() - 1);
                    const int ny = std::clamp(y + dy, 0, image.height() - 1);
                    uniform = uniform && (map.at(nx, ny, 0) > 0.5f) == second;
                }
            }
            if (!uniform) continue;
            ++interior;
            interior_own += second == from_second;
        }
    }
    return {static_cast<double>(interior_own) / static_cast<double>(interior),
            static_cast<double>(own) / static_cast<double>(image.pixel_count())};
}

TEST(NoisyLocalSource, EachRegionIsDrawnFromItsOwnMedium) {
    const TwoMedia in;
    NoisyOptions options;
    options.patch_size = 5;
    for (const float noise : {1.0f, 4.0f}) {
        for (const bool with_noise_map : {false, true}) {
            options.noise = noise;
            NoisyFrame frame = in.frame;
            // Pixels starting on different levels: the labels must hold on every level.
            if (with_noise_map) {
                frame.noise_map = Image(64, 64, 1);
                for (int y = 0; y < 64; ++y) {
                    for (int x = 0; x < 64; ++x) frame.noise_map.at(x, y, 0) = y / 63.0f;
                }
            }
            const Result<Image> out = synthesize_frame(in.sources, frame, options, 5);
            ASSERT_TRUE(out.ok()) << out.status().message();
            const Share share = own_source_share(out.value(), frame.source_map);
            std::printf("f = %g%s: own-source share %.4f inside the regions, %.4f overall\n", noise,
                        with_noise_map ? " with a noise map" : "", share.interior, share.all);
            // Only the last vote's 3x3 footprint mixes the media, along the boundary.
            EXPECT_EQ(share.interior, 1.0) << "f = " << noise;
            EXPECT_GT(share.all, 0.95) << "f = " << noise;
        }
    }
    // The map decides: swapping the sources swaps the media of the regions.
    options.noise = 4.0f;
    const std::vector<NoisySource> swapped{in.sources[1], in.sources[0]};
    NoisyFrame inverse = in.frame;
    for (float& v : inverse.source_map.data()) v = 1.0f - v;
    const Result<Image> out = synthesize_frame(swapped, inverse, options, 5);
    ASSERT_TRUE(out.ok()) << out.status().message();
    EXPECT_EQ(own_source_share(out.value(), inverse.source_map).interior, 0.0);
}

TEST(NoisyLocalSource, IsTheSameForAnyThreadCountAndOneSourceIsTheSingleSourceCall) {
    const TwoMedia in;
    NoisyOptions options;
    options.noise = 3.0f;
    options.patch_size = 5;
    const Result<Image> one = synthesize_frame(in.sources, in.frame, options, 2, RunContext(1));
    const Result<Image> two = synthesize_frame(in.sources, in.frame, options, 2, RunContext(2));
    ASSERT_TRUE(one.ok()) << one.status().message();
    ASSERT_TRUE(two.ok());
    EXPECT_TRUE(std::equal(one->data().begin(), one->data().end(), two->data().begin()));

    // One source with an all-0 map: the single-source frame, bit for bit.
    NoisyFrame frame = in.frame;
    frame.source_map = Image(64, 64, 1, 0.0f);
    const Result<Image> mapped =
        synthesize_frame(std::vector<NoisySource>{in.sources[0]}, frame, options, 2, RunContext(2));
    frame.source_map = Image();
    const Result<Image> plain =
        synthesize_frame(in.sources[0].image, frame, options, 2, RunContext(2));
    ASSERT_TRUE(mapped.ok()) << mapped.status().message();
    ASSERT_TRUE(plain.ok());
    EXPECT_TRUE(std::equal(mapped->data().begin(), mapped->data().end(), plain->data().begin()));
}

TEST(NoisyLocalSource, RejectsBadMapsAndSourcesWithOneLineMessages) {
    const TwoMedia in;
    NoisyOptions options;
    options.noise = 3.0f;
    auto message = [&](const std::vector<NoisySource>& sources, const NoisyFrame& frame) {
        return synthesize_frame(sources, frame, options, 0).status().message();
    };
    NoisyFrame frame = in.frame;
    frame.source_map = Image();
    EXPECT_EQ(message(in.sources, frame),
              "source map: is required with 2 sources (it chooses one per pixel)");
    frame.source_map = Image(32, 64, 1, 0.0f);
    EXPECT_EQ(message(in.sources, frame),
              "source map: is 32x64 (must be 64x64 like the reference)");
    frame.source_map = in.frame.source_map;
    frame.source_map.at(7, 3, 0) = 2.0f;
    EXPECT_EQ(message(in.sources, frame),
              "source map: value 2 at (7, 3) has no source (2 given: 0..1)");
    frame.source_map.at(7, 3, 0) = -1.0f;
    EXPECT_EQ(message(in.sources, frame),
              "source map: value -1 at (7, 3) has no source (2 given: 0..1)");
    EXPECT_EQ(message({}, in.frame), "sources: none given (need at least one)");
    std::vector<NoisySource> grey = in.sources;
    grey[1].image = Image(96, 96, 1, 0.5f);
    EXPECT_EQ(message(grey, in.frame),
              "source 1: has 1 channels but source 0 has 3 (every source needs the same "
              "channels)");
    std::vector<NoisySource> small = in.sources;
    small[1].image = tinted_medium(true, 3);
    small[1].image = Image(20, 30, 3, 0.5f);
    options.noise = 4.0f;
    EXPECT_EQ(message(small, in.frame),
              "noise: 4 is too strong for the 64x64 reference and the 20x30 source 1 with "
              "patch-size 7 (at most 2.22)");
    options.noise = 3.0f;
    std::vector<NoisySource> oriented = in.sources;
    oriented[0].orientation = Image(96, 96, 1, 0.0f);
    NoisyFrame oriented_frame = in.frame;
    oriented_frame.orientation = Image(64, 64, 1, 0.0f);
    EXPECT_EQ(message(oriented, oriented_frame),
              "source 1 orientation: is missing but source 0's is given (give every source's "
              "orientation field, or none)");
    oriented[1].orientation = Image(96, 96, 1, 0.3f);
    const Result<Image> both = synthesize_frame(oriented, oriented_frame, options, 0);
    EXPECT_TRUE(both.ok()) << both.status().message();
}

}  // namespace
}  // namespace exemplar::noisy
