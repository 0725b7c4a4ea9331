// Files written by another tool (OpenImageIO 2.4's oiiotool, tests/data/images/make.sh) in the
// layouts pipelines produce: tiled, planar, LZW/PIZ-compressed, ASCII, with a data window or
// extra channels. Each must read back as the reference picture they were all made from.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "exemplar/io/image_io.hpp"

namespace exemplar {
namespace {

const std::string kDir = std::string(EXEMPLAR_TEST_DATA_DIR) + "/images/";

Image load(const std::string& name) {
    auto image = load_image(kDir + name);
    EXPECT_TRUE(image.ok()) << image.status().message();
    return image.ok() ? std::move(image).value() : Image{};
}

const Image& reference() {
    static const Image image = load("reference.png");
    return image;
}

// Channel c of `image` against channel `ref_channel` of the reference, all pixels.
void expect_channel(const Image& image, int c, int ref_channel, float tolerance,
                    const std::string& what) {
    ASSERT_EQ(image.width(), reference().width()) << what;
    ASSERT_EQ(image.height(), reference().height()) << what;
    float worst = 0.0f;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            worst =
                std::max(worst, std::abs(image.at(x, y, c) - reference().at(x, y, ref_channel)));
    EXPECT_LE(worst, tolerance) << what << " channel " << c;
}

void expect_rgb(const std::string& name, float tolerance) {
    const Image image = load(name);
    ASSERT_GE(image.channels(), 3) << name;
    for (int c = 0; c < 3; ++c) expect_channel(image, c, c, tolerance, name);
}

TEST(ImageFormats, ReferenceIsARealPicture) {
    ASSERT_EQ(reference().width(), 24);
    ASSERT_EQ(reference().height(), 16);
    ASSERT_EQ(reference().channels(), 3);
    float lo = 1.0f, hi = 0.0f;
    for (float v : reference().data()) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    EXPECT_GT(hi - lo, 0.2f);
}

TEST(ImageFormats, LosslessVariantsReadAsTheReference) {
    expect_rgb("rgb16.png", 1e-6f);      // 16-bit: v * 257 / 65535 == v / 255
    expect_rgb("tiled_lzw.tif", 1e-6f);  // tiles of 16x16 over 24x16, LZW
    expect_rgb("planar16.tif", 1e-6f);   // one plane per channel, 16-bit
    expect_rgb("ascii.ppm", 1e-6f);      // P3
    expect_rgb("window.exr", 1e-6f);     // float, data window at (5, 3) of 40x30
    expect_rgb("tiled_piz.exr", 2e-3f);  // half: 11-bit mantissa
    EXPECT_EQ(load("tiled_piz.exr").channel_names(), (std::vector<std::string>{"R", "G", "B"}));
    EXPECT_EQ(load("rgb16.png").channel_names(), (std::vector<std::string>{"R", "G", "B"}));
}

TEST(ImageFormats, GreyFilesHaveOneChannel) {
    for (const char* name : {"grey.tif", "ascii.pgm"}) {
        const Image image = load(name);
        ASSERT_EQ(image.channels(), 1) << name;
        EXPECT_EQ(image.channel_names(), (std::vector<std::string>{"Y"})) << name;
        expect_channel(image, 0, 0, 1e-6f, name);
    }
    const Image jpeg = load("grey.jpg");
    ASSERT_EQ(jpeg.channels(), 1);
    expect_channel(jpeg, 0, 0, 0.1f, "grey.jpg");  // lossy
}

TEST(ImageFormats, AlphaAndExtraChannelsAreKeptUnassociated) {
    const Image extra = load("extra_float.tif");
    ASSERT_EQ(extra.channels(), 5);
    EXPECT_EQ(extra.channel_names(), (std::vector<std::string>{"R", "G", "B", "A", "channel4"}));
    for (int c = 0; c < 3; ++c) expect_channel(extra, c, c, 1e-6f, "extra_float.tif");
    // Colour under alpha 0.5 is the stored colour, neither multiplied nor divided by alpha.
    EXPECT_FLOAT_EQ(extra.at(3, 2, 3), 0.5f);
    EXPECT_FLOAT_EQ(extra.at(7, 9, 4), 0.25f);
}

}  // namespace
}  // namespace exemplar
