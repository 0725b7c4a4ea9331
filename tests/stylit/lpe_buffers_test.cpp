// Loading LPE buffer sets: PNG lists, multi-layer EXRs with each preset (written here), folders
// of `exemplar render`, and the errors a user meets: a missing layer (the message lists the
// file's layers), buffers of different sizes, unpaired buffers.

#include "exemplar/stylit/lpe_buffers.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "exemplar/io/image_io.hpp"
#include "exemplar/stylit/stylit.hpp"
#include "temp_dir.hpp"

namespace exemplar {
namespace {

namespace fs = std::filesystem;

Image constant(int w, int h, int channels, float value) {
    return Image(w, h, channels, value);
}

class LpeBuffers : public exemplar::testing::TempDirTest {
protected:
    // A multi-layer EXR whose layer i is constant 0.1 * (i + 1), RGB (the first RGBA).
    std::string write_layers(const std::string& name, const std::vector<std::string>& layers) {
        std::vector<Image> images;
        for (std::size_t i = 0; i < layers.size(); ++i) {
            images.push_back(constant(8, 6, i == 0 ? 4 : 3, 0.1f * static_cast<float>(i + 1)));
        }
        std::vector<std::pair<std::string, const Image*>> entries;
        for (std::size_t i = 0; i < layers.size(); ++i) entries.push_back({layers[i], &images[i]});
        const Status status = save_exr_layers(entries, path(name));
        EXPECT_TRUE(status.is_ok()) << status.message();
        return path(name);
    }

    static void expect_guide_order(const std::vector<LpeBuffer>& buffers) {
        ASSERT_EQ(buffers.size(), 4u);
        for (std::size_t i = 0; i < 4; ++i) {
            EXPECT_EQ(buffers[i].image.channels(), 3) << buffers[i].origin;  // alpha dropped
            EXPECT_NEAR(buffers[i].image.at(3, 2, 0), 0.1f * static_cast<float>(i + 1), 1e-3f);
        }
    }
};

TEST_F(LpeBuffers, PngListKeepsTheOrder) {
    std::vector<std::string> paths;
    for (int i = 0; i < 3; ++i) {
        paths.push_back(path(std::string(1, static_cast<char>('a' + i)) + ".png"));
        ASSERT_TRUE(
            save_image(constant(8, 6, 3, 0.2f * static_cast<float>(i)), paths.back()).is_ok());
    }
    auto buffers = load_lpe_buffers(paths, *find_layer_preset("exemplar"));
    ASSERT_TRUE(buffers.ok()) << buffers.status().message();
    ASSERT_EQ(buffers->size(), 3u);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR((*buffers)[i].image.at(0, 0, 0), 0.2f * static_cast<float>(i), 1.0f / 255.0f);
        EXPECT_EQ((*buffers)[i].origin, paths[i]);
    }
}

TEST_F(LpeBuffers, ExemplarPresetReadsTheRenderersLayerNames) {
    // The layers `exemplar render --output x.exr` writes, in its order, with the extra buffers.
    const std::string exr =
        write_layers("ours.exr", {"fullgi", "direct_diffuse", "direct_specular", "indirect_diffuse",
                                  "diffuse_bounces", "diffuse_interreflection"});
    auto buffers = load_lpe_buffers({exr}, *find_layer_preset("exemplar"));
    ASSERT_TRUE(buffers.ok()) << buffers.status().message();
    expect_guide_order(*buffers);
    EXPECT_EQ((*buffers)[3].name, "indirect_diffuse");
    // The names of the preset's first version still work.
    const std::string old =
        write_layers("old.exr", {"full", "direct_diffuse", "direct_specular", "indirect"});
    buffers = load_lpe_buffers({old}, *find_layer_preset("exemplar"));
    ASSERT_TRUE(buffers.ok()) << buffers.status().message();
    expect_guide_order(*buffers);
}

TEST_F(LpeBuffers, FolderOfOneFilePerBuffer) {
    // What `exemplar render --output DIR` writes: <buffer>.png, picked by the preset's names.
    fs::create_directories(dir_ / "render");
    const std::vector<std::string> names = {"alpha", "direct_specular", "fullgi",
                                            "indirect_diffuse", "direct_diffuse"};
    const std::vector<float> values = {0.9f, 0.6f, 0.2f, 0.8f, 0.4f};
    for (std::size_t i = 0; i < names.size(); ++i) {
        ASSERT_TRUE(
            save_image(constant(8, 6, 3, values[i]), path("render/" + names[i] + ".png")).is_ok());
    }
    auto buffers = load_lpe_buffers({path("render")}, *find_layer_preset("exemplar"));
    ASSERT_TRUE(buffers.ok()) << buffers.status().message();
    ASSERT_EQ(buffers->size(), 4u);
    const float expected[] = {0.2f, 0.4f, 0.6f, 0.8f};
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_NEAR((*buffers)[i].image.at(1, 1, 0), expected[i], 1.0f / 255.0f) << i;
    }
    EXPECT_EQ((*buffers)[0].origin, path("render/fullgi.png"));

    // A missing buffer names the folder and the files looked for; .png and .exr of one buffer
    // are ambiguous.
    fs::remove(path("render/direct_specular.png"));
    buffers = load_lpe_buffers({path("render")}, *find_layer_preset("exemplar"));
    ASSERT_FALSE(buffers.ok());
    EXPECT_EQ(buffers.status().code(), ErrorCode::IoError);
    EXPECT_NE(buffers.status().message().find(path("render") + ": no file direct_specular.png or "
                                                               "direct_specular.exr"),
              std::string::npos)
        << buffers.status().message();
    ASSERT_TRUE(save_image(constant(8, 6, 3, 0.6f), path("render/direct_specular.png")).is_ok());
    ASSERT_TRUE(save_image(constant(8, 6, 3, 0.6f), path("render/direct_specular.exr")).is_ok());
    buffers = load_lpe_buffers({path("render")}, *find_layer_preset("exemplar"));
    ASSERT_FALSE(buffers.ok());
    EXPECT_NE(buffers.status().message().find("ambiguous"), std::string::npos)
        << buffers.status().message();
}

TEST_F(LpeBuffers, CyclesPresetWithViewLayerPrefixAndOtherPasses) {
    // Blender names layers "<view layer>.<pass>" and writes more passes than StyLit needs.
    const std::string exr =
        write_layers("cycles.exr", {"ViewLayer.Combined", "ViewLayer.GlossDir", "ViewLayer.DiffInd",
                                    "ViewLayer.DiffDir", "ViewLayer.DiffCol"});
    auto buffers = load_lpe_buffers({exr}, *find_layer_preset("cycles"));
    ASSERT_TRUE(buffers.ok()) << buffers.status().message();
    ASSERT_EQ(buffers->size(), 4u);
    // File order: Combined 0.1, GlossDir 0.2, DiffInd 0.3, DiffDir 0.4 -> guide order.
    EXPECT_NEAR((*buffers)[0].image.at(0, 0, 0), 0.1f, 1e-3f);
    EXPECT_NEAR((*buffers)[1].image.at(0, 0, 0), 0.4f, 1e-3f);
    EXPECT_NEAR((*buffers)[2].image.at(0, 0, 0), 0.2f, 1e-3f);
    EXPECT_NEAR((*buffers)[3].image.at(0, 0, 0), 0.3f, 1e-3f);
    EXPECT_EQ((*buffers)[1].name, "ViewLayer.DiffDir");
    EXPECT_EQ((*buffers)[0].image.channels(), 3);
}

TEST_F(LpeBuffers, ArnoldPresetWithUnprefixedBeauty) {
    // Arnold writes the beauty as plain R, G, B, A and AOVs as "<aov>.R".
    const std::string exr =
        write_layers("arnold.exr", {"", "diffuse_direct", "specular_direct", "diffuse_indirect"});
    auto buffers = load_lpe_buffers({exr}, *find_layer_preset("arnold"));
    ASSERT_TRUE(buffers.ok()) << buffers.status().message();
    expect_guide_order(*buffers);
}

TEST_F(LpeBuffers, CustomLayerList) {
    const std::string exr = write_layers("custom.exr", {"beauty", "a", "b", "c"});
    auto preset = custom_layer_preset("beauty,a,b,c");
    ASSERT_TRUE(preset.ok());
    auto buffers = load_lpe_buffers({exr}, *preset);
    ASSERT_TRUE(buffers.ok()) << buffers.status().message();
    expect_guide_order(*buffers);
    EXPECT_FALSE(custom_layer_preset("a,,b").ok());
    EXPECT_FALSE(find_layer_preset("vray").ok());
}

TEST_F(LpeBuffers, MissingLayerListsTheLayersTheFileHas) {
    const std::string exr = write_layers("partial.exr", {"Combined", "DiffDir", "DiffInd"});
    auto buffers = load_lpe_buffers({exr}, *find_layer_preset("cycles"));
    ASSERT_FALSE(buffers.ok());
    const std::string& message = buffers.status().message();
    EXPECT_EQ(buffers.status().code(), ErrorCode::IoError);
    EXPECT_NE(message.find("no layer GlossDir"), std::string::npos) << message;
    EXPECT_NE(message.find("direct specular"), std::string::npos) << message;
    EXPECT_NE(message.find("Combined, DiffDir, DiffInd"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
}

TEST_F(LpeBuffers, BuffersOfDifferentSizesAreRejected) {
    ASSERT_TRUE(save_image(constant(8, 6, 3, 0.5f), path("a.png")).is_ok());
    ASSERT_TRUE(save_image(constant(9, 6, 3, 0.5f), path("b.png")).is_ok());
    auto buffers = load_lpe_buffers({path("a.png"), path("b.png")}, *find_layer_preset("exemplar"));
    ASSERT_FALSE(buffers.ok());
    EXPECT_NE(buffers.status().message().find("9x6"), std::string::npos);
    EXPECT_NE(buffers.status().message().find("8x6"), std::string::npos);
}

TEST_F(LpeBuffers, PairsMustMatchInCountChannelsAndExemplarSize) {
    const LpeBuffer rgb{"a", "a.png", constant(8, 6, 3, 0.5f)};
    const LpeBuffer grey{"g", "g.png", constant(8, 6, 1, 0.5f)};
    EXPECT_TRUE(check_buffer_pairs({rgb, rgb}, {rgb, rgb}, 8, 6).is_ok());
    EXPECT_NE(check_buffer_pairs({rgb, rgb}, {rgb}, 8, 6).message().find("--target has 1"),
              std::string::npos);
    EXPECT_NE(check_buffer_pairs({rgb}, {grey}, 8, 6).message().find("g.png has 1"),
              std::string::npos);
    EXPECT_NE(check_buffer_pairs({rgb}, {rgb}, 10, 6).message().find("exemplar painting is 10x6"),
              std::string::npos);
}

TEST(StylitInput, SplitsTheGuidanceWeightOverTheBuffers) {
    const LpeBuffer buffer{"a", "a.png", Image(8, 6, 3, 0.5f)};
    const std::vector<LpeBuffer> four(4, buffer);
    auto input = stylit_input(Image(8, 6, 3, 0.5f), four, four, StylitOptions{});
    ASSERT_TRUE(input.ok()) << input.status().message();
    ASSERT_EQ(input->guides.size(), 4u);
    for (const GuidePair& guide : input->guides) EXPECT_FLOAT_EQ(guide.weight, 0.5f);
    StylitOptions bad;
    bad.guidance_weight = -1.0f;
    EXPECT_FALSE(stylit_input(Image(8, 6, 3, 0.5f), four, four, bad).ok());
}

}  // namespace
}  // namespace exemplar
