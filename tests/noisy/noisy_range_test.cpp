// noisy::synthesize_range, the range driver of `exemplar noisy` and the studio: every frame is
// synthesize_frame's, for any thread count (batches of parallel frames or one at a time), resume,
// cancel, and errors that stop the range before their frame.

#include "exemplar/noisy/noisy_range.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "file_bytes.hpp"
#include "procedural.hpp"
#include "temp_dir.hpp"

namespace exemplar::noisy {
namespace {

namespace fs = std::filesystem;

using exemplar::testing::file_bytes;

class NoisyRangeTest : public exemplar::testing::TempDirTest {
protected:
    // Frames 1..3 (32 x 32 cels), two media (dark, bright), a source map per frame (the bright
    // medium right of a moving boundary) and one noise map.
    void SetUp() override {
        TempDirTest::SetUp();
        Image dark = testing::medium(64, 64), bright = testing::medium(64, 64, 7);
        for (float& v : dark.data()) v = 0.05f + 0.4f * std::clamp(v, 0.0f, 1.0f);
        for (float& v : bright.data()) v = 0.55f + 0.4f * std::clamp(v, 0.0f, 1.0f);
        media_ = {{dark, Image()}, {bright, Image()}};
        Image noise(32, 32, 1);
        for (int y = 0; y < 32; ++y) {
            for (int x = 0; x < 32; ++x) noise.at(x, y, 0) = static_cast<float>(y) / 31.0f;
        }
        ASSERT_TRUE(save_image(noise, file("noise.png")).is_ok());
        for (int n = 1; n <= 3; ++n) {
            ASSERT_TRUE(save_image(testing::cel(32, 32, 12 + n, 14, 9), file("r", n)).is_ok());
            Image map(32, 32, 1, 0.0f);
            for (int y = 0; y < 32; ++y) {
                for (int x = 14 + n; x < 32; ++x) map.at(x, y, 0) = 1.0f / 255.0f;
            }
            ASSERT_TRUE(save_image(map, file("m", n)).is_ok());
        }
        options_.noise = 3.0f;
        options_.patch_size = 5;
        options_.em_iterations = 2;
        options_.search_iterations = 3;
    }

    std::string file(const std::string& name, int n = -1) const {
        return (dir_ / (n < 0 ? name : name + std::to_string(n) + ".png")).string();
    }
    // The range 1..3 on the files, outputs `out`N.png.
    NoisyRange range(const std::string& out) const {
        NoisyRange r;
        r.first = 1;
        r.last = 3;
        r.reference = [this](int n) { return load_image(file("r", n)); };
        r.reference_name = [this](int n) { return file("r", n); };
        r.output_file = [this, out](int n) -> Result<std::string> { return file(out, n); };
        r.source_map.file = [this](int n) -> Result<std::string> { return file("m", n); };
        r.source_map.per_frame = true;
        r.noise_map.file = [this](int) -> Result<std::string> { return file("noise.png"); };
        return r;
    }

    std::vector<NoisySource> media_;
    NoisyOptions options_;
};

TEST_F(NoisyRangeTest, EveryFrameIsSynthesizeFramesForAnyThreadCount) {
    const std::pair<int, std::string> runs[] = {{1, "t1_"}, {2, "t2_"}, {3, "t3_"}};
    for (const auto& [threads, out] : runs) {
        NoisyRange r = range(out);
        std::vector<int> reported;
        r.on_frame = [&](int n, const std::string& path) {
            EXPECT_EQ(path, file(out, n));
            EXPECT_TRUE(fs::exists(path));
            reported.push_back(n);
            return Status::ok();
        };
        double last_fraction = 0.0;
        RunContext context(threads);
        context.progress = [&](const ProgressEvent& e) {
            EXPECT_GE(e.fraction, last_fraction);
            EXPECT_LE(e.fraction, 1.0);
            last_fraction = e.fraction;
        };
        const Status status = synthesize_range(media_, r, options_, context);
        ASSERT_TRUE(status.is_ok()) << status.message();
        EXPECT_EQ(reported, (std::vector<int>{1, 2, 3})) << threads << " threads";
        EXPECT_GT(last_fraction, 0.5);
    }
    auto noise = load_noise_map(file("noise.png"));
    ASSERT_TRUE(noise.ok());
    for (int n = 1; n <= 3; ++n) {
        NoisyFrame frame;
        frame.reference = *load_image(file("r", n));
        frame.noise_map = *noise;
        frame.source_map = Image(32, 32, 1, 0.0f);
        for (int y = 0; y < 32; ++y) {
            for (int x = 14 + n; x < 32; ++x) frame.source_map.at(x, y, 0) = 1.0f;
        }
        auto image = synthesize_frame(media_, frame, options_, n, RunContext(1));
        ASSERT_TRUE(image.ok()) << image.status().message();
        ASSERT_TRUE(save_image(*image, file("lib", n)).is_ok());
        for (const char* out : {"t1_", "t2_", "t3_"}) {
            EXPECT_EQ(file_bytes(file(out, n)), file_bytes(file("lib", n)))
                << out << " frame " << n;
        }
    }
}

TEST_F(NoisyRangeTest, ResumesAndStopsWhenCancelled) {
    { std::ofstream(file("o", 2), std::ios::binary) << "kept"; }
    NoisyRange r = range("o");
    std::vector<int> reported;
    r.on_frame = [&](int n, const std::string&) {
        reported.push_back(n);
        return Status::ok();
    };
    ASSERT_TRUE(synthesize_range(media_, r, options_, RunContext(2)).is_ok());
    EXPECT_EQ(reported, (std::vector<int>{1, 3}));
    EXPECT_EQ(file_bytes(file("o", 2)), "kept");

    CancelToken token;
    token.cancel();
    RunContext cancelled_context(2);
    cancelled_context.cancel = &token;
    const Status cancelled = synthesize_range(media_, range("c"), options_, cancelled_context);
    EXPECT_EQ(cancelled.code(), ErrorCode::Cancelled);
    EXPECT_FALSE(fs::exists(file("c", 1)));
}

TEST_F(NoisyRangeTest, ABadInputStopsTheRangeBeforeItsFrameWithOneLine) {
    // Frame 2's source map has another size: frame 1 is written, 2 and 3 are not.
    ASSERT_TRUE(save_image(Image(30, 32, 1, 0.0f), file("m", 2)).is_ok());
    Status status = synthesize_range(media_, range("e"), options_, RunContext(1));
    EXPECT_EQ(status.message(), file("m", 2) + ": is 30x32 but " + file("r", 2) + " is 32x32");
    EXPECT_TRUE(fs::exists(file("e", 1)));
    EXPECT_FALSE(fs::exists(file("e", 2)));
    EXPECT_FALSE(fs::exists(file("e", 3)));

    // A source-map value without a medium names the map.
    Image third(32, 32, 1, 0.0f);
    third.at(5, 9, 0) = 2.0f / 255.0f;
    ASSERT_TRUE(save_image(third, file("m", 2)).is_ok());
    status = synthesize_range(media_, range("e"), options_, RunContext(1));
    EXPECT_EQ(status.message(), file("m", 2) + ": value 2 at (5, 9) has no source (2 given: 0..1)");

    // A frame of another size, and the synthesis's own errors, name the frame.
    ASSERT_TRUE(save_image(Image(32, 32, 1, 0.0f), file("m", 2)).is_ok());
    ASSERT_TRUE(save_image(testing::cel(40, 32, 12, 14, 9), file("r", 3)).is_ok());
    status = synthesize_range(media_, range("e"), options_, RunContext(1));
    EXPECT_EQ(status.message(), file("r", 3) + ": is 40x32 but " + file("r", 2) + " is 32x32");
    NoisyOptions strong = options_;
    strong.noise = 9.0f;
    status = synthesize_range(media_, range("s"), strong, RunContext(1));
    EXPECT_EQ(status.message().rfind(file("r", 1) + ": noise: 9 is too strong", 0), 0u)
        << status.message();

    // Orientation fields need a float format.
    NoisyRange oriented = range("e");
    oriented.orientation.file = [this](int) -> Result<std::string> { return file("noise.png"); };
    status = synthesize_range(media_, oriented, options_, RunContext(1));
    EXPECT_EQ(status.message(), file("noise.png") +
                                    ": an orientation field holds angles in radians and needs a "
                                    "float format (EXR or float TIFF)");
}

}  // namespace
}  // namespace exemplar::noisy
