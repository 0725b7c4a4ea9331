// `exemplar render` run in-process: a tiny end-to-end render, output formats, error lines.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli.hpp"
#include "exemplar/io/flow_io.hpp"
#include "exemplar/io/image_io.hpp"
#include "temp_dir.hpp"

namespace exemplar::cli {
namespace {

namespace fs = std::filesystem;

struct CliResult {
    int code;
    std::string out, err;
};

CliResult run(std::vector<std::string> args) {
    args.insert(args.begin(), "exemplar");
    std::vector<const char*> argv;
    for (const auto& a : args) argv.push_back(a.c_str());
    std::ostringstream out, err;
    const int code = run_cli(static_cast<int>(argv.size()), argv.data(), out, err);
    return {code, out.str(), err.str()};
}

class RenderCli : public exemplar::testing::TempDirTest {
protected:
    static std::vector<std::string> tiny(std::vector<std::string> more) {
        std::vector<std::string> args = {
            "render", "--scene", "sphere-on-table", "--width", "24", "--height", "18",
            "--spp",  "2",       "--threads",       "2"};
        args.insert(args.end(), more.begin(), more.end());
        return args;
    }

    void expect_failure(const std::vector<std::string>& args, int code, const std::string& part) {
        const CliResult r = run(args);
        EXPECT_EQ(r.code, code) << r.err;
        EXPECT_EQ(r.err.rfind("exemplar: ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(part), std::string::npos) << "expected '" << part << "' in " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_TRUE(fs::is_empty(dir_)) << "a failed run wrote a file";
    }
};

TEST_F(RenderCli, WritesOneMultiLayerExrWithNamedLayers) {
    const CliResult r = run(tiny({"--output", path("out.exr")}));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, path("out.exr") + "\n");
    auto layers = read_layer_names(path("out.exr"));
    ASSERT_TRUE(layers.ok()) << layers.status().message();
    const std::vector<std::string> expected = {"fullgi",
                                               "direct_diffuse",
                                               "direct_specular",
                                               "indirect_diffuse",
                                               "diffuse_bounces",
                                               "diffuse_interreflection",
                                               "normal",
                                               "depth",
                                               "object_id",
                                               "material_id",
                                               "alpha"};
    for (const auto& name : expected) {
        EXPECT_NE(std::find(layers->begin(), layers->end(), name), layers->end()) << name;
    }
    auto fullgi = load_image_layer(path("out.exr"), "fullgi");
    ASSERT_TRUE(fullgi.ok());
    EXPECT_EQ(fullgi->width(), 24);
    EXPECT_EQ(fullgi->channels(), 3);
}

TEST_F(RenderCli, WritesAFolderOfPngsOrExrs) {
    ASSERT_EQ(run(tiny({"--output", path("png"), "--quiet"})).code, 0);
    for (const char* name : {"fullgi", "direct_diffuse", "direct_specular", "indirect_diffuse",
                             "normal", "depth", "object_id", "alpha"}) {
        EXPECT_TRUE(fs::exists(path("png") + "/" + name + ".png")) << name;
    }
    ASSERT_EQ(run(tiny({"--output", path("exr"), "--format", "exr", "-q"})).code, 0);
    auto depth = load_image(path("exr") + "/depth.exr");
    ASSERT_TRUE(depth.ok());
    EXPECT_GT(depth->at(12, 9, 0), 1.0f);  // linear distances, not normalized
}

TEST_F(RenderCli, SceneFilesRenderAndTheirErrorsNameFileAndKey) {
    const fs::path bad =
        fs::temp_directory_path() / ("exemplar_bad_" + std::to_string(::getpid()) + ".json");
    std::ofstream(bad) << R"({"camera": {"position": [0, 1, 5], "look_at": [0, 1, 0], "zoom": 2}})";
    expect_failure({"render", "--scene", bad.string(), "-o", path("out.exr")}, 1,
                   bad.string() + ": camera.zoom: unknown key");
    fs::remove(bad);
    expect_failure({"render", "--scene", path("missing.json"), "-o", path("out.exr")}, 1,
                   "missing.json: no such file");
    expect_failure({"render", "--scene", "cube-on-table", "-o", path("out.exr")}, 1,
                   "--scene: scene \"cube-on-table\" is not a built-in scene");
}

TEST_F(RenderCli, BadParametersAreNamed) {
    const std::vector<std::string> base = {"render", "--scene", "sphere-on-table", "-o",
                                           path("out.exr")};
    const auto with = [&](std::vector<std::string> more) {
        more.insert(more.begin(), base.begin(), base.end());
        return more;
    };
    expect_failure(with({"--spp", "0"}), 1, "--spp: 0 is invalid");
    expect_failure(with({"--width", "0"}), 1, "--width: 0 is invalid");
    expect_failure(with({"--max-bounces", "99"}), 1, "--max-bounces: 99 is invalid");
    expect_failure(with({"--threads", "-1"}), 1, "--threads: -1");
    expect_failure(tiny({"--format", "tga", "-o", path("out")}), 1, "--format: \"tga\"");
    {
        // A file where the output's folder would go (missing folders are created otherwise).
        std::ofstream(path("blocker")) << "x";
        const CliResult r = run(tiny({"-o", path("blocker/out.exr")}));
        EXPECT_EQ(r.code, 1) << r.err;
        EXPECT_NE(r.err.find("blocker is a file, not a folder"), std::string::npos) << r.err;
        fs::remove(path("blocker"));
    }
    expect_failure({"render", "-o", path("out.exr")}, 2, "--scene is required");
    expect_failure(with({"--spp", "many"}), 2, "--spp");
}

// A small animated scene file (outside the output folder, which failed runs must leave empty).
class AnimationCli : public RenderCli {
protected:
    void SetUp() override {
        RenderCli::SetUp();
        scene_ = fs::temp_directory_path() /
                 ("exemplar_anim_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".json");
        write_scene(R"("frames": [0, 3],)");
    }
    void TearDown() override {
        fs::remove(scene_);
        RenderCli::TearDown();
    }
    void write_scene(const std::string& extra) const {
        std::ofstream(scene_) << "{" << extra << R"(
            "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov_deg": 40},
            "sky": [0.2, 0.2, 0.2],
            "materials": [{"name": "m"}],
            "objects": [{"shape": "sphere", "material": "m", "subdivisions": 16,
                         "keyframes": [{"frame": 0, "translate": [0, 0, 0]},
                                       {"frame": 10, "translate": [1, 0, 0]}]}]})";
    }
    std::vector<std::string> anim(std::vector<std::string> more) const {
        std::vector<std::string> args = {"render",   "--scene", scene_.string(), "--width", "32",
                                         "--height", "24",      "--spp",         "1",       "-j",
                                         "2"};
        args.insert(args.end(), more.begin(), more.end());
        return args;
    }
    fs::path scene_;
};

TEST_F(AnimationCli, FramesGoToAPatternWithFlowLayersThatLoadFlowReads) {
    // The pattern's folders do not exist yet: they are created.
    const CliResult r = run(anim({"--frames", "1-2", "-o", path("shots/a/f_%03d.exr")}));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, path("shots/a/f_001.exr") + "\n" + path("shots/a/f_002.exr") + "\n");
    EXPECT_FALSE(fs::exists(path("shots/a/f_000.exr")));
    auto layers = read_layer_names(path("shots/a/f_002.exr"));
    ASSERT_TRUE(layers.ok()) << layers.status().message();
    for (const char* name : {"fullgi", "orientation", "lines", "forward_flow", "backward_flow",
                             "occlusion", "disocclusion"}) {
        EXPECT_NE(std::find(layers->begin(), layers->end(), name), layers->end()) << name;
    }
    auto forward = load_flow(path("shots/a/f_001.exr"), "forward_flow");
    auto backward = load_flow(path("shots/a/f_001.exr"), "backward_flow");
    ASSERT_TRUE(forward.ok()) << forward.status().message();
    ASSERT_TRUE(backward.ok()) << backward.status().message();
    ASSERT_EQ(forward->width(), 32);
    // The sphere moves right by 0.1 per frame at constant depth: the same step forward and
    // backward.
    EXPECT_GT(forward->at(16, 12, 0), 0.5f);
    EXPECT_NEAR(forward->at(16, 12, 0), -backward->at(16, 12, 0), 1e-3f);
    EXPECT_EQ(forward->at(0, 0, 0), 0.0f);  // the sky of a still camera
}

TEST_F(AnimationCli, OneFrameToAFolderWritesFlowsAsExrAndMasksAsPng) {
    ASSERT_EQ(run(anim({"--frame", "2", "-o", path("new/frame"), "-q"})).code, 0);
    for (const char* name : {"forward_flow.exr", "backward_flow.exr", "orientation.exr",
                             "occlusion.png", "disocclusion.png", "lines.png", "fullgi.png"}) {
        EXPECT_TRUE(fs::exists(path("new/frame") + "/" + name)) << name;
    }
    EXPECT_TRUE(load_flow(path("new/frame") + "/forward_flow.exr").ok());
    // The scene's own range (0-3) when no --frames is given.
    ASSERT_EQ(run(anim({"-o", path("all_%d"), "-q"})).code, 0);
    for (int f = 0; f <= 3; ++f) EXPECT_TRUE(fs::is_directory(path("all_" + std::to_string(f))));
}

TEST_F(AnimationCli, BadFramesAndPatternsAreNamed) {
    expect_failure(anim({"--frames", "3-1", "-o", path("f_%d.exr")}), 1,
                   "--frames: \"3-1\" is invalid");
    expect_failure(anim({"--frames", "a", "-o", path("f_%d.exr")}), 1, "--frames: \"a\"");
    expect_failure(anim({"--frame", "-2", "-o", path("f.exr")}), 1, "--frame: \"-2\"");
    expect_failure(anim({"--frames", "1-2", "--frame", "1", "-o", path("f_%d.exr")}), 1,
                   "--frame: cannot be combined with --frames");
    expect_failure(anim({"--frames", "0-3", "-o", path("f.exr")}), 1,
                   "needs a frame number pattern");
    expect_failure(anim({"--frames", "0-3", "-o", path("f_%d_%d.exr")}), 1, "--output");
    expect_failure(tiny({"-o", path("still_%04d.exr")}), 1, "the scene is a still");
    write_scene("");
    expect_failure(anim({"-o", path("f_%d.exr")}), 1, "--frames: required");
}

}  // namespace
}  // namespace exemplar::cli
