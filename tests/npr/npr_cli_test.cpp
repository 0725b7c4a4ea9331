// `exemplar npr` through run_cli on frame folders that `exemplar render --frames` writes (a
// tiny moving sphere): outputs, resume with identical bytes, MP4, one-line errors with exit code 1
// that keep the finished frames.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "cli_fixture.hpp"
#include "exemplar/io/image_io.hpp"
#include "npr_patterns.hpp"
#include "temp_dir.hpp"

namespace exemplar::npr {
namespace {

namespace fs = std::filesystem;
using cli::testing::CliRun;
using cli::testing::file_bytes;
using cli::testing::run;

// Three 64x48 frames of a sphere moving right, and a 64x64 stipple pattern.
class NprCli : public exemplar::testing::TempDirTest {
protected:
    void SetUp() override {
        TempDirTest::SetUp();
        std::ofstream(path("scene.json")) << R"({
            "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov_deg": 40},
            "sky": [0.8, 0.8, 0.8],
            "materials": [{"name": "m"}],
            "objects": [{"shape": "sphere", "material": "m", "subdivisions": 24,
                         "keyframes": [{"frame": 0, "translate": [0, 0, 0]},
                                       {"frame": 10, "translate": [1, 0, 0]}]}]})";
        const CliRun render =
            run({"render", "--scene", path("scene.json"), "--width", "64", "--height", "48",
                 "--spp", "2", "-j", "2", "--frames", "0-2", "-o", path("R/frame_%04d"), "-q"});
        ASSERT_EQ(render.code, 0) << render.err;
        ASSERT_TRUE(save_image(testing::stipple_pattern(64, 5.0f), path("stipple.png")).is_ok());
    }

    // The bytes of the outputs O/0000.png .. O/0002.png.
    std::vector<std::string> outputs() const {
        std::vector<std::string> bytes;
        for (int n = 0; n <= 2; ++n)
            bytes.push_back(file_bytes(path("O/000" + std::to_string(n) + ".png")));
        return bytes;
    }
    std::vector<std::string> npr(std::vector<std::string> more) const {
        std::vector<std::string> args = {"npr",
                                         "--pattern",
                                         path("stipple.png"),
                                         "--frames",
                                         path("R/frame_%04d"),
                                         "--first",
                                         "0",
                                         "--last",
                                         "2",
                                         "-o",
                                         path("O/%04d.png"),
                                         "--tone",
                                         "fullgi",
                                         "-j",
                                         "2",
                                         "-q"};
        args.insert(args.end(), more.begin(), more.end());
        return args;
    }
};

TEST_F(NprCli, WritesThresholdedFramesAndResumesToTheSameBytes) {
    const CliRun first = run(npr({}));
    ASSERT_EQ(first.code, 0) << first.err;
    for (int n = 0; n <= 2; ++n) {
        const std::string out = path("O/000" + std::to_string(n) + ".png");
        ASSERT_TRUE(fs::exists(out)) << out;
        ASSERT_TRUE(fs::exists(out + ".state.exr")) << out;
    }
    const std::vector<std::string> first_outputs = outputs();
    const Result<Image> image = load_image(path("O/0001.png"));
    ASSERT_TRUE(image.ok());
    EXPECT_EQ(image->width(), 64);
    EXPECT_EQ(image->height(), 48);
    int ink = 0;
    for (float v : image->data()) {
        EXPECT_TRUE(v == 0.0f || v == 1.0f);
        ink += v == 0.0f;
    }
    EXPECT_GT(ink, 0);
    EXPECT_LT(ink, 64 * 48);
    // Everything done: nothing rewritten
    CliRun again = run(npr({}));
    ASSERT_EQ(again.code, 0) << again.err;
    // Frames 1 and 2 redone from frame 0's stored state: the same bytes
    fs::remove(path("O/0001.png"));
    fs::remove(path("O/0002.png"));
    again = run(npr({}));
    ASSERT_EQ(again.code, 0) << again.err;
    EXPECT_EQ(outputs(), first_outputs);
}

TEST_F(NprCli, WritesAnMp4OfTheRange) {
    const CliRun r = run(npr({"--mp4", path("movie/npr.mp4")}));
    ASSERT_EQ(r.code, 0) << r.err;
    ASSERT_TRUE(fs::exists(path("movie/npr.mp4")));
    EXPECT_GT(fs::file_size(path("movie/npr.mp4")), 1000u);
    EXPECT_TRUE(fs::exists(path("O/0002.png")));
}

TEST_F(NprCli, HatchStyleUsesTheOrientationBuffer) {
    ASSERT_TRUE(save_image(testing::hatching_pattern(64, 8, 2.5f), path("hatch.png")).is_ok());
    std::vector<std::string> args = npr({"--style", "hatch"});
    args[2] = path("hatch.png");
    const CliRun hatch = run(args);
    ASSERT_EQ(hatch.code, 0) << hatch.err;
    EXPECT_TRUE(fs::exists(path("O/0002.png")));
    // Without the buffer the hatch style fails, naming it
    fs::remove_all(path("O"));
    fs::remove(path("R/frame_0000/orientation.exr"));
    const CliRun missing = run(args);
    EXPECT_EQ(missing.code, 1);
    EXPECT_NE(missing.err.find("missing buffer 'orientation'"), std::string::npos) << missing.err;
}

// The paper layer: a scanned paper texture (tests/data/paper), its state stored beside the
// pattern's so that a resumed run gives the same bytes; outside the sphere (alpha) only paper
// (and the sphere's silhouette line).
TEST_F(NprCli, PaperLayerResumesToTheSameBytes) {
    const std::string paper = std::string(EXEMPLAR_TEST_DATA_DIR) + "/paper/struc.pgm";
    const CliRun first = run(npr({"--paper", paper, "--erosion", "1.5"}));
    ASSERT_EQ(first.code, 0) << first.err;
    for (int n = 0; n <= 2; ++n) {
        const std::string out = path("O/000" + std::to_string(n) + ".png");
        ASSERT_TRUE(fs::exists(out + ".paper.state.exr")) << out;
    }
    const std::vector<std::string> first_outputs = outputs();
    const Result<Image> image = load_image(path("O/0001.png"));
    const Result<Image> alpha = load_image(path("R/frame_0001/alpha.png"));
    const Result<Image> lines = load_image(path("R/frame_0001/lines.png"));
    ASSERT_TRUE(image.ok() && alpha.ok() && lines.ok());
    int outside = 0, light = 0;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x)
            if (alpha->at(x, y, 0) < 0.5f && lines->at(x, y, 0) < 0.5f) {
                ++outside;
                light += image->at(x, y, 0) >= 0.8f;  // paper: 1 - 0.15 at the darkest grain
            }
    EXPECT_GT(outside, 100);
    EXPECT_EQ(light, outside);
    fs::remove(path("O/0001.png"));
    fs::remove(path("O/0002.png"));
    const CliRun again = run(npr({"--paper", paper, "--erosion", "1.5"}));
    ASSERT_EQ(again.code, 0) << again.err;
    EXPECT_EQ(outputs(), first_outputs);
    // The paper's options need the paper; a paper too small is named
    const CliRun grain = run(npr({"--paper-grain", "0.5"}));
    EXPECT_EQ(grain.code, 1);
    EXPECT_EQ(grain.err, "exemplar: --paper-grain: needs --paper\n");
    ASSERT_TRUE(save_image(testing::halftone_pattern(16, 8), path("tiny.png")).is_ok());
    const CliRun small = run(npr({"--paper", path("tiny.png")}));
    EXPECT_EQ(small.code, 1);
    EXPECT_NE(small.err.find("--paper " + path("tiny.png") + ": pattern: 16x16 is too small"),
              std::string::npos)
        << small.err;
}

// The bidirectional loop: frame 0, then frames 1-2 forward and frame 1 again backward along
// frame 1's forward flow, the part visible since frame 0 held; resumes to the same bytes.
TEST_F(NprCli, BidirectionalLoopResumesToTheSameBytes) {
    const CliRun first = run(npr({"--bidirectional", "2"}));
    ASSERT_EQ(first.code, 0) << first.err;
    const std::vector<std::string> first_outputs = outputs();
    // The forward-only run has the same first frame; frame 1's hidden strip was redone backward
    // (its coordinates differ)
    std::vector<std::string> args = npr({"--bidirectional", "0"});
    args[10] = path("F/%04d.png");
    const CliRun forward = run(args);
    ASSERT_EQ(forward.code, 0) << forward.err;
    EXPECT_EQ(file_bytes(path("F/0000.png")), first_outputs[0]);
    EXPECT_NE(file_bytes(path("F/0001.png.state.exr")), file_bytes(path("O/0001.png.state.exr")));
    // An unfinished block is done again as a whole
    fs::remove(path("O/0001.png"));
    const CliRun again = run(npr({"--bidirectional", "2"}));
    ASSERT_EQ(again.code, 0) << again.err;
    EXPECT_EQ(outputs(), first_outputs);
    // With the paper layer: both held and redone backward
    std::vector<std::string> with_paper =
        npr({"--bidirectional", "2", "--paper",
             std::string(EXEMPLAR_TEST_DATA_DIR) + "/paper/struc.pgm"});
    with_paper[10] = path("P/%04d.png");
    const CliRun papered = run(with_paper);
    EXPECT_EQ(papered.code, 0) << papered.err;
    EXPECT_TRUE(fs::exists(path("P/0002.png.paper.state.exr")));
    // It needs the forward flow
    fs::remove_all(path("O"));
    fs::remove(path("R/frame_0001/forward_flow.exr"));
    const CliRun missing = run(npr({"--bidirectional", "2"}));
    EXPECT_EQ(missing.code, 1);
    EXPECT_NE(missing.err.find(path("R/frame_0001") + ": missing buffer 'forward_flow'"),
              std::string::npos)
        << missing.err;
    EXPECT_TRUE(fs::exists(path("O/0000.png")));
    const CliRun one = run(npr({"--bidirectional", "1"}));
    EXPECT_EQ(one.err, "exemplar: --bidirectional: 1 is invalid (must be 0 or 2..1000)\n");
}

// Any exemplar render animation: the bundled camera zoom, squash-and-stretch hop and turntable
// (two tiny frames each) go through exemplar npr.
TEST_F(NprCli, RunsOnTheBundledZoomDeformingAndTurntableAnimations) {
    for (const char* scene : {"spot-zoom", "spot-squash", "spot-turntable"}) {
        const std::string frames = path(std::string(scene) + "/frame_%04d");
        const CliRun render =
            run({"render", "--scene",
                 std::string(EXEMPLAR_SOURCE_DIR) + "/examples/render/" + scene + ".json",
                 "--width", "64", "--height", "48", "--spp", "1", "-j", "2", "--frames", "0-1",
                 "-o", frames, "-q"});
        ASSERT_EQ(render.code, 0) << scene << ": " << render.err;
        std::vector<std::string> args = npr({"--style", "hatch"});
        args[2] = path("hatch.png");
        args[4] = frames;
        args[8] = "1";
        args[10] = path(std::string(scene) + "/O/%04d.png");
        ASSERT_TRUE(save_image(testing::hatching_pattern(64, 8, 2.5f), path("hatch.png")).is_ok());
        const CliRun styled = run(args);
        ASSERT_EQ(styled.code, 0) << scene << ": " << styled.err;
        EXPECT_TRUE(fs::exists(path(std::string(scene) + "/O/0001.png"))) << scene;
    }
}

TEST_F(NprCli, AMissingBufferIsNamedAndFinishedFramesAreKept) {
    fs::remove(path("R/frame_0002/backward_flow.exr"));
    const CliRun r = run(npr({}));
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find(path("R/frame_0002") + ": missing buffer 'backward_flow'"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(fs::exists(path("O/0000.png")));
    EXPECT_TRUE(fs::exists(path("O/0001.png")));
    EXPECT_FALSE(fs::exists(path("O/0002.png")));
}

TEST_F(NprCli, BadInputsFailWithOneLineAndNoOutput) {
    ASSERT_TRUE(save_image(testing::halftone_pattern(16, 8), path("tiny.png")).is_ok());
    std::vector<std::string> args = npr({});
    args[2] = path("tiny.png");
    const CliRun small = run(args);
    EXPECT_EQ(small.code, 1);
    EXPECT_NE(small.err.find("--pattern " + path("tiny.png") +
                             ": pattern: 16x16 is too small (needs at least 48x48"),
              std::string::npos)
        << small.err;
    EXPECT_EQ(std::count(small.err.begin(), small.err.end(), '\n'), 1) << small.err;
    const CliRun style = run(npr({"--style", "crosshatch"}));
    EXPECT_EQ(style.code, 1);
    EXPECT_NE(style.err.find("--style: 'crosshatch' is invalid"), std::string::npos) << style.err;
    const CliRun levels = run(npr({"--levels", "9"}));
    EXPECT_EQ(levels.code, 1);
    EXPECT_NE(levels.err.find("levels: 9 is invalid"), std::string::npos) << levels.err;
    EXPECT_FALSE(fs::exists(path("O/0000.png")));
}

}  // namespace
}  // namespace exemplar::npr
