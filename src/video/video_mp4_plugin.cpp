// The video codec plugin, libexemplar_video_mp4.so: OpenCV's videoio (FFmpeg backend) behind the
// interface of video_codec.hpp. exemplar::video loads it on the first video read or write; it is
// the only exemplar binary that links libopencv_videoio.

#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>
#include <string>

#include "video_codec.hpp"

namespace exemplar::video::codec {
namespace {

class CaptureReader final : public VideoReader {
public:
    bool open(const std::string& path) override { return capture_.open(path, cv::CAP_FFMPEG); }
    bool is_open() const override { return capture_.isOpened(); }
    bool grab() override { return capture_.grab(); }
    Retrieved retrieve(DecodedFrame& frame) override {
        cv::Mat mat;
        if (!capture_.retrieve(mat) || mat.empty()) return Retrieved::Nothing;
        if (mat.depth() != CV_8U && mat.depth() != CV_16U) return Retrieved::UnsupportedSampleType;
        frame.width = mat.cols;
        frame.height = mat.rows;
        frame.channels = mat.channels();
        frame.values.resize(mat.total() * static_cast<std::size_t>(frame.channels));
        cv::Mat values(mat.rows, mat.cols, CV_32FC(frame.channels), frame.values.data());
        mat.convertTo(values, values.type(), mat.depth() == CV_16U ? 1.0 / 65535.0 : 1.0 / 255.0);
        return Retrieved::Frame;
    }
    void release() override { capture_.release(); }

private:
    cv::VideoCapture capture_;
};

class Mp4vWriter final : public VideoWriter {
public:
    bool open(const std::string& path, double fps, int width, int height) override {
        size_ = cv::Size(width, height);
        return writer_.open(path, cv::CAP_FFMPEG, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), fps,
                            cv::Size(width, height), true);
    }
    void write(const std::uint8_t* bgr) override {
        writer_.write(cv::Mat(size_, CV_8UC3, const_cast<std::uint8_t*>(bgr)));
    }
    void release() override { writer_.release(); }

private:
    cv::VideoWriter writer_;
    cv::Size size_;
};

std::unique_ptr<VideoReader> new_reader() {
    return std::make_unique<CaptureReader>();
}
std::unique_ptr<VideoWriter> new_writer() {
    return std::make_unique<Mp4vWriter>();
}

constexpr Entry kEntry{kPlugin.abi_version, &new_reader, &new_writer};

}  // namespace
}  // namespace exemplar::video::codec

// The one exported symbol (the library is built with hidden visibility); its name is
// codec::kPlugin.entry_symbol.
extern "C" __attribute__((visibility("default"))) const exemplar::video::codec::Entry*
exemplar_video_codec_entry() {
    return &exemplar::video::codec::kEntry;
}
