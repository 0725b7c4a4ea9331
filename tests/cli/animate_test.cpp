// `exemplar animate`: job files, frame ranges with hand-over, resume, keyframes with alpha, and
// one-line errors.

#include <algorithm>
#include <fstream>

#include "cli_fixture.hpp"
#include "exemplar/io/flow_io.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/video/frame_sequence.hpp"
#include "synthetic_scene.hpp"

namespace exemplar::cli::testing {
namespace {

using animate::testing::Scene;

class AnimateCli : public Cli {
protected:
    void SetUp() override {
        Cli::SetUp();
        fs::create_directories(dir_ / "frames");
        fs::create_directories(dir_ / "flow");
        fs::create_directories(dir_ / "out");
        for (int t = 0; t < scene_.frames; ++t) {
            char name[32];
            std::snprintf(name, sizeof name, "frames/%02d.png", t);
            write(name, scene_.frame(t), {});
            if (t + 1 < scene_.frames) {
                const video::FlowPair m = scene_.motion(t);
                std::snprintf(name, sizeof name, "flow/f%02d.flo", t);
                ASSERT_TRUE(save_flo(m.forward, path(name)).is_ok());
                std::snprintf(name, sizeof name, "flow/b%02d.flo", t + 1);
                ASSERT_TRUE(save_flo(m.backward, path(name)).is_ok());
            }
        }
        const animate::testing::Style style = animate::testing::make_style();
        write("s_in.png", style.input);
        write("s_out.png", style.output);
    }
    // A job file with the given extra JSON members (each "key": value, comma-separated).
    std::string job(const std::string& extra = "", const std::string& name = "job.json") {
        std::ofstream f(path(name));
        f << R"({"frames": "frames/%02d.png", "first": 0, "last": )" << scene_.frames - 1
          << R"(, "flows": {"forward": "flow/f%02d.flo", "backward": "flow/b%02d.flo"},)"
          << R"( "style": {"input": "s_in.png", "output": "s_out.png"},)"
          << R"( "output": "out/%02d.png")" << (extra.empty() ? "" : ", " + extra) << "}";
        return path(name);
    }
    std::string out(int t) const {
        char name[32];
        std::snprintf(name, sizeof name, "out/%02d.png", t);
        return path(name);
    }
    double seam_error(const Image& previous, const Image& current, int t) const {
        const video::FlowPair m = scene_.motion(t - 1);
        return animate::testing::warp_error(previous, current, m.backward, m.forward);
    }

    Scene scene_;
};

// A folder of frames: "first"/"last" narrow the job to part of it (they were ignored once, and
// every frame was solved); numbers outside the folder's frames are an error naming them.
TEST_F(AnimateCli, FolderFramesHonourFirstAndLast) {
    std::ofstream(path("folder.json"))
        << R"({"frames": "frames", "first": 1, "last": 2,)"
        << R"( "flows": {"forward": "flow/f%02d.flo", "backward": "flow/b%02d.flo"},)"
        << R"( "style": {"input": "s_in.png", "output": "s_out.png"}, "output": "out/%02d.png"})";
    CliRun r = run({"animate", path("folder.json"), "-j", "2"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, path("out/%02d.png") + " (2 frames)\n");
    EXPECT_FALSE(fs::exists(out(0)));
    EXPECT_TRUE(fs::exists(out(1)) && fs::exists(out(2)));
    EXPECT_FALSE(fs::exists(out(3)));
    std::ofstream(path("beyond.json"))
        << R"({"frames": "frames", "last": 99,)"
        << R"( "style": {"input": "s_in.png", "output": "s_out.png"}, "output": "out/%02d.png"})";
    r = run({"animate", path("beyond.json"), "-q"});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("first/last 0..99 is invalid (it has frames 0.." +
                         std::to_string(scene_.frames - 1) + ")"),
              std::string::npos)
        << r.err;
}

TEST_F(AnimateCli, RangesHandOverAndResumeSkipsFinishedFrames) {
    const std::string j = job();
    CliRun r = run({"animate", j, "--frames", "0-3", "-j", "2"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, path("out/%02d.png") + " (4 frames)\n");
    for (int t = 0; t < 4; ++t) EXPECT_TRUE(fs::exists(out(t)));
    EXPECT_FALSE(fs::exists(out(4)));
    const std::string frame3 = file_bytes(out(3));

    // The next range starts from frame 3's output (hand-over) and leaves it as it is.
    r = run({"animate", j, "--frames", "4-7", "-q"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(file_bytes(out(3)), frame3);
    const double handed = seam_error(read("out/03.png"), read("out/04.png"), 4);

    // Without the hand-over (frame 3 absent) frame 4 does not continue frame 3.
    fs::create_directories(dir_ / "alone");
    r = run({"animate", j, "--frames", "4-7", "-q", "-o", path("alone/%02d.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const double alone = seam_error(read("out/03.png"), read("alone/04.png"), 4);
    EXPECT_LT(handed, 0.2 * alone) << handed << " vs " << alone;

    // Resume: nothing left to do; a deleted frame is redone alone, the others untouched.
    const std::string frame6 = file_bytes(out(6));
    r = run({"animate", j});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("every frame of the range exists"), std::string::npos);
    fs::remove(out(5));
    r = run({"animate", j, "-q"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(out(5)));
    EXPECT_EQ(file_bytes(out(6)), frame6);
    EXPECT_EQ(file_bytes(out(3)), frame3);
}

// The quality dial: --quality fast equals "quality": "fast" in the job, and changes the frames;
// an explicit engine option in the job stays over the flag's preset.
TEST_F(AnimateCli, QualityFlagAndJobKeyAgree) {
    ASSERT_EQ(run({"animate", job(), "--frames", "0-1", "-q", "-o", path("d/%02d.png")}).code, 0);
    ASSERT_EQ(run({"animate", job(), "--frames", "0-1", "-q", "--quality", "fast", "-o",
                   path("f/%02d.png")})
                  .code,
              0);
    ASSERT_EQ(run({"animate", job(R"("quality": "fast")"), "--frames", "0-1", "-q", "-o",
                   path("k/%02d.png")})
                  .code,
              0);
    EXPECT_EQ(file_bytes(path("f/01.png")), file_bytes(path("k/01.png")));
    EXPECT_NE(file_bytes(path("f/01.png")), file_bytes(path("d/01.png")));
    // The job's em-iterations 3 (the default's) over the flag's fast preset: only the other
    // fast knobs apply, so the frames differ from both.
    ASSERT_EQ(run({"animate", job(R"("em-iterations": 3)"), "--frames", "0-1", "-q", "--quality",
                   "fast", "-o", path("e/%02d.png")})
                  .code,
              0);
    EXPECT_NE(file_bytes(path("e/01.png")), file_bytes(path("f/01.png")));
}

TEST_F(AnimateCli, NoResumeIgnoresStaleOutputsAndChunksAreDeterministic) {
    const std::string j = job();
    ASSERT_EQ(run({"animate", j, "--chunk", "4", "-q"}).code, 0);
    // Redo everything with another seed over the old outputs: no old frame may be handed over,
    // so the result equals a fresh run in an empty folder.
    ASSERT_EQ(run({"animate", j, "--chunk", "4", "-q", "--no-resume", "--seed", "2"}).code, 0);
    fs::create_directories(dir_ / "fresh");
    ASSERT_EQ(
        run({"animate", j, "--chunk", "4", "-q", "--seed", "2", "-o", path("fresh/%02d.png")}).code,
        0);
    for (int t = 0; t < scene_.frames; ++t) {
        char name[32];
        std::snprintf(name, sizeof name, "fresh/%02d.png", t);
        EXPECT_EQ(file_bytes(out(t)), file_bytes(path(name))) << "frame " << t;
    }
    // The second chunk continues the first: the seam is as coherent as the frames inside.
    const double seam = seam_error(read("fresh/03.png"), read("fresh/04.png"), 4);
    const double inside = seam_error(read("fresh/02.png"), read("fresh/03.png"), 3);
    EXPECT_LT(seam, 3.0 * inside + 1e-4) << seam << " vs " << inside;
}

TEST_F(AnimateCli, VideoFramesAndMp4Output) {
    auto writer = video::Mp4Writer::open(path("clip.mp4"), scene_.width, scene_.height, 12.0);
    ASSERT_TRUE(writer.ok()) << writer.status().message();
    for (int t = 0; t < scene_.frames; ++t) ASSERT_TRUE(writer->write(scene_.frame(t)).is_ok());
    ASSERT_TRUE(writer->finish().is_ok());
    // Decoded video frames are RGB: give the style input three channels too.
    const Image grey = read("s_in.png");
    write("s_in_rgb.png", concat_channels({&grey, &grey, &grey}));
    std::ofstream(path("video.json"))
        << R"({"frames": "clip.mp4", "style": {"input": "s_in_rgb.png", "output": "s_out.png"},)"
        << R"( "output": "out/%02d.png", "mp4": "out/result.mp4", "fps": 12})";
    const CliRun r = run({"animate", path("video.json"), "-q"});
    ASSERT_EQ(r.code, 0) << r.err;
    for (int t = 0; t < scene_.frames; ++t) EXPECT_TRUE(fs::exists(out(t)));
    auto result = video::FrameSequence::from_video(path("out/result.mp4"));
    ASSERT_TRUE(result.ok()) << result.status().message();
    EXPECT_EQ(result->size(), scene_.frames);
}

TEST_F(AnimateCli, RgbaKeyframeIsAPartialHardConstraint) {
    Image key(scene_.width, scene_.height, 4, 0.0f);
    for (int y = 0; y < scene_.height; ++y) {
        for (int x = 0; x < scene_.width; ++x) {
            if (!scene_.in_square(x, y, 2)) continue;
            key.at(x, y, 1) = 0.8f;
            key.at(x, y, 3) = 1.0f;
        }
    }
    write("key2.png", key);
    const CliRun r = run({"animate", job(R"("keyframes": [{"frame": 2, "image": "key2.png"}])"),
                          "-q", "--frames", "0-3"});
    ASSERT_EQ(r.code, 0) << r.err;
    const Image o = read("out/02.png");
    int green = 0;
    for (int y = 0; y < scene_.height; ++y) {
        for (int x = 0; x < scene_.width; ++x) {
            if (!scene_.in_square(x, y, 2)) continue;
            green += o.at(x, y, 0) == 0.0f && std::abs(o.at(x, y, 1) - 0.8f) < 0.003f &&
                     o.at(x, y, 2) == 0.0f;
        }
    }
    EXPECT_EQ(green, scene_.square * scene_.square);
}

TEST_F(AnimateCli, LineDrawingsFeedTheLineTerm) {
    // The frames themselves serve as line drawings (their dark background is "line").
    const CliRun r = run({"animate",
                          job(R"("lines": {"style": "s_in.png", "frames": "frames/%02d.png"},)"
                              R"( "weights": {"lines": 2}, "line-max-distance": 6)"),
                          "-q", "--frames", "0-2"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(out(2)));
}

TEST_F(AnimateCli, LayersAreSolvedApartAndComposited) {
    fs::create_directories(dir_ / "bg");
    fs::create_directories(dir_ / "mask");
    Scene empty = scene_;
    empty.square = 0;
    for (int t = 0; t < scene_.frames; ++t) {
        char name[32];
        std::snprintf(name, sizeof name, "bg/%02d.png", t);
        write(name, empty.frame(t));
        Image m(scene_.width, scene_.height, 1, 0.0f);
        for (int y = 0; y < scene_.height; ++y) {
            for (int x = 0; x < scene_.width; ++x) m.at(x, y, 0) = scene_.in_square(x, y, t);
        }
        std::snprintf(name, sizeof name, "mask/%02d.png", t);
        write(name, m);
    }
    const std::string j = job(R"("layers": [{"frames": "bg/%02d.png", "flows": "estimate"},)"
                              R"( {"frames": "frames/%02d.png", "coverage": "mask/%02d.png"}])");
    CliRun r = run({"animate", j, "-q", "--frames", "0-3"});
    ASSERT_EQ(r.code, 0) << r.err;
    for (int t = 0; t < 4; ++t) {
        char name[32];
        std::snprintf(name, sizeof name, "out/%02d.layer1.png", t);
        ASSERT_TRUE(fs::exists(path(name))) << name;
    }
    const Image composite = read("out/02.png"), back = read("out/02.layer0.png"),
                front = read("out/02.layer1.png");
    for (int y = 0; y < scene_.height; ++y) {
        for (int x = 0; x < scene_.width; ++x) {
            const Image& want = scene_.in_square(x, y, 2) ? front : back;
            for (int c = 0; c < 3; ++c) ASSERT_EQ(composite.at(x, y, c), want.at(x, y, c));
        }
    }
    // The next range hands each layer its own frame 3 over.
    r = run({"animate", j, "-q", "--frames", "4-5"});
    ASSERT_EQ(r.code, 0) << r.err;
    const double seam = seam_error(read("out/03.png"), read("out/04.png"), 4);
    EXPECT_LT(seam, 0.001) << seam;

    expect_failure_as_is({"animate", job(R"("layers": [{}, {"frames": "frames/%02d.png"}])")}, 1,
                         path("job.json") + ": layer 1: key 'coverage' is missing");
    expect_failure_as_is({"animate", job(R"("layers": [{"colour": 1}])")}, 1,
                         path("job.json") + ": unknown key 'layers.colour'");
}

// One multi-layer EXR per frame holding both directions (as `exemplar render --frames` writes
// them): flows.forward_layer / backward_layer pick a layer each; the result equals the same
// flows given as .flo files.
TEST_F(AnimateCli, FlowsFromLayersOfOneExrPerFrame) {
    for (int t = 0; t < scene_.frames; ++t) {
        Image forward(scene_.width, scene_.height, 2), backward(scene_.width, scene_.height, 2);
        if (t + 1 < scene_.frames) forward = scene_.motion(t).forward;
        if (t > 0) backward = scene_.motion(t - 1).backward;
        forward.set_channel_names({"u", "v"});
        backward.set_channel_names({"u", "v"});
        char name[32];
        std::snprintf(name, sizeof name, "flow/m%02d.exr", t);
        ASSERT_TRUE(
            save_exr_layers({{"forward_flow", &forward}, {"backward_flow", &backward}}, path(name))
                .is_ok());
    }
    CliRun r = run({"animate", job(), "--frames", "0-2", "-q"});
    ASSERT_EQ(r.code, 0) << r.err;
    const Image from_flo = read("out/02.png");
    fs::remove_all(dir_ / "out");
    fs::create_directories(dir_ / "out");
    std::ofstream(path("layers.json"))
        << R"({"frames": "frames/%02d.png", "first": 0, "last": )" << scene_.frames - 1
        << R"(, "flows": {"forward": "flow/m%02d.exr", "backward": "flow/m%02d.exr",)"
        << R"( "forward_layer": "forward_flow", "backward_layer": "backward_flow"},)"
        << R"( "style": {"input": "s_in.png", "output": "s_out.png"}, "output": "out/%02d.png"})";
    r = run({"animate", path("layers.json"), "--frames", "0-2", "-q"});
    ASSERT_EQ(r.code, 0) << r.err;
    const Image from_layers = read("out/02.png");
    ASSERT_TRUE(from_layers.same_size(from_flo));
    EXPECT_TRUE(
        std::equal(from_layers.data().begin(), from_layers.data().end(), from_flo.data().begin()));
}

// A range reads only its own frames and the hand-over neighbours: the others may be missing.
TEST_F(AnimateCli, RangeNeedsOnlyTheFramesItReads) {
    for (int t : {0, 1, 6, 7}) {
        char name[32];
        std::snprintf(name, sizeof name, "frames/%02d.png", t);
        fs::remove(path(name));
    }
    // A keyframe outside the range (its file missing too) is not read either. (The keyframe
    // terms' keys are accepted.)
    const std::string j =
        job(R"("keyframes": [{"frame": 7, "image": "gone.png"}], "ribbons": false,)"
            R"( "weights": {"input_derivative": 1})");
    CliRun r = run({"animate", j, "--frames", "2-3", "-q"});
    ASSERT_EQ(r.code, 0) << r.err;
    r = run({"animate", j, "--frames", "4-5", "-q"});  // hands over from frame 3
    ASSERT_EQ(r.code, 0) << r.err;
    for (int t = 2; t <= 5; ++t) EXPECT_TRUE(fs::exists(out(t)));
    EXPECT_FALSE(fs::exists(out(1)));
    EXPECT_FALSE(fs::exists(out(6)));
    // The hand-over frame's input is needed: its absence is named.
    fs::remove(path("frames/03.png"));
    expect_failure_as_is({"animate", j, "--frames", "4-5", "--no-resume"}, 1,
                         path("frames/03.png") + ": no such file (frame 3 of 0..7)");
    expect_failure_as_is({"animate", j, "--frames", "6-6"}, 1,
                         path("frames/06.png") + ": no such file (frame 6 of 0..7)");
}

TEST_F(AnimateCli, ErrorsAreOneLineAndNameTheProblem) {
    expect_failure_as_is({"animate", job(R"("framez": 3)")}, 1,
                         path("job.json") + ": unknown key 'framez'");
    expect_failure_as_is({"animate", job(R"("keyframes": [{"frame": 40, "image": "s_out.png"}])")},
                         1, path("job.json") + ": keyframe 40 is outside the frames 0..7");
    expect_failure_as_is({"animate", job(R"("lines": {"style": "s_in.png"})")}, 1,
                         path("job.json") + ": key 'lines' needs both \"style\" and \"frames\"");
    expect_failure_as_is({"animate", job(R"("weights": {"line": 2})")}, 1,
                         path("job.json") + ": unknown key 'weights.line'");
    expect_failure_as_is(
        {"animate", job(R"("quality": "superb")")}, 1,
        path("job.json") + ": quality: 'superb' is invalid (must be one of fast, default, best)");
    expect_failure_as_is(
        {"animate", job(), "--quality", "fine"}, 1,
        "exemplar: quality: 'fine' is invalid (must be one of fast, default, best)");
    expect_failure_as_is({"animate", job(R"("ribbons": 1)")}, 1,
                         path("job.json") + ": key 'ribbons' must be true or false");
    expect_failure_as_is({"animate", job(R"("weights": {"input-derivative": -1})")}, 1,
                         "input-derivative-weight: -1");
    expect_failure_as_is({"animate", job(), "--frames", "5-9"}, 1,
                         "--frames: 5-9 is outside the frames 0..7");
    fs::remove(path("frames/05.png"));
    expect_failure_as_is({"animate", job()}, 1, "frames/05.png: no such file");
    write("frames/05.png", scene_.frame(5));
    ASSERT_TRUE(save_flo(Image(10, 8, 2), path("flow/f02.flo")).is_ok());
    expect_failure_as_is({"animate", job(), "-q"}, 1,
                         "flow/f02.flo: flow is 10x8 but the frames are 64x48");
    std::ofstream(path("clip.mp4")) << "not a video";
    std::ofstream(path("video.json"))
        << R"({"frames": "clip.mp4", "style": {"input": "s_in.png", "output": "s_out.png"},)"
        << R"( "output": "out/%02d.png"})";
    expect_failure_as_is({"animate", path("video.json")}, 1, "clip.mp4");
}

// The output pattern's folders are created (animate -o shots/a/%02d.png on a fresh checkout); a
// file in the way is a one-line error before any frame is solved.
TEST_F(AnimateCli, OutputFoldersAreCreated) {
    const CliRun r =
        run({"animate", job(), "--frames", "0-1", "-q", "-o", path("shots/a/%02d.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(path("shots/a/00.png")));
    EXPECT_TRUE(fs::exists(path("shots/a/01.png")));
    std::ofstream(path("blocker")) << "x";
    expect_failure_as_is({"animate", job(), "--frames", "0-1", "-o", path("blocker/%02d.png")}, 1,
                         "output " + path("blocker/00.png") + ": cannot create folder \"" +
                             path("blocker") + "\": " + path("blocker") +
                             " is a file, not a folder");
}

}  // namespace
}  // namespace exemplar::cli::testing
