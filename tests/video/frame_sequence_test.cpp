// Frame sequences: patterns, folders, video files; PNG sequence and MP4 writers; errors that
// name the missing or unreadable file.

#include "exemplar/video/frame_sequence.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "exemplar/io/image_io.hpp"
#include "temp_dir.hpp"

namespace exemplar::video {
namespace {

namespace fs = std::filesystem;

// Frame n: a gradient whose brightness depends on n (distinguishable after MP4 compression).
Image frame(int n, int w = 32, int h = 24) {
    Image image(w, h, 3);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            image.at(x, y, 0) = 0.1f + 0.15f * static_cast<float>(n);
            image.at(x, y, 1) = static_cast<float>(x) / static_cast<float>(w);
            image.at(x, y, 2) = static_cast<float>(y) / static_cast<float>(h);
        }
    }
    return image;
}

double mean_abs_diff(const Image& a, const Image& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) sum += std::abs(a.data()[i] - b.data()[i]);
    return sum / static_cast<double>(a.size());
}

class Sequences : public exemplar::testing::TempDirTest {
protected:
    void SetUp() override {
        TempDirTest::SetUp();
        fs::create_directories(dir_ / "frames");
    }
};

TEST(FramePattern, FormatsOneIntegerConversion) {
    EXPECT_EQ(*format_frame_path("f/%04d.png", 7), "f/0007.png");
    EXPECT_EQ(*format_frame_path("f_%d.exr", 123), "f_123.exr");
    EXPECT_EQ(*format_frame_path("100%%/%3d.png", 5), "100%/  5.png");
    EXPECT_EQ(format_frame_path("plain.png", 1).status().code(), ErrorCode::InvalidArgument);
    EXPECT_FALSE(format_frame_path("%d_%d.png", 1).ok());
    EXPECT_FALSE(format_frame_path("%s.png", 1).ok());
    EXPECT_NE(format_frame_path("%x.png", 1).status().message().find("\"%x.png\""),
              std::string::npos);
}

TEST_F(Sequences, PatternReadsWrittenFramesAndNamesTheMissingOne) {
    const std::string pattern = path("frames/%04d.png");
    for (int n = 3; n <= 6; ++n) ASSERT_TRUE(write_frame(frame(n), pattern, n).is_ok());
    EXPECT_TRUE(fs::exists(path("frames/0005.png")));

    auto sequence = FrameSequence::from_pattern(pattern, 3, 6);
    ASSERT_TRUE(sequence.ok()) << sequence.status().message();
    EXPECT_EQ(sequence->size(), 4);
    EXPECT_EQ(sequence->first_number(), 3);
    EXPECT_FALSE(sequence->is_video());
    EXPECT_EQ(sequence->frame_name(2), path("frames/0005.png"));
    auto third = sequence->read(2);
    ASSERT_TRUE(third.ok());
    EXPECT_LT(mean_abs_diff(*third, frame(5)), 0.003);  // 8-bit rounding only
    EXPECT_EQ(sequence->read(4).status().code(), ErrorCode::InvalidArgument);

    auto missing = FrameSequence::from_pattern(pattern, 3, 8);
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.status().code(), ErrorCode::IoError);
    EXPECT_EQ(missing.status().message(),
              path("frames/0007.png") + ": no such file (frame 7 of 3..8)");
    EXPECT_FALSE(FrameSequence::from_pattern(pattern, 5, 4).ok());
}

TEST_F(Sequences, FolderIsSortedAndSkipsOtherFiles) {
    for (int n : {2, 0, 1})
        ASSERT_TRUE(save_image(frame(n), path("frames/f" + std::to_string(n) + ".png")).is_ok());
    std::ofstream(path("frames/notes.txt")) << "not a frame";
    std::ofstream(path("frames/.hidden.png")) << "not a frame";
    auto sequence = FrameSequence::from_folder(path("frames"));
    ASSERT_TRUE(sequence.ok()) << sequence.status().message();
    ASSERT_EQ(sequence->size(), 3);
    EXPECT_EQ(sequence->frame_name(0), path("frames/f0.png"));
    EXPECT_EQ(sequence->frame_name(2), path("frames/f2.png"));

    fs::create_directories(path("empty"));
    auto empty = FrameSequence::from_folder(path("empty"));
    EXPECT_EQ(empty.status().code(), ErrorCode::IoError);
    EXPECT_NE(empty.status().message().find("no image files"), std::string::npos);
    EXPECT_NE(FrameSequence::from_folder(path("nope")).status().message().find("no such folder"),
              std::string::npos);
}

TEST_F(Sequences, Mp4RoundTrip) {
    if (!mp4_writing_supported()) GTEST_SKIP() << "this OpenCV build cannot encode MP4";
    {
        auto writer = Mp4Writer::open(path("clip.mp4"), 32, 24, 10.0);
        ASSERT_TRUE(writer.ok()) << writer.status().message();
        for (int n = 0; n < 5; ++n) ASSERT_TRUE(writer->write(frame(n)).is_ok());
        EXPECT_EQ(writer->write(frame(0, 30, 24)).code(), ErrorCode::InvalidArgument);
        EXPECT_FALSE(fs::exists(path("clip.mp4"))) << "visible before finish()";
        ASSERT_TRUE(writer->finish().is_ok());
    }
    auto sequence = FrameSequence::from_video(path("clip.mp4"));
    ASSERT_TRUE(sequence.ok()) << sequence.status().message();
    EXPECT_TRUE(sequence->is_video());
    ASSERT_EQ(sequence->size(), 5);
    // Random access, forwards and backwards; lossy codec, so compare loosely but tell frames
    // apart (neighbours differ by 0.05 on average).
    for (int index : {3, 1, 4}) {
        auto image = sequence->read(index);
        ASSERT_TRUE(image.ok()) << image.status().message();
        ASSERT_EQ(image->channels(), 3);
        EXPECT_LT(mean_abs_diff(*image, frame(index)), 0.02) << index;
    }
    EXPECT_EQ(sequence->frame_name(2), path("clip.mp4") + " frame 2");

    // Abandoned writers leave nothing behind.
    {
        auto writer = Mp4Writer::open(path("abandoned.mp4"), 32, 24, 10.0);
        ASSERT_TRUE(writer.ok());
        ASSERT_TRUE(writer->write(frame(0)).is_ok());
    }
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), {}), 2) << "frames/ and clip.mp4";
}

TEST_F(Sequences, UnreadableVideoIsAnErrorNamingTheFile) {
    std::ofstream(path("bad.mp4")) << "this is not a video";
    auto bad = FrameSequence::from_video(path("bad.mp4"));
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.status().code(), ErrorCode::IoError);
    EXPECT_EQ(bad.status().message().rfind(path("bad.mp4") + ": ", 0), 0u)
        << bad.status().message();
    EXPECT_EQ(FrameSequence::from_video(path("none.mp4")).status().message(),
              path("none.mp4") + ": no such file");
    EXPECT_EQ(Mp4Writer::open(path("odd.mp4"), 31, 24, 10).status().code(),
              ErrorCode::InvalidArgument);
    EXPECT_EQ(Mp4Writer::open(path("clip.avi"), 32, 24, 10).status().code(),
              ErrorCode::Unsupported);
}

}  // namespace
}  // namespace exemplar::video
