// `exemplar fluid` and `exemplar fluid simulate` through run_cli, in a temporary folder: the
// files written, resume, the job file, and one-line errors with exit code 1 and no output frame.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "cli_fixture.hpp"
#include "exemplar/io/flow_io.hpp"
#include "exemplar/io/image_io.hpp"
#include "fluid_scene.hpp"
#include "temp_dir.hpp"

namespace exemplar::fluid {
namespace {

namespace fs = std::filesystem;
using cli::testing::CliRun;
using cli::testing::file_bytes;
using cli::testing::run;

// A temporary folder with a 6-frame 48x48 plume (sim/alpha, sim/motion) and a 28x28 exemplar.
class FluidCli : public exemplar::testing::TempDirTest {
protected:
    void SetUp() override {
        TempDirTest::SetUp();
        const CliRun sim = run({"fluid", "simulate", "--scene", "plume", "--width", "48",
                                "--height", "48", "--frames", "6", "-o", path("sim"), "-q"});
        ASSERT_EQ(sim.code, 0) << sim.err;
        ASSERT_TRUE(save_image(test::fire_exemplar(28), path("fire.png")).is_ok());
    }

    std::vector<std::string> args(const std::string& output = "out/%04d.png") const {
        return {"fluid",
                "--exemplar",
                path("fire.png"),
                "--alpha",
                path("sim/alpha/%04d.png"),
                "--motion",
                path("sim/motion/%04d.flo"),
                "--first",
                "0",
                "--last",
                "5",
                "--output",
                path(output),
                "--blur-radius",
                "1.5",
                "-j",
                "2",
                "-q"};
    }
    // The run with `flag value` added fails with `message` (one line, exit 1) and writes no
    // frame.
    void expect_bad_option(const char* flag, const char* value, const std::string& message) const {
        std::vector<std::string> a = args();
        a.insert(a.end(), {flag, value});
        const CliRun r = run(a);
        EXPECT_EQ(r.code, 1);
        EXPECT_EQ(r.err, "exemplar: " + message + "\n");
        EXPECT_FALSE(fs::exists(path("out")));
    }
    std::vector<std::string> frames(const std::string& folder) const {
        std::vector<std::string> out;
        for (int n = 0; n <= 5; ++n) {
            char name[32];
            std::snprintf(name, sizeof name, "/%04d.png", n);
            out.push_back(file_bytes(path(folder) + name));
        }
        return out;
    }
};

TEST_F(FluidCli, SimulateWritesAlphaAndMotionPerFrame) {
    for (int n = 0; n < 6; ++n) {
        char name[32];
        std::snprintf(name, sizeof name, "%04d", n);
        auto alpha = load_image(path("sim/alpha/") + name + ".png");
        ASSERT_TRUE(alpha.ok()) << alpha.status().message();
        EXPECT_EQ(alpha->width(), 48);
        EXPECT_EQ(alpha->channels(), 1);
        auto motion = load_flo(path("sim/motion/") + name + ".flo");
        ASSERT_TRUE(motion.ok()) << motion.status().message();
        EXPECT_EQ(motion->width(), 48);
        EXPECT_EQ(motion->channels(), 2);
    }
    EXPECT_FALSE(fs::exists(path("sim/alpha/0006.png")));
}

TEST_F(FluidCli, SimulateReadsASceneFile) {
    std::ofstream(path("scene.json")) << R"({"width": 40, "height": 32, "buoyancy": 0.05,
        "emitters": [{"position": [20, 26], "radius": 4, "rate": 0.5, "velocity": [0, -1]}],
        "obstacles": [{"position": [20, 10], "radius": 4}]})";
    const CliRun ok = run({"fluid", "simulate", "--scene", path("scene.json"), "--frames", "3",
                           "-o", path("scene_out"), "-q"});
    ASSERT_EQ(ok.code, 0) << ok.err;
    auto alpha = load_image(path("scene_out/alpha/0002.png"));
    ASSERT_TRUE(alpha.ok());
    EXPECT_EQ(alpha->width(), 40);
    EXPECT_EQ(alpha->height(), 32);
    EXPECT_GT(alpha->at(20, 26, 0), 0.3f);  // the emitter

    std::ofstream(path("bad.json")) << R"({"emitters": [{"position": [1, 2], "radiuss": 3}]})";
    const CliRun bad = run({"fluid", "simulate", "--scene", path("bad.json"), "--frames", "3", "-o",
                            path("bad_out"), "-q"});
    EXPECT_EQ(bad.code, 1);
    EXPECT_EQ(bad.err, "exemplar: " + path("bad.json") + ": unknown key 'emitters[0].radiuss'\n");
    EXPECT_FALSE(fs::exists(path("bad_out")));
}

TEST_F(FluidCli, WritesRgbaFramesAndResumesToTheSameBytes) {
    const CliRun first = run(args());
    ASSERT_EQ(first.code, 0) << first.err;
    const std::vector<std::string> all = frames("out");
    for (int n = 0; n <= 5; ++n) {
        auto image = load_image(path("out/000") + std::to_string(n) + ".png");
        ASSERT_TRUE(image.ok());
        EXPECT_EQ(image->channels(), 4);
        EXPECT_EQ(image->width(), 48);
    }
    // Interrupted after frame 2: frames 3-5 are redone from frame 2's file.
    for (int n = 3; n <= 5; ++n) fs::remove(path("out/000") + std::to_string(n) + ".png");
    const auto untouched = fs::last_write_time(path("out/0001.png"));
    const CliRun again = run(args());
    ASSERT_EQ(again.code, 0) << again.err;
    EXPECT_EQ(frames("out"), all);
    EXPECT_EQ(fs::last_write_time(path("out/0001.png")), untouched);
}

TEST_F(FluidCli, WritesAnMp4OfTheRange) {
    std::vector<std::string> a = args();
    a.insert(a.end(), {"--mp4", path("movie/plume.mp4")});
    const CliRun r = run(a);
    ASSERT_EQ(r.code, 0) << r.err;
    ASSERT_TRUE(fs::exists(path("movie/plume.mp4")));
    EXPECT_GT(fs::file_size(path("movie/plume.mp4")), 1000u);
    EXPECT_TRUE(fs::exists(path("out/0005.png")));
}

TEST_F(FluidCli, JobFileGivesTheSameFramesAsFlags) {
    ASSERT_EQ(run(args()).code, 0);
    std::ofstream(path("job.json")) << R"({"exemplar": "fire.png", "alpha": "sim/alpha/%04d.png",
        "motion": "sim/motion/%04d.flo", "first": 0, "last": 5, "output": "job/%04d.png",
        "blur-radius": 1.5, "temporal-weight": 0.2, "seed": 1})";
    const CliRun job = run({"fluid", "--config", path("job.json"), "-j", "1", "-q"});
    ASSERT_EQ(job.code, 0) << job.err;
    EXPECT_EQ(frames("job"), frames("out"));

    std::ofstream(path("typo.json")) << R"({"exemplar": "fire.png", "tempral-weight": 1})";
    const CliRun typo = run({"fluid", "--config", path("typo.json"), "-q"});
    EXPECT_EQ(typo.code, 1);
    EXPECT_EQ(typo.err, "exemplar: " + path("typo.json") + ": unknown key 'tempral-weight'\n");
}

// examples/fluid/job.json with the bundled ink exemplar (README of examples/fluid), its
// simulation paths and range overridden by flags: the output is RGBA ink where the plume is and
// clear where it is not.
TEST_F(FluidCli, BundledInkExampleRunsOnAPlume) {
    const std::string job = std::string(EXEMPLAR_SOURCE_DIR) + "/examples/fluid/job.json";
    // The fixture's flags with the job file in place of the exemplar (flags override the job).
    std::vector<std::string> flags = args("ink/%04d.png");
    flags[1] = "--config";
    flags[2] = job;
    flags.insert(flags.end(), {"--mp4", ""});
    const CliRun r = run(flags);
    ASSERT_EQ(r.code, 0) << r.err;
    const Result<Image> out = load_image(path("ink/0005.png"));
    const Result<Image> target = load_image(path("sim/alpha/0005.png"));
    ASSERT_TRUE(out.ok() && target.ok());
    ASSERT_EQ(out->channels(), 4);
    double inside = 0, outside = 0;
    int inside_n = 0, outside_n = 0;
    for (int y = 0; y < target->height(); ++y) {
        for (int x = 0; x < target->width(); ++x) {
            const float t = target->at(x, y, 0), a = out->at(x, y, 3);
            if (t >= 0.5f) {
                inside += a;
                ++inside_n;
            } else if (t == 0.0f) {
                outside += a;
                ++outside_n;
            }
        }
    }
    ASSERT_GT(inside_n, 20);
    ASSERT_GT(outside_n, 500);
    std::printf("mean alpha inside the plume %.3f, outside %.4f\n", inside / inside_n,
                outside / outside_n);
    EXPECT_GT(inside / inside_n, 0.3);
    EXPECT_LT(outside / outside_n, 0.02);
}

TEST_F(FluidCli, MissingAlphaFrameFailsBeforeAnyOutput) {
    fs::remove(path("sim/alpha/0004.png"));
    const CliRun r = run(args());
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: " + path("sim/alpha/0004.png") +
                         ": no such file (alpha of frame 4 of 0..5)\n");
    EXPECT_FALSE(fs::exists(path("out")));
}

TEST_F(FluidCli, MotionOfTheWrongSizeNamesTheFileAndWritesNoFrame) {
    ASSERT_TRUE(
        save_flo(test::uniform_motion(40, 48, 1.0f, 0.0f), path("sim/motion/0000.flo")).is_ok());
    const CliRun r = run(args());
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: " + path("sim/motion/0000.flo") +
                         ": motion is 40x48 but the alpha masks are 48x48\n");
    // Frame 0 needs no motion and was written; frame 1 (which needs motion 0) was not.
    EXPECT_TRUE(fs::exists(path("out/0000.png")));
    EXPECT_FALSE(fs::exists(path("out/0001.png")));
}

TEST_F(FluidCli, ExemplarWithoutAlphaNeedsExemplarAlpha) {
    const Image rgba = test::fire_exemplar(28);
    ASSERT_TRUE(save_image(extract_channels(rgba, 0, 3), path("fire_rgb.png")).is_ok());
    ASSERT_TRUE(save_image(extract_channels(rgba, 3, 1), path("fire_alpha.png")).is_ok());
    std::vector<std::string> a = args("rgb/%04d.png");
    a[2] = path("fire_rgb.png");
    const CliRun r = run(a);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: " + path("fire_rgb.png") +
                         ": the exemplar has 3 channels but needs an alpha channel (RGBA), or "
                         "give exemplar-alpha\n");
    EXPECT_FALSE(fs::exists(path("rgb")));

    a.insert(a.end(), {"--exemplar-alpha", path("fire_alpha.png")});
    const CliRun ok = run(a);
    ASSERT_EQ(ok.code, 0) << ok.err;
    ASSERT_EQ(run(args()).code, 0);
    EXPECT_EQ(frames("rgb"), frames("out"));  // the same exemplar, given in two files
}

TEST_F(FluidCli, BadOptionIsOneLine) {
    expect_bad_option("--boundary-high", "0.05",
                      "boundary-high: 0.05 is invalid (must be above boundary-low 0.1)");
}

// The vote's weights are flags of the option table: out of range is one line, and 0 for both
// (the paper's plain vote) gives other frames than the default.
TEST_F(FluidCli, VoteWeightsAreFlags) {
    expect_bad_option("--vote-coherence", "-1", "vote-coherence: -1 is invalid (must be 0..100)");

    std::vector<std::string> paper = args("paper/%04d.png");
    paper.insert(paper.end(), {"--vote-coherence", "0", "--vote-histogram", "0"});
    ASSERT_EQ(run(paper).code, 0);
    ASSERT_EQ(run(args()).code, 0);
    EXPECT_NE(frames("paper"), frames("out"));
}

// The assignment's coherence sweeps are a flag of the option table too: an integer in range, and
// 0 (the paper's placement) gives other frames than the default.
TEST_F(FluidCli, CoherenceSweepsAreAFlag) {
    expect_bad_option("--coherence-sweeps", "1.5",
                      "coherence-sweeps: 1.5 is invalid (must be an integer 0..100)");
    expect_bad_option("--coherence-sweeps", "101",
                      "coherence-sweeps: 101 is invalid (must be an integer 0..100)");

    std::vector<std::string> scattered = args("scattered/%04d.png");
    scattered.insert(scattered.end(), {"--coherence-sweeps", "0"});
    ASSERT_EQ(run(scattered).code, 0);
    ASSERT_EQ(run(args()).code, 0);
    EXPECT_NE(frames("scattered"), frames("out"));
}

}  // namespace
}  // namespace exemplar::fluid
