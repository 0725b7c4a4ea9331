#pragma once
/// \file
/// Frame sequences: the input animation I_t as image files (a printf-style pattern with a frame
/// range, or a folder) or a video file decoded by OpenCV (FFmpeg backend), and writers for PNG/EXR
/// sequences and MP4 files.
///
/// Video files are decoded and encoded by a plugin, `libexemplar_video_mp4.so`, loaded on the
/// first video read or write: it holds OpenCV's videoio and with it FFmpeg and GStreamer, which
/// would otherwise load into every process. It is looked for next to the executable, then in
/// `../lib/exemplar/` from it (the install layout), or only in `$EXEMPLAR_PLUGIN_DIR` if that is
/// set. Without it image sequences work as usual and every video call returns Unsupported
/// `clip.mp4: video support is not available (libexemplar_video_mp4.so: <reason>)`.
///
/// Frames are read on demand, as `Image`s like `load_image` returns them (video frames: 3
/// channels "R", "G", "B" in [0, 1]). Errors are one line naming the file: a missing frame
/// `frames/0042.png: no such file` when the sequence is described, not halfway through a run.
/// A FrameSequence is not thread-safe (a video keeps its decoder position); use one per thread.

#include <memory>
#include <string>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/io/image_io.hpp"

namespace exemplar::video {

/// The file name of frame `number` in a printf-style `pattern` with exactly one integer
/// conversion `%d`, `%Nd` or `%0Nd` (`%%` is a literal '%'): ("f/%04d.png", 7) → "f/0007.png".
/// InvalidArgument naming the pattern if it has no, several or other conversions.
Result<std::string> format_frame_path(const std::string& pattern, int number);

/// An ordered list of frames. Create with one of the `from_*` functions.
class FrameSequence {
public:
    /// Files `pattern` % n for n = first..last (inclusive). IoError naming the first missing
    /// file; InvalidArgument for a bad pattern or last < first.
    static Result<FrameSequence> from_pattern(const std::string& pattern, int first, int last);
    /// The image files of `folder` (extensions png, jpg, jpeg, exr, tif, tiff, ppm, pgm, any
    /// case; hidden files skipped) sorted by name, so frames must be zero-padded. IoError if the
    /// folder is missing or holds no image file.
    static Result<FrameSequence> from_folder(const std::string& folder);
    /// A video file (anything OpenCV's FFmpeg backend decodes: MP4, MOV, AVI, ...). The frames
    /// are counted by decoding the file once. IoError if the file is missing, cannot be decoded
    /// or has no frame; Unsupported if the video plugin cannot be loaded.
    static Result<FrameSequence> from_video(const std::string& path);

    FrameSequence(FrameSequence&&) noexcept;
    FrameSequence& operator=(FrameSequence&&) noexcept;
    ~FrameSequence();

    /// Number of frames.
    int size() const { return count_; }
    /// True for a video file, false for image files.
    bool is_video() const { return !video_path_.empty(); }
    /// Frame number of index 0 (`first` for a pattern, else 0).
    int first_number() const { return first_number_; }
    /// Name for messages: the file path, or "<video> frame <index>".
    std::string frame_name(int index) const;
    /// Reads frame `index` (0-based, < size(); InvalidArgument otherwise). IoError naming the
    /// file if it cannot be read (e.g. deleted since the sequence was described).
    Result<Image> read(int index);

private:
    struct Decoder;
    FrameSequence() = default;

    std::vector<std::string> files_;
    std::string video_path_;
    int first_number_ = 0;
    int count_ = 0;
    std::unique_ptr<Decoder> decoder_;
};

/// Writes frame `number` of a sequence to `format_frame_path(pattern, number)` with
/// `save_image` (atomic per frame; format from the extension, e.g. PNG or EXR).
Status write_frame(const Image& frame, const std::string& pattern, int number,
                   const SaveOptions& options = {});

/// Ok if video files can be read and written: the video plugin loads (on the first call).
/// Unsupported `<file>: video support is not available (libexemplar_video_mp4.so: <reason>)`
/// otherwise, so a command can check before it starts a long run that ends in a video.
Status check_video_support(const std::string& file);

/// True if the video plugin loads and its OpenCV build can encode MP4 (codec "mp4v", MPEG-4
/// Part 2 through FFmpeg).
bool mp4_writing_supported();

/// Writes an MP4 file frame by frame with cv::VideoWriter ("mp4v"). The file is written under a
/// temporary name and renamed onto `path` by `finish()`, so `path` is never half-written;
/// destroying the writer without `finish()` leaves `path` untouched.
class Mp4Writer {
public:
    /// Opens the writer for `width` x `height` frames (each ≥ 2 and even: the codec needs it)
    /// at `fps` (> 0). InvalidArgument for bad values, IoError/Unsupported if the file cannot
    /// be created, the video plugin cannot be loaded or the codec is missing.
    static Result<Mp4Writer> open(const std::string& path, int width, int height, double fps);

    Mp4Writer(Mp4Writer&&) noexcept;
    Mp4Writer& operator=(Mp4Writer&&) noexcept;
    ~Mp4Writer();

    /// Appends one frame: 1 (grey), 3 (RGB) or 4 (RGBA, alpha dropped) channels in [0, 1]
    /// (clamped), of the size given to `open`. InvalidArgument otherwise.
    Status write(const Image& frame);
    /// Closes the file and moves it into place. IoError if nothing was written.
    Status finish();

private:
    struct State;
    Mp4Writer() = default;
    std::unique_ptr<State> state_;
};

}  // namespace exemplar::video
