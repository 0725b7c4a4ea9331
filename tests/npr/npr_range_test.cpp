// The frame-range driver on files (npr::stylize_range) on synthetic render frame folders: the
// frames of stylize_frame called frame by frame, determinism for any thread count with the paper
// layer and the bidirectional loop, resume by blocks, the frame callback, progress over the
// range, cancel between frames, and the checks of check_npr_range.
#include "exemplar/npr/npr_range.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "exemplar/io/flow_io.hpp"
#include "exemplar/io/image_io.hpp"
#include "file_bytes.hpp"
#include "npr_patterns.hpp"
#include "temp_dir.hpp"

namespace exemplar::npr {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 48, kHeight = 32, kFrames = 5, kStep = 2;

using exemplar::testing::file_bytes;

// kFrames folders F/frame_N of what `exemplar render --frames` writes and npr reads: a tone
// ramp moving right by kStep px a frame, a vertical line moving with it, the motion both ways,
// the strip it uncovers (left) and hides (right), and a shape (alpha) of the left two thirds.
class NprRangeDriver : public exemplar::testing::TempDirTest {
protected:
    void SetUp() override {
        TempDirTest::SetUp();
        for (int n = 0; n < kFrames; ++n) {
            const fs::path folder = dir_ / "F" / ("frame_" + std::to_string(n));
            fs::create_directories(folder);
            Image tone(kWidth, kHeight, 1), lines(kWidth, kHeight, 1), alpha(kWidth, kHeight, 1);
            Image backward(kWidth, kHeight, 2), forward(kWidth, kHeight, 2);
            Image disocclusion(kWidth, kHeight, 1), occlusion(kWidth, kHeight, 1);
            for (int y = 0; y < kHeight; ++y) {
                for (int x = 0; x < kWidth; ++x) {
                    const int u = (x - kStep * n + 4 * kWidth) % kWidth;
                    tone.at(x, y, 0) = static_cast<float>(u) / static_cast<float>(kWidth);
                    lines.at(x, y, 0) = u == 20 ? 1.0f : 0.0f;
                    alpha.at(x, y, 0) = 3 * x < 2 * kWidth ? 1.0f : 0.0f;
                    backward.at(x, y, 0) = -kStep;
                    forward.at(x, y, 0) = kStep;
                    disocclusion.at(x, y, 0) = x < kStep ? 1.0f : 0.0f;
                    occlusion.at(x, y, 0) = x >= kWidth - kStep ? 1.0f : 0.0f;
                }
            }
            const auto save = [&](const Image& image, const char* name) {
                ASSERT_TRUE(save_image(image, (folder / name).string()).is_ok()) << name;
            };
            save(tone, "direct_diffuse.png");
            save(lines, "lines.png");
            save(alpha, "alpha.png");
            save(disocclusion, "disocclusion.png");
            save(occlusion, "occlusion.png");
            ASSERT_TRUE(save_flow(backward, (folder / "backward_flow.exr").string()).is_ok());
            ASSERT_TRUE(save_flow(forward, (folder / "forward_flow.exr").string()).is_ok());
        }
        options_.levels = 2;
        options_.patch_size = 8;
        options_.seed = 5;
        auto pattern = prepare_pattern(testing::stipple_pattern(64, 5.0f), options_);
        ASSERT_TRUE(pattern.ok()) << pattern.status().message();
        pattern_ = std::move(pattern).value();
        auto paper = prepare_pattern(testing::halftone_pattern(64, 8), options_);
        ASSERT_TRUE(paper.ok()) << paper.status().message();
        paper_ = std::move(paper).value();
    }

    std::string folder(int n) const {
        return (dir_ / "F" / ("frame_" + std::to_string(n))).string();
    }
    std::string output(const std::string& run, int n) const {
        return (dir_ / run / (std::to_string(n) + ".png")).string();
    }
    // Frames first..last of the folders, written to run/N.png.
    NprRange range(const std::string& run, int first = 0, int last = kFrames - 1) const {
        NprRange r;
        r.first = first;
        r.last = last;
        r.frame_folder = [this](int n) -> Result<std::string> { return folder(n); };
        r.output_file = [this, run](int n) -> Result<std::string> {
            if (n < 0) return invalid_argument("no frame " + std::to_string(n));
            return output(run, n);
        };
        return r;
    }
    // The bytes of every file the run wrote, by name.
    std::vector<std::string> run_bytes(const std::string& run) const {
        std::vector<std::string> files;
        for (const auto& e : fs::directory_iterator(dir_ / run)) files.push_back(e.path().string());
        std::sort(files.begin(), files.end());
        std::vector<std::string> bytes;
        for (const std::string& f : files)
            bytes.push_back(fs::path(f).filename().string() + ":" + file_bytes(f));
        return bytes;
    }

    NprOptions options_;
    Pattern pattern_, paper_;
};

TEST_F(NprRangeDriver, AForwardRangeIsStylizeFrameFrameByFrame) {
    NprRange r = range("A");
    std::vector<int> handed;
    r.on_frame = [&](int n, const std::string& out, const Image* image) -> Status {
        handed.push_back(n);
        EXPECT_EQ(out, output("A", n));
        EXPECT_NE(image, nullptr);
        return Status::ok();
    };
    ASSERT_TRUE(stylize_range(pattern_, nullptr, r, options_, RunContext(2)).is_ok());
    EXPECT_EQ(handed, (std::vector<int>{0, 1, 2, 3, 4}));
    std::optional<FrameState> previous;
    for (int n = 0; n < kFrames; ++n) {
        NprFrame frame;
        for (const BufferNeed& need : needed_buffers(options_, previous.has_value())) {
            auto buffer = load_image(frame_buffer_file(folder(n), need.name));
            ASSERT_TRUE(buffer.ok()) << need.name;
            frame[need.role] = std::move(buffer).value();
        }
        auto styled = stylize_frame(pattern_, frame, previous ? &*previous : nullptr, n, options_,
                                    RunContext(1));
        ASSERT_TRUE(styled.ok()) << styled.status().message();
        const std::string mine = output("mine", n);
        ASSERT_TRUE(save_image(styled->image, mine).is_ok());
        EXPECT_EQ(file_bytes(output("A", n)), file_bytes(mine)) << "frame " << n;
        EXPECT_TRUE(fs::exists(output("A", n) + ".state.exr")) << n;
        EXPECT_FALSE(fs::exists(output("A", n) + ".paper.state.exr")) << n;
        previous = std::move(styled->state);
    }
}

// Blocks [0], [1, 2], [3, 4]: the same bytes for 1 and 2 threads; a block with a frame missing
// is done again as a whole, the others skipped, to the same bytes.
TEST_F(NprRangeDriver, BidirectionalWithPaperIsThreadIndependentAndResumesByBlocks) {
    options_.paper = true;
    for (const auto& [run, threads] : {std::pair{"one", 1}, std::pair{"two", 2}}) {
        NprRange r = range(run);
        r.bidirectional = 2;
        ASSERT_TRUE(stylize_range(pattern_, &paper_, r, options_, RunContext(threads)).is_ok());
    }
    const std::vector<std::string> bytes = run_bytes("one");
    EXPECT_EQ(bytes.size(), 3u * kFrames);
    EXPECT_EQ(bytes, run_bytes("two"));
    // Frame 1's backward pass changed it: the forward-only run differs there, not at frame 0
    NprRange forward = range("forward");
    ASSERT_TRUE(stylize_range(pattern_, &paper_, forward, options_, RunContext(2)).is_ok());
    EXPECT_EQ(file_bytes(output("forward", 0)), file_bytes(output("one", 0)));
    EXPECT_NE(file_bytes(output("forward", 1) + ".state.exr"),
              file_bytes(output("one", 1) + ".state.exr"));

    fs::remove(output("one", 2) + ".paper.state.exr");
    NprRange again = range("one");
    again.bidirectional = 2;
    std::vector<std::pair<int, bool>> handed;
    again.on_frame = [&](int n, const std::string&, const Image* image) -> Status {
        handed.emplace_back(n, image != nullptr);
        return Status::ok();
    };
    ASSERT_TRUE(stylize_range(pattern_, &paper_, again, options_, RunContext(2)).is_ok());
    const std::vector<std::pair<int, bool>> expected{
        {0, false}, {1, true}, {2, true}, {3, false}, {4, false}};
    EXPECT_EQ(handed, expected);
    EXPECT_EQ(run_bytes("one"), bytes);
}

// A range continued from the frame before it equals the range run at once.
TEST_F(NprRangeDriver, AContinuedRangeTakesOverTheStatesOfTheFrameBefore) {
    options_.paper = true;
    ASSERT_TRUE(stylize_range(pattern_, &paper_, range("whole"), options_).is_ok());
    ASSERT_TRUE(stylize_range(pattern_, &paper_, range("parts", 0, 1), options_).is_ok());
    ASSERT_TRUE(stylize_range(pattern_, &paper_, range("parts", 2, 4), options_).is_ok());
    EXPECT_EQ(run_bytes("parts"), run_bytes("whole"));
}

TEST_F(NprRangeDriver, ProgressCoversTheRangeAndCancelKeepsTheFinishedFramesWhole) {
    options_.paper = true;
    NprRange r = range("A");
    r.bidirectional = 2;
    std::vector<double> fractions;
    RunContext context(2);
    context.progress = [&](const ProgressEvent& event) { fractions.push_back(event.fraction); };
    ASSERT_TRUE(stylize_range(pattern_, &paper_, r, options_, context).is_ok());
    // 5 frames and 2 backward passes, pattern and paper, 2 levels each
    EXPECT_EQ(fractions.size(), 7u * 2u * 2u);
    EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
    EXPECT_GT(fractions.front(), 0.0);
    EXPECT_DOUBLE_EQ(fractions.back(), 1.0);

    // Cancelled as frame 1 is handed over (with block [1, 2]): frames 0..2 stay, whole, with
    // their states, no other
    CancelToken cancel;
    NprRange c = range("C");
    c.bidirectional = 2;
    c.on_frame = [&](int n, const std::string&, const Image*) -> Status {
        if (n == 1) cancel.cancel();
        return Status::ok();
    };
    RunContext cancelling(2);
    cancelling.cancel = &cancel;
    const Status status = stylize_range(pattern_, &paper_, c, options_, cancelling);
    EXPECT_EQ(status.code(), ErrorCode::Cancelled) << status.message();
    for (int n = 0; n <= 2; ++n) {
        for (const char* suffix : {"", ".state.exr", ".paper.state.exr"}) {
            EXPECT_EQ(file_bytes(output("C", n) + suffix), file_bytes(output("A", n) + suffix))
                << n << suffix;
        }
    }
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_ / "C"), fs::directory_iterator()), 9);
}

TEST_F(NprRangeDriver, ChecksNameTheMissingFolderBufferAndForwardFlow) {
    EXPECT_TRUE(check_npr_range(range("A"), options_).is_ok());
    NprRange bidirectional = range("A");
    bidirectional.bidirectional = 2;
    EXPECT_TRUE(check_npr_range(bidirectional, options_).is_ok());
    // Frame 1's forward flow: only the backward pass of block [1, 2] reads it
    fs::remove(folder(1) + "/forward_flow.exr");
    EXPECT_TRUE(check_npr_range(range("A"), options_).is_ok());
    Status status = check_npr_range(bidirectional, options_);
    EXPECT_EQ(status.code(), ErrorCode::IoError);
    EXPECT_EQ(status.message(), folder(1) + ": missing buffer 'forward_flow' (forward_flow.png " +
                                    "or forward_flow.exr)");
    // The run stops there too, with the same message, keeping frame 0
    status = stylize_range(pattern_, nullptr, bidirectional, options_);
    EXPECT_EQ(status.message(), folder(1) + ": missing buffer 'forward_flow' (forward_flow.png " +
                                    "or forward_flow.exr)");
    EXPECT_TRUE(fs::exists(output("A", 0)));
    EXPECT_FALSE(fs::exists(output("A", 1)));
    // The first frame reads no motion, the others do
    fs::remove(folder(0) + "/backward_flow.exr");
    EXPECT_TRUE(check_npr_range(range("B"), options_).is_ok());
    fs::remove(folder(3) + "/backward_flow.exr");
    EXPECT_EQ(check_npr_range(range("B"), options_).message(),
              folder(3) + ": missing buffer 'backward_flow' (backward_flow.png or " +
                  "backward_flow.exr)");
    // The paper layer reads the shape
    options_.paper = true;
    fs::remove(folder(2) + "/alpha.png");
    EXPECT_EQ(check_npr_range(range("B", 0, 2), options_).message(),
              folder(2) + ": missing buffer 'alpha' (alpha.png or alpha.exr)");
    EXPECT_EQ(check_npr_range(range("B", 0, 7), options_).message(),
              folder(2) + ": missing buffer 'alpha' (alpha.png or alpha.exr)");
    options_.paper = false;
    EXPECT_EQ(check_npr_range(range("B", 4, 7), options_).message(),
              folder(5) + ": no such frame folder (from exemplar render --frames)");
    // The range's own settings, and a paper given or not as the options say
    NprRange bad = range("B");
    bad.bidirectional = 1;
    EXPECT_EQ(validate(bad).message(), "bidirectional: 1 is invalid (must be 0 or 2..1000)");
    EXPECT_EQ(validate(range("B", 3, 2)).message(), "last: 2 is before first 3");
    EXPECT_EQ(stylize_range(pattern_, &paper_, range("B"), options_).code(),
              ErrorCode::InvalidArgument);
    options_.paper = true;
    EXPECT_EQ(stylize_range(pattern_, nullptr, range("B"), options_).code(),
              ErrorCode::InvalidArgument);
    EXPECT_FALSE(fs::exists(dir_ / "B"));
}

}  // namespace
}  // namespace exemplar::npr
