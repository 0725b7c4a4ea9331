#pragma once
// The interface between exemplar::video and its codec plugin, libexemplar_video_mp4.so
// (video_mp4_plugin.cpp): the only code that uses OpenCV's videoio.
//
// Why a plugin: linking libopencv_videoio loads FFmpeg, GStreamer and their dependencies (about
// 240 shared libraries, ~70 MB resident) before main() runs, in every process, whether or not it
// touches a video. exemplar::video loads the plugin with dlopen on the first video read or write
// instead (video_plugin.cpp), so only commands that use video files pay for the codecs.
//
// Both sides are compiled from this header by the same build, so std::unique_ptr and
// std::vector cross the boundary as they are; frames are plain buffers, as `exemplar` itself
// does not link OpenCV (src/plugin/opencv_kernels.hpp). kPlugin.abi_version rejects a plugin left
// over from a build with a different interface. The plugin is never unloaded (plugin_loader.hpp).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "plugin_loader.hpp"

namespace exemplar::video::codec {

/// The plugin; raise its abi_version whenever the classes or `Entry` below change.
inline constexpr plugin::PluginSpec kPlugin{"libexemplar_video_mp4.so",
                                            "exemplar_video_codec_entry", 2, "video support"};

/// A decoded frame: `channels` (1, 3 or 4) interleaved floats per pixel in OpenCV's order (blue
/// first), scaled from 8 or 16 bits to [0, 1].
struct DecodedFrame {
    int width = 0, height = 0, channels = 0;
    std::vector<float> values;
};

/// What `VideoReader::retrieve` found.
enum class Retrieved { Frame, Nothing, UnsupportedSampleType };

/// A video decoder (cv::VideoCapture with the FFmpeg backend).
class VideoReader {
public:
    virtual ~VideoReader() = default;
    /// Opens `path`; false if it cannot be decoded.
    virtual bool open(const std::string& path) = 0;
    virtual bool is_open() const = 0;
    /// Decodes the next frame; false at the end of the video or on a decoding error.
    virtual bool grab() = 0;
    /// The frame decoded by the last `grab()` (8 or 16 bits, grey, BGR or BGRA) as floats.
    virtual Retrieved retrieve(DecodedFrame& frame) = 0;
    virtual void release() = 0;
};

/// An MP4 encoder (cv::VideoWriter, FFmpeg backend, codec "mp4v" = MPEG-4 Part 2).
class VideoWriter {
public:
    virtual ~VideoWriter() = default;
    /// Opens `path` for `width` x `height` colour frames at `fps`; false if the encoder is missing.
    virtual bool open(const std::string& path, double fps, int width, int height) = 0;
    /// Appends one frame of the size given to `open`: 3 bytes (blue, green, red) per pixel.
    virtual void write(const std::uint8_t* bgr) = 0;
    /// Finishes the file.
    virtual void release() = 0;
};

/// What the plugin's entry point returns. `abi_version` comes first so that it can be checked
/// before anything else is read.
struct Entry {
    int abi_version;
    std::unique_ptr<VideoReader> (*new_reader)();
    std::unique_ptr<VideoWriter> (*new_writer)();
};

/// The type of the function the plugin exports as `kPlugin.entry_symbol` (C linkage).
using EntryFunction = const Entry* (*)();

}  // namespace exemplar::video::codec
