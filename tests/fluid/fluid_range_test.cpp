// The frame-range driver (fluid_range.hpp) on files: the frames are synthesize_fluid_frame's with
// the previous output read back from its file, a continued or resumed range gives the same bytes,
// missing targets fail before anything is written, cancel keeps the finished frames whole.

#include "exemplar/fluid/fluid_range.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "exemplar/io/flow_io.hpp"
#include "exemplar/io/image_io.hpp"
#include "exemplar/video/frame_sequence.hpp"
#include "file_bytes.hpp"
#include "fluid_scene.hpp"
#include "temp_dir.hpp"

namespace exemplar::fluid {
namespace {

namespace fs = std::filesystem;

using exemplar::testing::file_bytes;

class FluidRangeTest : public exemplar::testing::TempDirTest {
protected:
    // Frames 0..3: an ellipse moving 2 px right per frame, its motion, a 24 px exemplar.
    void SetUp() override {
        TempDirTest::SetUp();
        fs::create_directories(dir_ / "alpha");
        fs::create_directories(dir_ / "motion");
        for (int n = 0; n <= 3; ++n) {
            const Image alpha = test::ellipse_alpha(32, 24, 12.0f + 2.0f * n, 12.0f, 8.0f, 7.0f);
            ASSERT_TRUE(save_image(alpha, file("alpha", n)).is_ok());
            ASSERT_TRUE(
                save_flow(test::uniform_motion(32, 24, 2.0f, 0.0f), file("motion", n)).is_ok());
        }
        options_.patch_size = 3;
        options_.synthesis.seed = 7;
    }

    // `folder`/%04d.png (alpha, output) or .flo (motion) of frame n.
    std::string file(const std::string& folder, int n) const {
        const std::string type = folder == "motion" ? ".flo" : ".png";
        return (dir_ / folder / *video::format_frame_path("%04d" + type, n)).string();
    }

    FluidRange range(int first, int last, const std::string& output) {
        FluidRange r;
        r.first = first;
        r.last = last;
        r.exemplar = [this](int) -> Result<Image> { return exemplar_; };
        r.alpha_file = [this](int n) -> Result<std::string> { return file("alpha", n); };
        r.motion_file = [this](int n) -> Result<std::string> { return file("motion", n); };
        r.output_file = [this, output](int n) -> Result<std::string> { return file(output, n); };
        r.on_frame = [this](int n, const Image&, bool written) -> Status {
            frames_.push_back(written ? n : -n - 1);
            return Status::ok();
        };
        return r;
    }

    Image exemplar_ = test::fire_exemplar(24);
    FluidOptions options_;
    std::vector<int> frames_;  // on_frame's calls: n when written, −n − 1 when resumed
};

TEST_F(FluidRangeTest, FramesAreTheLibrarysEachContinuingFromTheStoredOne) {
    fs::create_directories(dir_ / "out");
    ASSERT_TRUE(synthesize_fluid_range(range(0, 3, "out"), options_, RunContext(1)).is_ok());
    EXPECT_EQ(frames_, (std::vector<int>{0, 1, 2, 3}));
    fs::create_directories(dir_ / "mine");
    std::optional<Image> previous, previous_motion;
    for (int n = 0; n <= 3; ++n) {
        const Image alpha = *load_image(file("alpha", n));
        FluidFrameInput input;
        input.exemplar = &exemplar_;
        input.target_alpha = &alpha;
        input.previous_output = previous ? &*previous : nullptr;
        input.previous_motion = previous_motion ? &*previous_motion : nullptr;
        auto frame = synthesize_fluid_frame(input, options_, RunContext(1));
        ASSERT_TRUE(frame.ok()) << frame.status().message();
        ASSERT_TRUE(save_image(frame->rgba, file("mine", n)).is_ok());
        EXPECT_TRUE(file_bytes(file("out", n)) == file_bytes(file("mine", n))) << "frame " << n;
        previous = *load_image(file("mine", n));
        previous_motion = *load_flow(file("motion", n));
    }
}

TEST_F(FluidRangeTest, ContinuedAndResumedRangesGiveTheSameBytes) {
    fs::create_directories(dir_ / "whole");
    ASSERT_TRUE(synthesize_fluid_range(range(0, 3, "whole"), options_, RunContext(2)).is_ok());
    // Two ranges, the second continuing from the first's last frame, on one thread.
    fs::create_directories(dir_ / "halves");
    ASSERT_TRUE(synthesize_fluid_range(range(0, 1, "halves"), options_, RunContext(1)).is_ok());
    ASSERT_TRUE(synthesize_fluid_range(range(2, 3, "halves"), options_, RunContext(1)).is_ok());
    // Resumed: frames 0 and 1 are there, 2 and 3 are made.
    fs::create_directories(dir_ / "resumed");
    for (int n = 0; n <= 1; ++n) fs::copy_file(file("whole", n), file("resumed", n));
    frames_.clear();
    ASSERT_TRUE(synthesize_fluid_range(range(0, 3, "resumed"), options_, RunContext(1)).is_ok());
    EXPECT_EQ(frames_, (std::vector<int>{-1, -2, 2, 3}));
    for (int n = 0; n <= 3; ++n) {
        EXPECT_TRUE(file_bytes(file("whole", n)) == file_bytes(file("halves", n))) << n;
        EXPECT_TRUE(file_bytes(file("whole", n)) == file_bytes(file("resumed", n))) << n;
    }
    // Without resume every frame is made again, to the same bytes.
    frames_.clear();
    FluidRange again = range(0, 3, "resumed");
    again.resume = false;
    ASSERT_TRUE(synthesize_fluid_range(again, options_, RunContext(1)).is_ok());
    EXPECT_EQ(frames_, (std::vector<int>{0, 1, 2, 3}));
    for (int n = 0; n <= 3; ++n)
        EXPECT_TRUE(file_bytes(file("whole", n)) == file_bytes(file("resumed", n))) << n;
}

TEST_F(FluidRangeTest, MissingTargetsFailBeforeAnyFrameIsWritten) {
    fs::create_directories(dir_ / "out");
    fs::remove(file("motion", 2));
    const Status status = synthesize_fluid_range(range(0, 3, "out"), options_, RunContext(1));
    EXPECT_EQ(status.code(), ErrorCode::IoError);
    EXPECT_EQ(status.message(), file("motion", 2) + ": no such file (motion of frame 2 to 3)");
    EXPECT_TRUE(fs::is_empty(dir_ / "out"));
    // The last frame needs no motion.
    ASSERT_TRUE(synthesize_fluid_range(range(0, 2, "out"), options_, RunContext(1)).is_ok());
    EXPECT_EQ(synthesize_fluid_range(range(3, 2, "out"), options_).code(),
              ErrorCode::InvalidArgument);
}

TEST_F(FluidRangeTest, CancelKeepsTheFinishedFramesWhole) {
    fs::create_directories(dir_ / "out");
    CancelToken cancel;
    RunContext context(1);
    context.cancel = &cancel;
    FluidRange r = range(0, 3, "out");
    r.on_frame = [&](int n, const Image&, bool) -> Status {
        if (n == 1) cancel.cancel();
        return Status::ok();
    };
    EXPECT_EQ(synthesize_fluid_range(r, options_, context).code(), ErrorCode::Cancelled);
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_ / "out"))
        names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"0000.png", "0001.png"}));
}

}  // namespace
}  // namespace exemplar::fluid
