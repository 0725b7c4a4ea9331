#include "exemplar/synth/inpaint.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "exemplar/filters/measures.hpp"
#include "exemplar/io/image_io.hpp"

namespace exemplar {
namespace {

// The painted red of texture-synthesis' 3.jpg (a saturated red the bark never has).
bool painted_red(const Image& im, int x, int y) {
    const float* p = im.pixel(x, y);
    return p[0] > 0.6f && p[1] < 0.3f && p[2] < 0.3f;
}

TEST(InpaintingKnown, AveragesColourNoiseAndThresholdsAtOneHalf) {
    // A JPEG's chroma noise: channels that straddle 0.5 read by their mean.
    Image mask(3, 1, 3, 1.0f);
    const float dark[3] = {0.7f, 0.2f, 0.3f};   // mean 0.4: hole
    const float light[3] = {0.3f, 0.8f, 0.6f};  // mean 0.567: known
    for (int c = 0; c < 3; ++c) {
        mask.at(0, 0, c) = dark[c];
        mask.at(1, 0, c) = light[c];
        mask.at(2, 0, c) = 0.5f;  // exactly 0.5: hole
    }
    auto known = inpainting_known(mask);
    ASSERT_TRUE(known.ok()) << known.status().message();
    ASSERT_EQ(known->channels(), 1);
    EXPECT_EQ(known->at(0, 0, 0), 0.0f);
    EXPECT_EQ(known->at(1, 0, 0), 1.0f);
    EXPECT_EQ(known->at(2, 0, 0), 0.0f);
    // Grey with an opaque alpha channel: the alpha is not a colour.
    Image grey_alpha(2, 1, 2, 1.0f);
    grey_alpha.at(0, 0, 0) = 0.0f;
    known = inpainting_known(grey_alpha);
    ASSERT_TRUE(known.ok());
    EXPECT_EQ(known->at(0, 0, 0), 0.0f);
    EXPECT_EQ(known->at(1, 0, 0), 1.0f);
}

TEST(InpaintingKnown, RejectsTransparencyAndMasksWithoutAHole) {
    Image rgba(2, 2, 4, 1.0f);
    rgba.at(0, 0, 0) = 0.0f;
    rgba.at(1, 1, 3) = 0.5f;
    auto known = inpainting_known(rgba, "hole.png");
    ASSERT_FALSE(known.ok());
    EXPECT_EQ(known.status().message().rfind("hole.png: is partly transparent", 0), 0u)
        << known.status().message();
    known = inpainting_known(Image(4, 4, 1, 0.8f), "white.png");
    ASSERT_FALSE(known.ok());
    EXPECT_EQ(known.status().message(), "white.png: has no hole (no pixel <= 0.5)");
}

TEST(InpaintingInput, SetsMasksAndStartsTheHoleFromTheKnownMean) {
    Image image(4, 2, 3);
    Image known(4, 2, 1, 1.0f);
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 4; ++x) {
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = 0.1f * static_cast<float>(x + c);
        }
    }
    known.at(3, 0, 0) = 0.0f;
    known.at(3, 1, 0) = 0.0f;  // the hole: column 3
    auto in = inpainting_input(image, known);
    ASSERT_TRUE(in.ok()) << in.status().message();
    EXPECT_TRUE(std::ranges::equal(in->style.data(), image.data()));
    EXPECT_TRUE(std::ranges::equal(in->source_mask.data(), known.data()));
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 4; ++x) {
            EXPECT_EQ(in->target_mask.at(x, y, 0), x == 3 ? 1.0f : 0.0f);
            for (int c = 0; c < 3; ++c) {
                // Known columns 0..2: mean 0.1 * (1 + c).
                const float expected =
                    x == 3 ? 0.1f * static_cast<float>(1 + c) : image.at(x, y, c);
                EXPECT_NEAR(in->initial_target.at(x, y, c), expected, 1e-6f);
            }
        }
    }
    auto wrong = inpainting_input(image, Image(4, 3, 1, 1.0f));
    ASSERT_FALSE(wrong.ok());
    EXPECT_EQ(wrong.status().message(), "inpaint mask: is 4x3 but the image is 4x2");
    wrong = inpainting_input(image, Image(4, 2, 3, 1.0f));
    ASSERT_FALSE(wrong.ok());
    EXPECT_EQ(wrong.status().message(),
              "inpaint mask: has 3 channels (pass it through inpainting_known)");
}

// A 96x96 crop of texture-synthesis' 3.jpg (birch bark with a red Z painted over it) and of its
// JPEG mask (black over the Z; its colour channels differ by the JPEG's chroma noise): the Z
// goes, nothing else changes, the fill is bark, and 1 or 2 threads give the same bytes.
TEST(Inpaint, FillsThePaintedZWithBark) {
    const std::string dir = EXEMPLAR_TEST_DATA_DIR "/texture-synthesis/";
    auto image = load_image(dir + "3_crop.png");
    auto mask = load_image(dir + "3_inpaint_crop.png");
    ASSERT_TRUE(image.ok() && mask.ok());
    ASSERT_EQ(mask->channels(), 3);
    auto known = inpainting_known(*mask);
    ASSERT_TRUE(known.ok()) << known.status().message();
    auto in = inpainting_input(*image, *known);
    ASSERT_TRUE(in.ok()) << in.status().message();
    const Image& hole = in->target_mask;

    int red_before = 0, hole_pixels = 0;
    for (int y = 0; y < image->height(); ++y) {
        for (int x = 0; x < image->width(); ++x) {
            const bool inside = hole.at(x, y, 0) > 0.5f;
            hole_pixels += inside ? 1 : 0;
            red_before += inside && painted_red(*image, x, y) ? 1 : 0;
        }
    }
    ASSERT_GT(red_before, 1500);  // the crop holds a piece of the Z (about 1/4 of it)

    const SynthesisOptions options;
    auto one = synthesize(*in, options, RunContext(1));
    auto two = synthesize(*in, options, RunContext(2));
    ASSERT_TRUE(one.ok() && two.ok()) << one.status().message();
    EXPECT_TRUE(std::ranges::equal(one->image.data(), two->image.data()));
    const Image& out = one->image;

    int red_after = 0;
    double hole_error = 0.0;
    for (int y = 0; y < out.height(); ++y) {
        for (int x = 0; x < out.width(); ++x) {
            if (hole.at(x, y, 0) > 0.5f) {
                red_after += painted_red(out, x, y) ? 1 : 0;
                hole_error += one->error.at(x, y, 0);
                continue;
            }
            for (int c = 0; c < out.channels(); ++c) {
                ASSERT_EQ(out.at(x, y, c), image->at(x, y, c)) << x << "," << y;
            }
        }
    }
    EXPECT_EQ(red_after, 0);
    // The fill is made of known patches and keeps the bark's detail. Measured: mean final patch
    // error 0.166 in the hole, texture kept 0.80 (plain averaging of patches washes out to about
    // 0.6; the mean colour the hole starts from has none).
    const double mean_error = hole_error / hole_pixels;
    const double texture = gradient_energy(out, hole) / gradient_energy(*image, *known);
    std::printf("hole: %d pixels, mean patch error %.4f, texture kept %.3f\n", hole_pixels,
                mean_error, texture);
    EXPECT_LT(mean_error, 0.25);
    EXPECT_GT(texture, 0.7);
    EXPECT_LT(texture, 1.3);
}

}  // namespace
}  // namespace exemplar
