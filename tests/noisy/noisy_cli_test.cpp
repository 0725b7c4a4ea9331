// `exemplar noisy` run in-process: outputs, resume, thread independence, job files, errors.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "cli_fixture.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/video/frame_sequence.hpp"
#include "procedural.hpp"
#include "temp_dir.hpp"

namespace exemplar::noisy {
namespace {

namespace fs = std::filesystem;
using cli::testing::CliRun;
using cli::testing::file_bytes;

// `exemplar noisy ARGS...`, in-process.
CliRun run_noisy(std::vector<std::string> args) {
    args.insert(args.begin(), "noisy");
    return cli::testing::run(std::move(args));
}

class NoisyCli : public exemplar::testing::TempDirTest {
protected:
    void SetUp() override {
        TempDirTest::SetUp();
        fs::create_directories(dir_ / "R");
        ASSERT_TRUE(save_image(testing::medium(64, 64), (dir_ / "S.png").string()).ok());
        for (int n = 1; n <= 4; ++n) {
            const Image cel = testing::cel(32, 32, 12 + n, 14, 9);
            ASSERT_TRUE(save_image(cel, path("R/%04d.png", n)).ok());
        }
    }
    std::string path(const std::string& pattern, int n = -1) const {
        if (n < 0) return (dir_ / pattern).string();
        char name[64];
        std::snprintf(name, sizeof name, pattern.c_str(), n);
        return (dir_ / name).string();
    }
    // A quick run: small patches and few iterations keep the test fast.
    std::vector<std::string> args(const std::string& output, const std::string& threads) const {
        return {"--exemplar",
                path("S.png"),
                "--frames",
                path("R/%04d.png"),
                "--first",
                "1",
                "--last",
                "4",
                "--noise",
                "3",
                "--output",
                path(output),
                "--patch-size",
                "5",
                "--em-iterations",
                "2",
                "--search-iterations",
                "3",
                "-j",
                threads,
                "-q"};
    }
};

TEST_F(NoisyCli, WritesEveryFrameIdenticallyForAnyThreadCount) {
    const CliRun one = run_noisy(args("A/%04d.png", "1"));
    ASSERT_EQ(one.code, 0) << one.err;
    const CliRun two = run_noisy(args("B/%04d.png", "2"));
    ASSERT_EQ(two.code, 0) << two.err;
    for (int n = 1; n <= 4; ++n) {
        const std::string a = file_bytes(path("A/%04d.png", n)),
                          b = file_bytes(path("B/%04d.png", n));
        EXPECT_FALSE(a.empty());
        EXPECT_EQ(a, b) << "frame " << n;
    }
    EXPECT_NE(file_bytes(path("A/%04d.png", 1)), file_bytes(path("A/%04d.png", 2)));
}

TEST_F(NoisyCli, ResumesAndSplitsRangesWithoutChangingAFrame) {
    ASSERT_EQ(run_noisy(args("A/%04d.png", "2")).code, 0);
    // Frames 2..3 alone, into another folder: the same bytes as in the whole range.
    std::vector<std::string> part = args("B/%04d.png", "1");
    part[5] = "2";
    part[7] = "3";
    ASSERT_EQ(run_noisy(part).code, 0);
    EXPECT_EQ(file_bytes(path("B/%04d.png", 2)), file_bytes(path("A/%04d.png", 2)));
    EXPECT_FALSE(fs::exists(path("B/%04d.png", 1)));
    // Resume: an existing frame is kept as it is.
    { std::ofstream(path("A/%04d.png", 3), std::ios::binary) << "kept"; }
    std::vector<std::string> again = args("A/%04d.png", "2");
    again.pop_back();  // not quiet
    const CliRun resumed = run_noisy(again);
    ASSERT_EQ(resumed.code, 0) << resumed.err;
    EXPECT_EQ(file_bytes(path("A/%04d.png", 3)), "kept");
}

TEST_F(NoisyCli, ReadsAJobFileAndFlagsWin) {
    {
        std::ofstream job(path("job.json"));
        job << "{\"exemplar\": \"" << path("S.png") << "\", \"frames\": \"" << path("R/%04d.png")
            << "\", \"first\": 1, \"last\": 2, \"noise\": 3, \"output\": \"" << path("J/%04d.png")
            << "\", \"patch_size\": 5, \"em-iterations\": 2, \"search-iterations\": 3}";
    }
    const CliRun from_job = run_noisy({"--config", path("job.json"), "--last", "1", "-q"});
    ASSERT_EQ(from_job.code, 0) << from_job.err;
    EXPECT_TRUE(fs::exists(path("J/%04d.png", 1)));
    EXPECT_FALSE(fs::exists(path("J/%04d.png", 2)));
    {
        std::ofstream job(path("bad.json"));
        job << "{\"noise\": 3, \"colour\": 1}";
    }
    const CliRun bad = run_noisy({"--config", path("bad.json")});
    EXPECT_EQ(bad.code, 1);
    EXPECT_EQ(bad.err, "exemplar: " + path("bad.json") + ": unknown key 'colour'\n");
}

TEST_F(NoisyCli, BadInputsGiveOneLineErrors) {
    std::vector<std::string> a = args("E/%04d.png", "1");
    a[7] = "5";  // --last 5: R/0005.png is missing
    CliRun r = run_noisy(a);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: " + path("R/%04d.png", 5) + ": no such file (frame 5 of 1..5)\n");

    a = args("E/%04d.png", "1");
    a[9] = "-2";
    r = run_noisy(a);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: noise: -2 is invalid (must be 0..256)\n");

    a = args("E/%04d.png", "1");
    a[9] = "9";
    r = run_noisy(a);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: " + path("R/%04d.png", 1) +
                         ": noise: 9 is too strong for the 32x32 reference and the 64x64 "
                         "source with patch-size 5 (at most 6.4)\n");

    a = args("E/%04d.png", "1");
    a.insert(a.end(), {"--warm-search-iterations", "-1"});
    r = run_noisy(a);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err,
              "exemplar: warm-search-iterations: -1 is invalid (must be an integer, 0..100)\n");

    a = args("E/%04d.png", "1");
    a.insert(a.end(), {"--warm-em-iterations", "0"});
    r = run_noisy(a);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: warm-em-iterations: 0 is invalid (must be an integer, 1..100)\n");

    a = args("E/%04d.png", "1");
    a.insert(a.end(), {"--filter", "gauss"});
    r = run_noisy(a);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: filter: 'gauss' is invalid (must be one of box, lanczos3)\n");

    a = args("E/%04d.png", "-1");
    r = run_noisy(a);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: --threads: -1 is invalid (must be >= 0)\n");

    a = args("E/%04d.png", "1");
    a.erase(a.begin() + 4, a.begin() + 8);  // no --first, --last
    r = run_noisy(a);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: --frames " + path("R/%04d.png") +
                         ": a frame pattern needs --first and --last\n");

    a = args("E/%04d.png", "1");
    a.erase(a.begin() + 8, a.begin() + 10);  // no --noise
    r = run_noisy(a);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: --noise: is required (the low-pass strength f in pixels)\n");

    ASSERT_TRUE(save_image(Image(16, 16, 1, 0.5f), path("map.png")).ok());
    a = args("E/%04d.png", "1");
    a.insert(a.end(), {"--noise-map", path("map.png")});
    r = run_noisy(a);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: " + path("map.png") + ": is 16x16 but " + path("R/%04d.png", 1) +
                         " is 32x32\n");

    ASSERT_TRUE(save_image(testing::cel(40, 32, 12, 14, 9), path("R/%04d.png", 3)).ok());
    r = run_noisy(args("E/%04d.png", "1"));
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: " + path("R/%04d.png", 3) + ": is 40x32 but " +
                         path("R/%04d.png", 1) + " is 32x32\n");
}

TEST_F(NoisyCli, TakesOrientationFields) {
    ASSERT_TRUE(save_image(Image(64, 64, 1, 0.0f), path("OS.exr")).ok());
    fs::create_directories(dir_ / "O");
    for (int n = 1; n <= 2; ++n) {
        ASSERT_TRUE(save_image(Image(32, 32, 1, 0.5f * n), path("O/%04d.exr", n)).ok());
    }
    std::vector<std::string> a = args("T/%04d.png", "2");
    a[7] = "2";
    a.insert(a.end(),
             {"--exemplar-orientation", path("OS.exr"), "--frame-orientation", path("O/%04d.exr")});
    const CliRun oriented = run_noisy(a);
    ASSERT_EQ(oriented.code, 0) << oriented.err;
    EXPECT_TRUE(fs::exists(path("T/%04d.png", 2)));

    a.resize(a.size() - 2);  // no --frame-orientation
    CliRun r = run_noisy(a);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err,
              "exemplar: --exemplar-orientation and --frame-orientation: give both, or neither\n");
    ASSERT_TRUE(save_image(Image(64, 64, 1, 0.0f), path("OS.png")).ok());
    a[a.size() - 1] = path("OS.png");
    a.insert(a.end(), {"--frame-orientation", path("O/%04d.exr")});
    r = run_noisy(a);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: --exemplar-orientation " + path("OS.png") +
                         ": an orientation field holds angles in radians and needs a float "
                         "format (EXR or float TIFF)\n");
}

// Two media and a source map (thesis §4.3.3): a dark medium left of the map's boundary, a bright
// one right of it; frames come from their own medium, from flags or a job file alike.
TEST_F(NoisyCli, ChoosesTheMediumPerPixelFromASourceMap) {
    Image dark = testing::medium(64, 64), bright = testing::medium(64, 64, 7);
    for (float& v : dark.data()) v = 0.05f + 0.4f * std::clamp(v, 0.0f, 1.0f);
    for (float& v : bright.data()) v = 0.55f + 0.4f * std::clamp(v, 0.0f, 1.0f);
    ASSERT_TRUE(save_image(dark, path("dark.png")).ok());
    ASSERT_TRUE(save_image(bright, path("bright.png")).ok());
    fs::create_directories(dir_ / "M");
    for (int n = 1; n <= 4; ++n) {
        Image map(32, 32, 1, 0.0f);  // grey level 1 of 255 names the second --exemplar
        for (int y = 0; y < 32; ++y) {
            for (int x = 12 + n; x < 32; ++x) map.at(x, y, 0) = 1.0f / 255.0f;
        }
        ASSERT_TRUE(save_image(map, path("M/%04d.png", n)).ok());
    }
    std::vector<std::string> a = args("T/%04d.png", "2");
    a[1] = path("dark.png");
    a.insert(a.end(), {"--exemplar", path("bright.png"), "--source-map", path("M/%04d.png")});
    const CliRun r = run_noisy(a);
    ASSERT_EQ(r.code, 0) << r.err;
    for (int n = 1; n <= 4; ++n) {
        auto frame = load_image(path("T/%04d.png", n));
        ASSERT_TRUE(frame.ok());
        long own = 0, count = 0;
        for (int y = 0; y < 32; ++y) {
            for (int x = 0; x < 32; ++x) {
                if (std::abs(x - (12 + n)) <= 1) continue;  // the last vote's 3x3 mixes here
                const bool bright_side = x >= 12 + n;
                own += (frame->at(x, y, 0) > 0.5f) == bright_side;
                ++count;
            }
        }
        EXPECT_EQ(own, count) << "frame " << n;
    }

    // The same from a job file, with the media as an array: the same bytes.
    {
        std::ofstream job(path("job.json"));
        job << "{\"exemplar\": [\"" << path("dark.png") << "\", \"" << path("bright.png")
            << "\"], \"source-map\": \"" << path("M/%04d.png") << "\", \"frames\": \""
            << path("R/%04d.png") << "\", \"first\": 2, \"last\": 2, \"noise\": 3, \"output\": \""
            << path("J/%04d.png")
            << "\", \"patch_size\": 5, \"em-iterations\": 2, \"search-iterations\": 3}";
    }
    const CliRun from_job = run_noisy({"--config", path("job.json"), "-q"});
    ASSERT_EQ(from_job.code, 0) << from_job.err;
    EXPECT_EQ(file_bytes(path("J/%04d.png", 2)), file_bytes(path("T/%04d.png", 2)));
}

TEST_F(NoisyCli, BadSourceMapsStopTheRangeWithOneLineErrors) {
    ASSERT_TRUE(save_image(testing::medium(64, 64, 7), path("S2.png")).ok());
    fs::create_directories(dir_ / "M");
    for (int n = 1; n <= 4; ++n) {
        ASSERT_TRUE(save_image(Image(32, 32, 1, (n % 2) / 255.0f), path("M/%04d.png", n)).ok());
    }
    std::vector<std::string> a = args("E/%04d.png", "1");
    a.insert(a.end(), {"--exemplar", path("S2.png")});
    CliRun r = run_noisy(a);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err,
              "exemplar: --source-map: is required with 2 --exemplar (it chooses the "
              "medium of every pixel)\n");

    // Frame 3's map has another size: frames 1 and 2 are written, 3 and 4 are not.
    a.insert(a.end(), {"--source-map", path("M/%04d.png")});
    ASSERT_TRUE(save_image(Image(30, 32, 1, 0.0f), path("M/%04d.png", 3)).ok());
    r = run_noisy(a);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: " + path("M/%04d.png", 3) + ": is 30x32 but " +
                         path("R/%04d.png", 3) + " is 32x32\n");
    EXPECT_TRUE(fs::exists(path("E/%04d.png", 2)));
    EXPECT_FALSE(fs::exists(path("E/%04d.png", 3)));
    EXPECT_FALSE(fs::exists(path("E/%04d.png", 4)));

    // Frame 4's map names a third medium: frame 3 is made on resume, 4 is not.
    ASSERT_TRUE(save_image(Image(32, 32, 1, 0.0f), path("M/%04d.png", 3)).ok());
    Image third(32, 32, 1, 0.0f);
    third.at(5, 9, 0) = 2.0f / 255.0f;
    ASSERT_TRUE(save_image(third, path("M/%04d.png", 4)).ok());
    r = run_noisy(a);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err, "exemplar: " + path("M/%04d.png", 4) +
                         ": value 2 at (5, 9) has no source (2 given: 0..1)\n");
    EXPECT_TRUE(fs::exists(path("E/%04d.png", 3)));
    EXPECT_FALSE(fs::exists(path("E/%04d.png", 4)));
    for (const auto& entry : fs::directory_iterator(dir_ / "E")) {
        EXPECT_EQ(entry.path().extension(), ".png") << "a partial file: " << entry.path();
    }

    // Orientation fields: one per medium.
    ASSERT_TRUE(save_image(Image(64, 64, 1, 0.0f), path("OS.exr")).ok());
    ASSERT_TRUE(save_image(Image(32, 32, 1, 0.0f), path("O.exr")).ok());
    a.insert(a.end(),
             {"--exemplar-orientation", path("OS.exr"), "--frame-orientation", path("O.exr")});
    r = run_noisy(a);
    EXPECT_EQ(r.code, 1);
    EXPECT_EQ(r.err,
              "exemplar: --exemplar-orientation: 1 given for 2 --exemplar (give one per "
              "exemplar, in their order)\n");
}

TEST_F(NoisyCli, ReadsAVideo) {
    if (!video::mp4_writing_supported()) GTEST_SKIP() << "no MP4 codec in this OpenCV build";
    {
        auto writer = video::Mp4Writer::open(path("clip.mp4"), 32, 32, 24.0);
        ASSERT_TRUE(writer.ok()) << writer.status().message();
        for (int n = 0; n < 3; ++n)
            ASSERT_TRUE(writer->write(testing::cel(32, 32, 12 + n, 14, 9)).ok());
        ASSERT_TRUE(writer->finish().ok());
    }
    std::vector<std::string> a = args("V/%04d.png", "2");
    a[3] = path("clip.mp4");
    a[5] = "0";
    a[7] = "1";
    const CliRun r = run_noisy(a);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(path("V/%04d.png", 0)));
    EXPECT_TRUE(fs::exists(path("V/%04d.png", 1)));
    EXPECT_FALSE(fs::exists(path("V/%04d.png", 2)));
    a[7] = "5";
    const CliRun beyond = run_noisy(a);
    EXPECT_EQ(beyond.code, 1);
    EXPECT_EQ(beyond.err,
              "exemplar: --first/--last: 0..5 is invalid (the video has frames 0..2)\n");
}

}  // namespace
}  // namespace exemplar::noisy
