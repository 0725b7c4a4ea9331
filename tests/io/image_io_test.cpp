#include "exemplar/io/image_io.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "file_bytes.hpp"
#include "temp_dir.hpp"

namespace exemplar {
namespace {

namespace fs = std::filesystem;

// Each test works in its own empty folder under the system temp folder, removed afterwards.
class ImageIo : public testing::TempDirTest {
protected:
    std::set<std::string> files_in_dir() const {
        std::set<std::string> names;
        for (const auto& entry : fs::directory_iterator(dir_)) {
            names.insert(entry.path().filename().string());
        }
        return names;
    }
};

void write_bytes(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out << bytes;
}

// Deterministic image whose values are multiples of 1/levels (exactly representable in a file
// with that many levels), varying across pixels and channels.
Image quantized_image(int width, int height, int channels, int levels) {
    Image im(width, height, channels);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < channels; ++c) {
                const long k = (static_cast<long>(x) * 37 + y * 101 + c * 53) % (levels + 1);
                im.at(x, y, c) = static_cast<float>(k) / static_cast<float>(levels);
            }
    return im;
}

// Smooth image for lossy formats.
Image gradient_image(int width, int height, int channels) {
    Image im(width, height, channels);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < channels; ++c) {
                im.at(x, y, c) = 0.1f + 0.8f * (static_cast<float>(x + y + 7 * c) /
                                                static_cast<float>(width + height + 7 * channels));
            }
    return im;
}

float max_abs_difference(const Image& a, const Image& b) {
    EXPECT_EQ(a.width(), b.width());
    EXPECT_EQ(a.height(), b.height());
    EXPECT_EQ(a.channels(), b.channels());
    if (a.size() != b.size()) return std::numeric_limits<float>::infinity();
    float worst = 0.0f;
    for (std::size_t i = 0; i < a.size(); ++i) {
        worst = std::max(worst, std::abs(a.data()[i] - b.data()[i]));
    }
    return worst;
}

// Errors are one line naming the file.
void expect_error_names_file(const Status& status, const std::string& file) {
    EXPECT_FALSE(status.is_ok());
    EXPECT_NE(status.message().find(file), std::string::npos) << status.message();
    EXPECT_EQ(status.message().find('\n'), std::string::npos) << status.message();
}

Image round_trip(const Image& image, const std::string& file, PixelFormat format) {
    SaveOptions options;
    options.format = format;
    const Status saved = save_image(image, file, options);
    EXPECT_TRUE(saved.is_ok()) << saved.message();
    auto loaded = load_image(file);
    EXPECT_TRUE(loaded.ok()) << loaded.status().message();
    return loaded.ok() ? std::move(loaded).value() : Image();
}

TEST_F(ImageIo, Png8BitRoundTripIsExact) {
    const Image im = quantized_image(13, 7, 3, 255);
    const Image back = round_trip(im, path("a.png"), PixelFormat::UInt8);
    EXPECT_LT(max_abs_difference(im, back), 1e-6f);
    EXPECT_EQ(back.channel_names(), (std::vector<std::string>{"R", "G", "B"}));
}

TEST_F(ImageIo, Png16BitRoundTripIsExact) {
    const Image im = quantized_image(9, 11, 4, 65535);
    const Image back = round_trip(im, path("a.png"), PixelFormat::UInt16);
    EXPECT_LT(max_abs_difference(im, back), 1e-6f);  // one 16-bit step is 1.5e-5
}

TEST_F(ImageIo, Png8BitRoundsToNearestLevel) {
    Image im(17, 5, 1);
    for (std::size_t i = 0; i < im.size(); ++i) {
        im.data()[i] = static_cast<float>(i % 101) / 100.0f;
    }
    const Image back = round_trip(im, path("gray.png"), PixelFormat::Auto);
    EXPECT_LE(max_abs_difference(im, back), 0.5f / 255.0f + 1e-6f);
    EXPECT_EQ(back.channel_names(), (std::vector<std::string>{"Y"}));
}

TEST_F(ImageIo, RgbaKeepsColourUnderAnyAlpha) {
    Image im = quantized_image(6, 4, 4, 255);
    // Colour under zero and half alpha must come back unchanged (no premultiplication).
    im.at(0, 0, 0) = 204.0f / 255.0f;
    im.at(0, 0, 3) = 0.0f;
    im.at(1, 0, 1) = 153.0f / 255.0f;
    im.at(1, 0, 3) = 128.0f / 255.0f;
    for (const char* name : {"rgba.png", "rgba.tif", "rgba.exr"}) {
        const Image back = round_trip(im, path(name), PixelFormat::Auto);
        ASSERT_EQ(back.channels(), 4) << name;
        EXPECT_LT(max_abs_difference(im, back), 1e-3f) << name;  // EXR: half precision
        EXPECT_EQ(back.channel_names()[3], "A") << name;
        EXPECT_NEAR(back.at(0, 0, 0), 204.0f / 255.0f, 1e-3f) << name;
        EXPECT_NEAR(back.at(1, 0, 1), 153.0f / 255.0f, 1e-3f) << name;
    }
    const Image png = round_trip(im, path("exact.png"), PixelFormat::Auto);
    EXPECT_LT(max_abs_difference(im, png), 1e-6f);
}

TEST_F(ImageIo, PngGrayAlphaRoundTrip) {
    const Image im = quantized_image(5, 5, 2, 65535);
    const Image back = round_trip(im, path("ya.png"), PixelFormat::UInt16);
    EXPECT_LT(max_abs_difference(im, back), 1e-6f);
    EXPECT_EQ(back.channel_names(), (std::vector<std::string>{"Y", "A"}));
}

TEST_F(ImageIo, JpegRoundTripWithinLossyTolerance) {
    const Image im = gradient_image(64, 48, 3);
    const Image back = round_trip(im, path("a.jpg"), PixelFormat::Auto);
    ASSERT_EQ(back.channels(), 3);
    double total = 0.0;
    for (std::size_t i = 0; i < im.size(); ++i) total += std::abs(im.data()[i] - back.data()[i]);
    EXPECT_LT(total / static_cast<double>(im.size()), 0.01);
    EXPECT_LT(max_abs_difference(im, back), 0.06f);

    const Image gray = gradient_image(32, 32, 1);
    EXPECT_LT(max_abs_difference(gray, round_trip(gray, path("gray.jpeg"), PixelFormat::UInt8)),
              0.06f);
}

TEST_F(ImageIo, JpegQualityIsHonouredAndValidated) {
    Image noise(64, 64, 3);
    for (std::size_t i = 0; i < noise.size(); ++i) {
        noise.data()[i] = static_cast<float>((i * 2654435761u) % 1000u) / 1000.0f;
    }
    SaveOptions low;
    low.jpeg_quality = 10;
    SaveOptions high;
    high.jpeg_quality = 95;
    ASSERT_TRUE(save_image(noise, path("low.jpg"), low).is_ok());
    ASSERT_TRUE(save_image(noise, path("high.jpg"), high).is_ok());
    EXPECT_LT(fs::file_size(path("low.jpg")), fs::file_size(path("high.jpg")));

    for (int quality : {0, 101}) {
        SaveOptions bad;
        bad.jpeg_quality = quality;
        const Status status = save_image(noise, path("bad.jpg"), bad);
        EXPECT_EQ(status.code(), ErrorCode::InvalidArgument);
        EXPECT_NE(status.message().find("jpeg_quality"), std::string::npos) << status.message();
        EXPECT_NE(status.message().find("1..100"), std::string::npos) << status.message();
    }
    EXPECT_FALSE(fs::exists(path("bad.jpg")));
}

class TiffRoundTrip : public ImageIo, public ::testing::WithParamInterface<PixelFormat> {};

TEST_P(TiffRoundTrip, FiveChannelsAtEveryDepth) {
    const PixelFormat format = GetParam();
    const Image im = format == PixelFormat::UInt8    ? quantized_image(10, 6, 5, 255)
                     : format == PixelFormat::UInt16 ? quantized_image(10, 6, 5, 65535)
                                                     : gradient_image(10, 6, 5);
    const Image back = round_trip(im, path("a.tif"), format);
    ASSERT_EQ(back.channels(), 5);
    if (format == PixelFormat::Float) {
        EXPECT_EQ(max_abs_difference(im, back), 0.0f);
    } else {
        EXPECT_LT(max_abs_difference(im, back), 1e-6f);
    }
}

INSTANTIATE_TEST_SUITE_P(Formats, TiffRoundTrip,
                         ::testing::Values(PixelFormat::UInt8, PixelFormat::UInt16,
                                           PixelFormat::Float));

TEST_F(ImageIo, TiffAutoIs16BitAndHalfIsRejected) {
    const Image im = quantized_image(4, 4, 3, 65535);
    EXPECT_LT(max_abs_difference(im, round_trip(im, path("auto.tiff"), PixelFormat::Auto)), 1e-6f);
    SaveOptions half;
    half.format = PixelFormat::Half;
    const Status status = save_image(im, path("half.tif"), half);
    EXPECT_EQ(status.code(), ErrorCode::Unsupported);
    expect_error_names_file(status, "half.tif");
}

// Channels come back in the file's order (OpenEXR sorts them), so compare by name.
void expect_same_channels_by_name(const Image& expected, const Image& actual, float tolerance) {
    ASSERT_EQ(expected.channels(), actual.channels());
    ASSERT_TRUE(expected.same_size(actual));
    for (int c = 0; c < expected.channels(); ++c) {
        const std::string& name = expected.channel_names()[static_cast<std::size_t>(c)];
        const int other = find_channel(actual, name);
        ASSERT_GE(other, 0) << "channel " << name << " missing";
        for (int y = 0; y < expected.height(); ++y)
            for (int x = 0; x < expected.width(); ++x) {
                const float e = expected.at(x, y, c);
                EXPECT_NEAR(actual.at(x, y, other), e, tolerance * std::max(1.0f, std::abs(e)))
                    << name << " at " << x << "," << y;
            }
    }
}

Image named_six_channel_image() {
    Image im(7, 5, 6);
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x)
            for (int c = 0; c < 6; ++c) im.at(x, y, c) = 0.37f * x - 0.91f * y + 10.5f * c - 3.0f;
    im.set_channel_names({"R", "G", "B", "A", "depth", "mask"});
    return im;
}

TEST_F(ImageIo, ExrFloatKeepsNamedChannelsExactly) {
    const Image im = named_six_channel_image();
    const Image back = round_trip(im, path("a.exr"), PixelFormat::Float);
    expect_same_channels_by_name(im, back, 0.0f);
}

TEST_F(ImageIo, ExrHalfKeepsNamedChannelsToHalfPrecision) {
    const Image im = named_six_channel_image();
    for (PixelFormat format : {PixelFormat::Half, PixelFormat::Auto}) {
        const Image back = round_trip(im, path("h.exr"), format);
        expect_same_channels_by_name(im, back, 1e-3f);  // half: 11-bit mantissa
    }
    auto names = read_channel_names(path("h.exr"));
    ASSERT_TRUE(names.ok()) << names.status().message();
    EXPECT_EQ(std::set<std::string>(names->begin(), names->end()),
              (std::set<std::string>{"R", "G", "B", "A", "depth", "mask"}));
}

// A file stores channels sorted by name; reading puts them back in a useful order, the one
// OpenImageIO 2.4 gives (each case below was checked with its oiiotool).
TEST_F(ImageIo, ExrChannelsComeBackInCanonicalOrder) {
    using Names = std::vector<std::string>;
    const std::vector<std::pair<Names, Names>> cases = {
        {{"x", "y", "angle", "error"}, {"x", "y", "angle", "error"}},
        {{"B", "G", "R", "A", "depth", "Z"}, {"R", "G", "B", "A", "Z", "depth"}},
        {{"x", "R", "y", "A", "Z", "G", "B"}, {"R", "G", "B", "x", "y", "Z", "A"}},
        {{"Z", "W", "X", "Y"}, {"X", "Y", "Z", "W"}},
        {{"W", "real", "A", "depth", "Zback", "Z", "Y"},
         {"Y", "real", "A", "Z", "depth", "Zback", "W"}},
        {{"AB", "BA", "GA", "AG", "A", "depth"}, {"A", "AG", "GA", "AB", "BA", "depth"}},
        {{"P.Z", "P.Y", "P.X", "N.y", "N.x"}, {"N.x", "N.y", "P.X", "P.Y", "P.Z"}},
        {{"u", "v", "w"}, {"u", "v", "w"}},
    };
    for (const auto& [written, expected] : cases) {
        Image im(2, 2, static_cast<int>(written.size()), 0.5f);
        im.set_channel_names(written);
        ASSERT_TRUE(save_image(im, path("order.exr")).is_ok());
        auto names = read_channel_names(path("order.exr"));
        ASSERT_TRUE(names.ok()) << names.status().message();
        EXPECT_EQ(*names, expected) << written.front();
        EXPECT_EQ(load_image(path("order.exr"))->channel_names(), expected);
    }
}

TEST_F(ImageIo, ExrRejectsIntegerFormatsAndDuplicateNames) {
    Image im = named_six_channel_image();
    SaveOptions u8;
    u8.format = PixelFormat::UInt8;
    EXPECT_EQ(save_image(im, path("a.exr"), u8).code(), ErrorCode::Unsupported);
    im.set_channel_names({"R", "G", "B", "A", "depth", "depth"});
    const Status status = save_image(im, path("a.exr"));
    EXPECT_EQ(status.code(), ErrorCode::InvalidArgument);
    EXPECT_NE(status.message().find("\"depth\""), std::string::npos) << status.message();
    EXPECT_TRUE(files_in_dir().empty());
}

TEST_F(ImageIo, LoadsNonFiniteValues) {
    Image im(3, 1, 1, 0.25f);
    im.at(0, 0, 0) = std::numeric_limits<float>::quiet_NaN();
    im.at(1, 0, 0) = std::numeric_limits<float>::infinity();
    im.at(2, 0, 0) = -std::numeric_limits<float>::infinity();
    const Image back = round_trip(im, path("nan.exr"), PixelFormat::Float);
    ASSERT_EQ(back.size(), 3u);
    EXPECT_TRUE(std::isnan(back.at(0, 0, 0)));
    EXPECT_EQ(back.at(1, 0, 0), std::numeric_limits<float>::infinity());
    EXPECT_EQ(back.at(2, 0, 0), -std::numeric_limits<float>::infinity());
}

TEST_F(ImageIo, IntegerFormatsClampOnWrite) {
    Image im(4, 1, 1);
    im.at(0, 0, 0) = -0.5f;
    im.at(1, 0, 0) = 1.5f;
    im.at(2, 0, 0) = std::numeric_limits<float>::quiet_NaN();
    im.at(3, 0, 0) = 0.5f;
    const Image back = round_trip(im, path("clamp.png"), PixelFormat::UInt16);
    ASSERT_EQ(back.size(), 4u);
    EXPECT_EQ(back.at(0, 0, 0), 0.0f);
    EXPECT_EQ(back.at(1, 0, 0), 1.0f);
    EXPECT_EQ(back.at(2, 0, 0), 0.0f);
    EXPECT_NEAR(back.at(3, 0, 0), 0.5f, 1e-4f);
}

TEST_F(ImageIo, PpmAndPgmRoundTrip) {
    const Image rgb = quantized_image(8, 3, 3, 255);
    EXPECT_LT(max_abs_difference(rgb, round_trip(rgb, path("a.ppm"), PixelFormat::UInt8)), 1e-6f);
    const Image gray = quantized_image(8, 3, 1, 255);
    EXPECT_LT(max_abs_difference(gray, round_trip(gray, path("a.pgm"), PixelFormat::Auto)), 1e-6f);

    const Status wrong_count = save_image(rgb, path("rgb.pgm"));
    EXPECT_EQ(wrong_count.code(), ErrorCode::Unsupported);
    EXPECT_NE(wrong_count.message().find("3 channels"), std::string::npos) << wrong_count.message();
    // PNM is written 8-bit only (the header promises what PixelFormat says).
    SaveOptions u16;
    u16.format = PixelFormat::UInt16;
    EXPECT_EQ(save_image(rgb, path("b.ppm"), u16).code(), ErrorCode::Unsupported);
    EXPECT_FALSE(fs::exists(path("b.ppm")));
}

TEST_F(ImageIo, Reads16BitPnm) {
    // Binary PPM, maxval 65535, two pixels, big-endian samples.
    std::string ppm = "P6\n2 1\n65535\n";
    for (unsigned value : {0u, 32768u, 65535u, 1u, 4096u, 60000u}) {
        ppm.push_back(static_cast<char>(value >> 8));
        ppm.push_back(static_cast<char>(value & 0xFFu));
    }
    write_bytes(path("deep.ppm"), ppm);
    auto loaded = load_image(path("deep.ppm"));
    ASSERT_TRUE(loaded.ok()) << loaded.status().message();
    ASSERT_EQ(loaded->channels(), 3);
    EXPECT_NEAR(loaded->at(0, 0, 1), 32768.0f / 65535.0f, 1e-6f);
    EXPECT_NEAR(loaded->at(1, 0, 0), 1.0f / 65535.0f, 1e-7f);
    EXPECT_FLOAT_EQ(loaded->at(1, 0, 2), 60000.0f / 65535.0f);
}

TEST_F(ImageIo, MultiLayerExr) {
    Image diffuse = gradient_image(6, 4, 3);
    Image specular = gradient_image(6, 4, 3);
    for (float& v : specular.data()) v *= 3.0f;
    Image depth(6, 4, 1, 42.0f);
    depth.set_channel_names({"Z"});
    const std::string file = path("layers.exr");
    const Status saved =
        save_exr_layers({{"diffuse", &diffuse}, {"specular", &specular}, {"depth", &depth}}, file);
    ASSERT_TRUE(saved.is_ok()) << saved.message();

    auto layers = read_layer_names(file);
    ASSERT_TRUE(layers.ok()) << layers.status().message();
    EXPECT_EQ(std::set<std::string>(layers->begin(), layers->end()),
              (std::set<std::string>{"diffuse", "specular", "depth"}));

    auto loaded = load_image_layer(file, "specular");
    ASSERT_TRUE(loaded.ok()) << loaded.status().message();
    EXPECT_EQ(loaded->channel_names(), (std::vector<std::string>{"R", "G", "B"}));
    expect_same_channels_by_name(specular, *loaded, 1e-3f);

    auto z = load_image_layer(file, "depth");
    ASSERT_TRUE(z.ok()) << z.status().message();
    ASSERT_EQ(z->channels(), 1);
    EXPECT_EQ(z->channel_names()[0], "Z");
    EXPECT_EQ(z->at(5, 3, 0), 42.0f);

    auto all = load_image(file);
    ASSERT_TRUE(all.ok()) << all.status().message();
    EXPECT_EQ(all->channels(), 7);
    EXPECT_GE(find_channel(*all, "diffuse.G"), 0);
}

TEST_F(ImageIo, UnnamedLayerComesFirst) {
    Image rgb = gradient_image(3, 3, 3);
    Image extra(3, 3, 2, 0.5f);
    extra.set_channel_names({"u", "v"});
    const std::string file = path("mixed.exr");
    ASSERT_TRUE(save_exr_layers({{"motion", &extra}, {"", &rgb}}, file).is_ok());
    auto layers = read_layer_names(file);
    ASSERT_TRUE(layers.ok()) << layers.status().message();
    EXPECT_EQ(*layers, (std::vector<std::string>{"", "motion"}));
    auto base = load_image_layer(file, "");
    ASSERT_TRUE(base.ok()) << base.status().message();
    expect_same_channels_by_name(rgb, *base, 1e-3f);
}

TEST_F(ImageIo, MissingLayerErrorListsLayers) {
    Image a(2, 2, 3, 0.5f);
    const std::string file = path("layers.exr");
    ASSERT_TRUE(save_exr_layers({{"diffuse", &a}, {"specular", &a}}, file).is_ok());
    auto loaded = load_image_layer(file, "albedo");
    ASSERT_FALSE(loaded.ok());
    const std::string& message = loaded.status().message();
    expect_error_names_file(loaded.status(), file);
    EXPECT_NE(message.find("albedo"), std::string::npos) << message;
    EXPECT_NE(message.find("\"diffuse\""), std::string::npos) << message;
    EXPECT_NE(message.find("\"specular\""), std::string::npos) << message;
}

TEST_F(ImageIo, SaveExrLayersValidatesInputs) {
    Image a(4, 4, 3);
    Image b(5, 4, 3);
    const Status sizes = save_exr_layers({{"a", &a}, {"b", &b}}, path("x.exr"));
    EXPECT_EQ(sizes.code(), ErrorCode::InvalidArgument);
    expect_error_names_file(sizes, "x.exr");
    EXPECT_EQ(save_exr_layers({{"a", &a}}, path("x.png")).code(), ErrorCode::Unsupported);
    EXPECT_EQ(save_exr_layers({}, path("x.exr")).code(), ErrorCode::InvalidArgument);
    EXPECT_EQ(save_exr_layers({{"a", nullptr}}, path("x.exr")).code(), ErrorCode::InvalidArgument);
    EXPECT_TRUE(files_in_dir().empty());
}

TEST_F(ImageIo, MissingFileErrorNamesFile) {
    const std::string file = path("nowhere.png");
    auto loaded = load_image(file);
    ASSERT_FALSE(loaded.ok());
    EXPECT_EQ(loaded.status().code(), ErrorCode::IoError);
    EXPECT_EQ(loaded.status().message(), file + ": no such file");
    EXPECT_FALSE(read_channel_names(file).ok());
    EXPECT_FALSE(read_layer_names(file).ok());
    EXPECT_FALSE(load_image_layer(file, "").ok());
}

TEST_F(ImageIo, CorruptFilesFailQuietlyWithOneLine) {
    // Valid PNG, then damaged copies: garbage, truncated, one flipped bit.
    ASSERT_TRUE(save_image(gradient_image(40, 30, 3), path("good.png")).is_ok());
    const std::string good = testing::file_bytes(path("good.png"));
    std::string flipped = good;
    flipped[flipped.size() / 2] = static_cast<char>(flipped[flipped.size() / 2] ^ 0x10);
    write_bytes(path("x.png"), "this is not an image at all, just some garbage bytes");
    write_bytes(path("truncated.png"), good.substr(0, good.size() / 2));
    write_bytes(path("flipped.png"), flipped);
    write_bytes(path("x.exr"), "garbage garbage garbage garbage");
    write_bytes(path("x.jpg"), "garbage garbage garbage garbage");
    write_bytes(path("x.tif"), "garbage garbage garbage garbage");
    write_bytes(path("empty.ppm"), "");
    // Valid files of the other formats cut in half.
    for (const char* name : {"t.jpg", "t.tif", "t.exr", "t.ppm"}) {
        ASSERT_TRUE(save_image(gradient_image(64, 48, 3), path(name)).is_ok());
        const std::string bytes = testing::file_bytes(path(name));
        write_bytes(path(std::string("truncated_") + name), bytes.substr(0, bytes.size() / 2));
    }

    for (const char* name :
         {"x.png", "truncated.png", "flipped.png", "x.exr", "x.jpg", "x.tif", "empty.ppm",
          "truncated_t.jpg", "truncated_t.tif", "truncated_t.exr", "truncated_t.ppm"}) {
        ::testing::internal::CaptureStderr();
        auto loaded = load_image(path(name));
        const std::string printed = ::testing::internal::GetCapturedStderr();
        ASSERT_FALSE(loaded.ok()) << name;
        EXPECT_EQ(loaded.status().code(), ErrorCode::IoError) << loaded.status().message();
        expect_error_names_file(loaded.status(), name);
        EXPECT_EQ(printed, "") << name << " made the library print";
    }
    auto truncated = load_image(path("truncated.png"));
    EXPECT_NE(truncated.status().message().find("truncated"), std::string::npos)
        << truncated.status().message();
}

TEST_F(ImageIo, FolderIsNotAnImage) {
    fs::create_directories(path("folder.png"));
    auto loaded = load_image(path("folder.png"));
    ASSERT_FALSE(loaded.ok());
    expect_error_names_file(loaded.status(), "folder.png");
}

TEST_F(ImageIo, UnknownExtension) {
    const Image im(2, 2, 3);
    const Status status = save_image(im, path("a.xyz"));
    EXPECT_EQ(status.code(), ErrorCode::Unsupported);
    expect_error_names_file(status, "a.xyz");
    EXPECT_NE(status.message().find(".xyz"), std::string::npos) << status.message();
    EXPECT_EQ(save_image(im, path("noextension")).code(), ErrorCode::Unsupported);

    write_bytes(path("b.xyz"), "garbage garbage garbage garbage");
    auto loaded = load_image(path("b.xyz"));
    ASSERT_FALSE(loaded.ok());
    expect_error_names_file(loaded.status(), "b.xyz");
    EXPECT_TRUE(files_in_dir() == std::set<std::string>{"b.xyz"});
}

TEST_F(ImageIo, ChannelCountsAFormatCannotHoldAreRejected) {
    struct Case {
        const char* file;
        int channels;
        const char* label;
    };
    for (const Case& c : {Case{"five.png", 5, "PNG"}, Case{"rgba.jpg", 4, "JPEG"},
                          Case{"two.jpg", 2, "JPEG"}, Case{"rgba.ppm", 4, "PPM"}}) {
        const Status status = save_image(Image(3, 3, c.channels), path(c.file));
        EXPECT_EQ(status.code(), ErrorCode::Unsupported) << c.file;
        expect_error_names_file(status, c.file);
        EXPECT_NE(status.message().find(c.label), std::string::npos) << status.message();
        EXPECT_NE(status.message().find(std::to_string(c.channels) + " channels"),
                  std::string::npos)
            << status.message();
    }
    EXPECT_TRUE(files_in_dir().empty());
}

TEST_F(ImageIo, SampleFormatsAFormatCannotHoldAreRejected) {
    const Image im(3, 3, 3);
    SaveOptions float_options;
    float_options.format = PixelFormat::Float;
    SaveOptions u16_options;
    u16_options.format = PixelFormat::UInt16;
    EXPECT_EQ(save_image(im, path("f.png"), float_options).code(), ErrorCode::Unsupported);
    EXPECT_EQ(save_image(im, path("f.ppm"), float_options).code(), ErrorCode::Unsupported);
    EXPECT_EQ(save_image(im, path("a.jpg"), u16_options).code(), ErrorCode::Unsupported);
    EXPECT_TRUE(files_in_dir().empty());
}

TEST_F(ImageIo, EmptyImageAndFileInTheWayAreErrors) {
    EXPECT_EQ(save_image(Image(), path("empty.png")).code(), ErrorCode::InvalidArgument);
    EXPECT_TRUE(files_in_dir().empty());
    // A file where a folder of the destination would go: one line naming both.
    ASSERT_TRUE(save_image(Image(2, 2, 3), path("blocker.png")).is_ok());
    const std::string file = path("blocker.png/sub/out.png");
    const Status status = save_image(Image(2, 2, 3), file);
    EXPECT_EQ(status.code(), ErrorCode::IoError);
    expect_error_names_file(status, file);
    EXPECT_NE(status.message().find("blocker.png is a file, not a folder"), std::string::npos)
        << status.message();
    EXPECT_EQ(files_in_dir(), std::set<std::string>{"blocker.png"});
}

// Missing folders of a destination are created (as Blender does), and the write stays atomic.
TEST_F(ImageIo, MissingFoldersAreCreated) {
    const Image im = gradient_image(4, 3, 3);
    ASSERT_TRUE(save_image(im, path("new/deeper/out.png")).is_ok());
    auto back = load_image(path("new/deeper/out.png"));
    ASSERT_TRUE(back.ok()) << back.status().message();
    EXPECT_EQ(back->width(), 4);
    EXPECT_EQ(std::distance(fs::directory_iterator(path("new/deeper")), fs::directory_iterator()),
              1);
}

TEST_F(ImageIo, AtomicWritesLeaveNoTemporaryFiles) {
    const Image im = gradient_image(5, 5, 3);
    for (const char* name : {"a.png", "a.jpg", "a.tif", "a.exr", "a.ppm"}) {
        ASSERT_TRUE(save_image(im, path(name)).is_ok()) << name;
    }
    ASSERT_TRUE(save_image(im, path("a.png")).is_ok());  // overwrite
    EXPECT_EQ(files_in_dir(), (std::set<std::string>{"a.png", "a.jpg", "a.tif", "a.exr", "a.ppm"}));
}

TEST_F(ImageIo, FailedWriteKeepsExistingDestination) {
    const std::string file = path("out.png");
    ASSERT_TRUE(save_image(gradient_image(4, 4, 3), file).is_ok());
    const std::string before = testing::file_bytes(file);

    // Rejected before anything is written.
    EXPECT_FALSE(save_image(Image(4, 4, 5), file).is_ok());
    EXPECT_EQ(testing::file_bytes(file), before);
    EXPECT_EQ(files_in_dir(), std::set<std::string>{"out.png"});

    // Fails at the final rename (the destination is a non-empty folder): the temporary file,
    // already complete, must be removed.
    fs::create_directories(path("taken.png/inside"));
    const Status status = save_image(gradient_image(4, 4, 3), path("taken.png"));
    EXPECT_EQ(status.code(), ErrorCode::IoError);
    expect_error_names_file(status, "taken.png");
    EXPECT_TRUE(fs::is_directory(path("taken.png/inside")));
    EXPECT_EQ(files_in_dir(), (std::set<std::string>{"out.png", "taken.png"}));
}

TEST_F(ImageIo, LoadsBundledStyleImage) {
    const std::string file = std::string(EXEMPLAR_SOURCE_DIR) + "/examples/stylit/source_style.png";
    auto loaded = load_image(file);
    ASSERT_TRUE(loaded.ok()) << loaded.status().message();
    EXPECT_EQ(loaded->width(), 600);
    EXPECT_EQ(loaded->height(), 456);
    ASSERT_GE(loaded->channels(), 3);
    const auto [lo, hi] = std::minmax_element(loaded->data().begin(), loaded->data().end());
    EXPECT_GE(*lo, 0.0f);
    EXPECT_LE(*hi, 1.0f);
    EXPECT_GT(*hi - *lo, 0.5f);  // real content, not a flat image
}

}  // namespace
}  // namespace exemplar
