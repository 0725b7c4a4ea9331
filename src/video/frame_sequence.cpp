// Frame sequences from image files or video files, and sequence/MP4 writers. Video files are
// decoded and encoded by the codec plugin (OpenCV videoio, FFmpeg backend), loaded on first use.

#include "exemplar/video/frame_sequence.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <optional>
#include <system_error>

#include "atomic_file.hpp"
#include "video_codec.hpp"
#include "video_plugin.hpp"

namespace exemplar::video {

namespace fs = std::filesystem;

namespace {

std::string lower(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

bool is_image_file(const fs::path& path) {
    static const char* const kExtensions[] = {".png", ".jpg",  ".jpeg", ".exr",
                                              ".tif", ".tiff", ".ppm",  ".pgm"};
    const std::string ext = lower(path.extension().string());
    return std::any_of(std::begin(kExtensions), std::end(kExtensions),
                       [&](const char* e) { return ext == e; });
}

// A decoded frame (blue first) as a float RGB(A) image.
Image from_decoded(const codec::DecodedFrame& frame) {
    const int channels = frame.channels;
    Image image(frame.width, frame.height, channels);
    for (int y = 0; y < frame.height; ++y) {
        const float* row =
            frame.values.data() + static_cast<std::size_t>(y) * frame.width * channels;
        float* out = image.pixel(0, y);
        for (int x = 0; x < frame.width; ++x) {
            for (int c = 0; c < channels; ++c) {
                // OpenCV stores blue first: swap to RGB.
                const int from = channels >= 3 && c < 3 ? 2 - c : c;
                out[x * channels + c] = row[x * channels + from];
            }
        }
    }
    return image;
}

// The codec plugin, or its error naming the video file.
Result<const codec::Entry*> codecs_for(const std::string& file) {
    auto codecs = codec::load_plugin();
    if (!codecs.ok()) {
        return Status(codecs.status().code(), file + ": " + codecs.status().message());
    }
    return codecs;
}

}  // namespace

// The decoder of a video sequence and the index of the frame the next grab() returns.
struct FrameSequence::Decoder {
    std::unique_ptr<codec::VideoReader> capture;
    int next = 0;
};

Result<std::string> format_frame_path(const std::string& pattern, int number) {
    std::string out;
    int conversions = 0;
    for (std::size_t i = 0; i < pattern.size(); ++i) {
        if (pattern[i] != '%') {
            out += pattern[i];
            continue;
        }
        if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
            out += '%';
            ++i;
            continue;
        }
        // %d, %Nd or %0Nd.
        std::size_t j = i + 1;
        const bool zero = j < pattern.size() && pattern[j] == '0';
        if (zero) ++j;
        int width = 0;
        while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j])) &&
               width < 100) {
            width = width * 10 + (pattern[j] - '0');
            ++j;
        }
        if (j >= pattern.size() || pattern[j] != 'd' || width >= 100) {
            return invalid_argument(fmt::format(
                "frame pattern \"{}\": unsupported conversion at position {} (use %d, %4d or "
                "%04d; %% for a literal %)",
                pattern, i));
        }
        out += zero ? fmt::format("{:0{}d}", number, width) : fmt::format("{:{}d}", number, width);
        ++conversions;
        i = j;
    }
    if (conversions != 1) {
        return invalid_argument(fmt::format(
            "frame pattern \"{}\": needs exactly one frame-number conversion such as %04d, has {}",
            pattern, conversions));
    }
    return out;
}

FrameSequence::FrameSequence(FrameSequence&&) noexcept = default;
FrameSequence& FrameSequence::operator=(FrameSequence&&) noexcept = default;
FrameSequence::~FrameSequence() = default;

Result<FrameSequence> FrameSequence::from_pattern(const std::string& pattern, int first, int last) {
    if (last < first) {
        return invalid_argument(fmt::format(
            "frame range {}..{} of \"{}\" is empty (last must be >= first)", first, last, pattern));
    }
    FrameSequence sequence;
    sequence.first_number_ = first;
    for (int n = first; n <= last; ++n) {
        auto path = format_frame_path(pattern, n);
        if (!path.ok()) return path.status();
        std::error_code ec;
        if (!fs::is_regular_file(*path, ec)) {
            return io_error(
                fmt::format("{}: no such file (frame {} of {}..{})", *path, n, first, last));
        }
        sequence.files_.push_back(std::move(path).value());
    }
    sequence.count_ = static_cast<int>(sequence.files_.size());
    return sequence;
}

Result<FrameSequence> FrameSequence::from_folder(const std::string& folder) {
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) return io_error(fmt::format("{}: no such folder", folder));
    FrameSequence sequence;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
        const fs::path& path = entry.path();
        if (path.filename().string().starts_with('.')) continue;
        if (entry.is_regular_file(ec) && is_image_file(path)) {
            sequence.files_.push_back(path.string());
        }
    }
    if (ec) return io_error(fmt::format("{}: cannot list the folder: {}", folder, ec.message()));
    if (sequence.files_.empty()) {
        return io_error(fmt::format(
            "{}: no image files (png, jpg, jpeg, exr, tif, tiff, ppm, pgm) in the folder", folder));
    }
    std::sort(sequence.files_.begin(), sequence.files_.end());
    sequence.count_ = static_cast<int>(sequence.files_.size());
    return sequence;
}

Result<FrameSequence> FrameSequence::from_video(const std::string& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return io_error(fmt::format("{}: no such file", path));
    auto codecs = codecs_for(path);
    if (!codecs.ok()) return codecs.status();
    auto decoder = std::make_unique<Decoder>();
    decoder->capture = (*codecs)->new_reader();
    if (!decoder->capture->open(path)) {
        return io_error(fmt::format("{}: cannot decode as video (unsupported or corrupt)", path));
    }
    // The container's frame count is an estimate for many formats: count by decoding.
    int count = 0;
    while (decoder->capture->grab()) ++count;
    if (count == 0) return io_error(fmt::format("{}: the video has no decodable frame", path));
    decoder->capture->release();

    FrameSequence sequence;
    sequence.video_path_ = path;
    sequence.count_ = count;
    sequence.decoder_ = std::move(decoder);
    sequence.decoder_->next = count;  // forces a reopen on the first read
    return sequence;
}

std::string FrameSequence::frame_name(int index) const {
    if (is_video()) return fmt::format("{} frame {}", video_path_, index);
    return index >= 0 && index < count_ ? files_[static_cast<std::size_t>(index)]
                                        : fmt::format("frame {}", index);
}

Result<Image> FrameSequence::read(int index) {
    if (index < 0 || index >= count_) {
        return invalid_argument(
            fmt::format("frame index {} is out of range (0..{})", index, count_ - 1));
    }
    if (!is_video()) return load_image(files_[static_cast<std::size_t>(index)]);

    // Decode forward from the current position; going back means reopening.
    Decoder& decoder = *decoder_;
    if (index < decoder.next || !decoder.capture->is_open()) {
        decoder.capture->release();
        if (!decoder.capture->open(video_path_)) {
            return io_error(fmt::format("{}: cannot decode as video", video_path_));
        }
        decoder.next = 0;
    }
    for (; decoder.next <= index; ++decoder.next) {
        if (!decoder.capture->grab()) {
            return io_error(fmt::format("{}: cannot decode", frame_name(decoder.next)));
        }
    }
    codec::DecodedFrame frame;
    switch (decoder.capture->retrieve(frame)) {
        case codec::Retrieved::Frame: break;
        case codec::Retrieved::Nothing:
            return io_error(fmt::format("{}: cannot decode", frame_name(index)));
        case codec::Retrieved::UnsupportedSampleType:
            return unsupported(fmt::format("{}: unsupported sample type", frame_name(index)));
    }
    return from_decoded(frame);
}

Status write_frame(const Image& frame, const std::string& pattern, int number,
                   const SaveOptions& options) {
    auto path = format_frame_path(pattern, number);
    if (!path.ok()) return path.status();
    return save_image(frame, *path, options);
}

// ---- MP4 ----------------------------------------------------------------------------------

struct Mp4Writer::State {
    explicit State(const std::string& destination) : temp(destination), path(destination) {}
    io_detail::TempFile temp;
    std::string path;
    std::unique_ptr<codec::VideoWriter> writer;
    int width = 0;
    int height = 0;
    int frames = 0;
};

Mp4Writer::Mp4Writer(Mp4Writer&&) noexcept = default;
Mp4Writer& Mp4Writer::operator=(Mp4Writer&&) noexcept = default;
Mp4Writer::~Mp4Writer() = default;

Result<Mp4Writer> Mp4Writer::open(const std::string& path, int width, int height, double fps) {
    if (lower(fs::path(path).extension().string()) != ".mp4") {
        return unsupported(fmt::format("{}: the video writer writes .mp4 files only", path));
    }
    if (width < 2 || height < 2 || width % 2 != 0 || height % 2 != 0) {
        return invalid_argument(
            fmt::format("{}: frame size {}x{} is invalid for MP4 (both sides even and >= 2)", path,
                        width, height));
    }
    if (!(std::isfinite(fps) && fps > 0.0)) {
        return invalid_argument(fmt::format("{}: fps {} is invalid (must be > 0)", path, fps));
    }
    auto codecs = codecs_for(path);
    if (!codecs.ok()) return codecs.status();
    Mp4Writer writer;
    writer.state_ = std::make_unique<State>(path);
    State& state = *writer.state_;
    EXEMPLAR_RETURN_IF_ERROR(state.temp.status());
    state.width = width;
    state.height = height;
    state.writer = (*codecs)->new_writer();
    if (!state.writer->open(state.temp.path(), fps, width, height)) {
        return unsupported(fmt::format(
            "{}: cannot open an MP4 encoder (this OpenCV build lacks FFmpeg's mpeg4 codec); "
            "write a PNG or EXR sequence instead",
            path));
    }
    return writer;
}

Status Mp4Writer::write(const Image& frame) {
    State& state = *state_;
    const int channels = frame.channels();
    if (frame.width() != state.width || frame.height() != state.height ||
        (channels != 1 && channels != 3 && channels != 4)) {
        return invalid_argument(fmt::format(
            "{}: frame {} is {}x{} with {} channels (expected {}x{} with 1, 3 or 4)", state.path,
            state.frames, frame.width(), frame.height(), channels, state.width, state.height));
    }
    std::vector<std::uint8_t> bgr(static_cast<std::size_t>(state.width) * state.height * 3);
    for (int y = 0; y < state.height; ++y) {
        std::uint8_t* row = bgr.data() + static_cast<std::size_t>(y) * state.width * 3;
        for (int x = 0; x < state.width; ++x) {
            const float* p = frame.pixel(x, y);
            for (int c = 0; c < 3; ++c) {
                float v = channels == 1 ? p[0] : p[c];
                v = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
                row[3 * x + 2 - c] = static_cast<std::uint8_t>(std::lround(v * 255.0f));
            }
        }
    }
    state.writer->write(bgr.data());
    ++state.frames;
    return Status::ok();
}

Status Mp4Writer::finish() {
    State& state = *state_;
    if (state.frames == 0) return io_error(fmt::format("{}: no frame was written", state.path));
    state.writer->release();
    return state.temp.commit();
}

Status check_video_support(const std::string& file) {
    auto codecs = codecs_for(file);
    return codecs.ok() ? Status::ok() : codecs.status();
}

bool mp4_writing_supported() {
    auto codecs = codec::load_plugin();
    if (!codecs.ok()) return false;
    const fs::path probe =
        fs::temp_directory_path() /
        fmt::format("exemplar-mp4-probe-{}.mp4", static_cast<const void*>(&probe));
    auto writer = (*codecs)->new_writer();
    const bool ok = writer->open(probe.string(), 10.0, 16, 16);
    writer->release();
    std::error_code ec;
    fs::remove(probe, ec);
    return ok;
}

}  // namespace exemplar::video
