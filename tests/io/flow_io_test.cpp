// Middlebury .flo and EXR flow files: round trips, known values of a ground-truth flow file,
// and one-line errors for bad magic, truncated and oversized files.

#include "exemplar/io/flow_io.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "exemplar/io/image_io.hpp"
#include "temp_dir.hpp"

namespace exemplar {
namespace {

namespace fs = std::filesystem;

// The synthetic pair's exact flow (tests/data/flow, written by bench/make_flow_pair).
const std::string kPairFlow = std::string(EXEMPLAR_TEST_DATA_DIR) + "/flow/synthetic-gt.flo";

class FlowIo : public exemplar::testing::TempDirTest {
protected:
    std::string bytes(const std::string& file) const {
        std::ifstream in(file, std::ios::binary);
        return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    }
    void write_bytes(const std::string& name, const std::string& data) const {
        std::ofstream(path(name), std::ios::binary) << data;
    }
    std::size_t entries() const {
        return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), {}));
    }
};

TEST_F(FlowIo, ReadsGroundTruthFile) {
    auto flow = load_flo(kPairFlow);
    ASSERT_TRUE(flow.ok()) << flow.status().message();
    EXPECT_EQ(flow->width(), 256);
    EXPECT_EQ(flow->height(), 192);
    ASSERT_EQ(flow->channels(), 2);
    EXPECT_EQ(flow->channel_names(), (std::vector<std::string>{"u", "v"}));
    // Values read with an independent script (Python's struct.unpack of the raw file). At
    // (75, 70) and (170, 110), the centres of two objects, the flow is their shift exactly.
    EXPECT_FLOAT_EQ(flow->at(0, 0, 0), 3.0479865f);
    EXPECT_FLOAT_EQ(flow->at(0, 0, 1), -7.3041077f);
    EXPECT_FLOAT_EQ(flow->at(75, 70, 0), 17.0f);
    EXPECT_FLOAT_EQ(flow->at(75, 70, 1), 8.0f);
    EXPECT_FLOAT_EQ(flow->at(170, 110, 0), -21.0f);
    EXPECT_FLOAT_EQ(flow->at(170, 110, 1), 9.0f);
    EXPECT_FLOAT_EQ(flow->at(255, 191, 0), 2.9590635f);
    EXPECT_FLOAT_EQ(flow->at(255, 191, 1), 3.2577567f);
}

TEST_F(FlowIo, FloRoundTripIsByteExact) {
    auto flow = load_flo(kPairFlow);
    ASSERT_TRUE(flow.ok());
    ASSERT_TRUE(save_flo(*flow, path("copy.flo")).is_ok());
    EXPECT_EQ(bytes(path("copy.flo")), bytes(kPairFlow));
    EXPECT_EQ(entries(), 1u) << "no temporary file left behind";
}

TEST_F(FlowIo, ExrRoundTripIsExactAndLoadsThroughLayers) {
    auto flow = load_flo(kPairFlow);
    ASSERT_TRUE(flow.ok());
    ASSERT_TRUE(save_flow(*flow, path("flow.exr")).is_ok());
    auto back = load_flow(path("flow.exr"));
    ASSERT_TRUE(back.ok()) << back.status().message();
    ASSERT_EQ(back->size(), flow->size());
    EXPECT_EQ(std::memcmp(back->data().data(), flow->data().data(), flow->size() * 4), 0);

    // A renderer's multi-layer EXR: the flow in layer "motion" beside the colour.
    Image colour(flow->width(), flow->height(), 3, 0.5f);
    Image motion = *flow;
    motion.set_channel_names({"x", "y"});
    ASSERT_TRUE(save_exr_layers({{"", &colour}, {"motion", &motion}}, path("render.exr"),
                                {PixelFormat::Float})
                    .is_ok());
    auto layer = load_flow(path("render.exr"), "motion");
    ASSERT_TRUE(layer.ok()) << layer.status().message();
    EXPECT_EQ(layer->channel_names(), (std::vector<std::string>{"u", "v"}));
    EXPECT_FLOAT_EQ(layer->at(75, 70, 1), 8.0f);

    auto colour_layer = load_flow(path("render.exr"), "");
    ASSERT_FALSE(colour_layer.ok());
    EXPECT_NE(colour_layer.status().message().find("has 3 channels"), std::string::npos)
        << colour_layer.status().message();
}

TEST_F(FlowIo, RejectsBadFiles) {
    const std::string good = bytes(kPairFlow);
    write_bytes("magic.flo", "XXXX" + good.substr(4));
    write_bytes("truncated.flo", good.substr(0, good.size() - 100));
    write_bytes("oversized.flo", good + "0123");
    write_bytes("header.flo", good.substr(0, 6));
    std::string huge = good.substr(0, 12);
    const std::int32_t side = 1 << 20;
    std::memcpy(huge.data() + 4, &side, 4);
    write_bytes("huge.flo", huge);

    const std::pair<const char*, const char*> cases[] = {
        {"magic.flo", "bad magic number"},
        {"truncated.flo", "truncated .flo file: 393128 bytes, but a 256x192 flow needs 393228"},
        {"oversized.flo", "oversized .flo file"},
        {"header.flo", "the header alone has 12"},
        {"huge.flo", "corrupt .flo header: size 1048576x192"},
        {"missing.flo", "no such file"},
    };
    for (const auto& [name, part] : cases) {
        auto flow = load_flo(path(name));
        ASSERT_FALSE(flow.ok()) << name;
        EXPECT_EQ(flow.status().code(), ErrorCode::IoError) << name;
        const std::string& message = flow.status().message();
        EXPECT_EQ(message.rfind(path(name), 0), 0u) << message;
        EXPECT_NE(message.find(part), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

TEST_F(FlowIo, RejectsNonFlowImagesAndFormats) {
    Image rgb(4, 4, 3);
    const Status bad = save_flo(rgb, path("x.flo"));
    EXPECT_EQ(bad.code(), ErrorCode::InvalidArgument);
    EXPECT_NE(bad.message().find("needs 2 channels"), std::string::npos) << bad.message();
    const Status png = save_flow(Image(4, 4, 2), path("x.png"));
    EXPECT_EQ(png.code(), ErrorCode::Unsupported) << png.message();
    EXPECT_EQ(entries(), 0u);
    // Missing folders are created; a file in the way of one is an error.
    ASSERT_TRUE(save_flo(Image(4, 4, 2), path("new/x.flo")).is_ok());
    const Status folder = save_flo(Image(4, 4, 2), path("new/x.flo/y.flo"));
    EXPECT_EQ(folder.code(), ErrorCode::IoError) << folder.message();
    EXPECT_NE(folder.message().find("is a file, not a folder"), std::string::npos)
        << folder.message();
    auto layered = load_flow(kPairFlow, "motion");
    EXPECT_EQ(layered.status().code(), ErrorCode::InvalidArgument);
}

}  // namespace
}  // namespace exemplar
