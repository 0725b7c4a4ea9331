#pragma once
// The image file formats, each on its own reference library (libpng, libjpeg-turbo, libtiff,
// OpenEXR; PNM by hand, it is a text header and raw samples). image_io.cpp chooses the codec
// and checks requests against what a format can store; a codec only moves pixels.
//
// Contract of every function here: errors are returned as one-line Status values that start
// with `shown` (the path the user gave; writers write to a temporary file `file` instead);
// nothing is printed; C library errors never longjmp past C++ objects (each codec keeps its
// setjmp in a function without them). Readers return every channel as float in [0, 1] for
// integer files (v / max), float data as stored; channel names as the format defines them.

#include <fmt/format.h>

#include <cstdio>
#include <string>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/status.hpp"
#include "exemplar/io/image_io.hpp"

namespace exemplar::io_detail {

enum class Codec { Png, Jpeg, Tiff, Exr, Pnm };

/// The codec whose signature starts `bytes` (the first 8 bytes of a file, or fewer), if any.
bool codec_from_signature(const std::string& bytes, Codec& codec);

Result<Image> read_png(const std::string& file);
Result<Image> read_jpeg(const std::string& file);
Result<Image> read_tiff(const std::string& file);
Result<Image> read_pnm(const std::string& file);

/// EXR channel names in reading order (a file stores them sorted by name): layers ("" first)
/// in byte order; within a layer colour, alpha and depth first (R G B A Z) and in a vector
/// layer X Y Z W, then the others by name, as OpenImageIO orders them (see codec_exr.cpp).
Result<std::vector<std::string>> read_exr_channel_names(const std::string& file);
/// The named channels of an EXR file (names as read_exr_channel_names gives them), in the order
/// given; every channel if `channels` is empty.
Result<Image> read_exr(const std::string& file, const std::vector<std::string>& channels);

/// Writers. `format` is already checked against the format's rules (never Auto); integer
/// formats get values clamped to [0, 1] and NaN as 0 (to_level).
Status write_png(const Image& image, const std::string& file, const std::string& shown,
                 PixelFormat format);
Status write_jpeg(const Image& image, const std::string& file, const std::string& shown,
                  int quality);
Status write_tiff(const Image& image, const std::string& file, const std::string& shown,
                  PixelFormat format);
Status write_exr(const Image& image, const std::string& file, const std::string& shown,
                 PixelFormat format);
Status write_pnm(const Image& image, const std::string& file, const std::string& shown);

/// An integer sample for a float value: clamped to [0, 1] (NaN as 0), scaled by `max`, rounded
/// to the nearest level.
inline unsigned to_level(float v, unsigned max) {
    if (!(v > 0.0f)) return 0;  // also NaN
    if (v >= 1.0f) return max;
    return static_cast<unsigned>(static_cast<double>(v) * max + 0.5);
}

/// Integer samples (8 or 16 bits, native byte order) as values in [0, 1].
void samples_to_floats(const unsigned char* samples, int bits, std::size_t count, float* out);
/// Values as integer samples (8 or 16 bits, native byte order): to_level of each.
void floats_to_samples(const float* values, std::size_t count, int bits, unsigned char* out);

/// Runs a C library codec on a file: opens `file` with `mode` ("rb" or "wb") into `handle`,
/// calls `codec()` (false on failure, with its reason in the buffer `message` by then), closes
/// it. Errors name `shown`: "<shown>: cannot read PNG: <message>".
template <class Codec>
Status run_file_codec(const std::string& file, const std::string& shown, const char* mode,
                      const char* label, std::FILE*& handle, const char* message, Codec&& codec) {
    const bool reading = mode[0] == 'r';
    handle = std::fopen(file.c_str(), mode);
    if (handle == nullptr) {
        return io_error(fmt::format("{}: cannot {}", shown, reading ? "open" : "write"));
    }
    const bool ok = codec();
    const bool closed = std::fclose(handle) == 0;
    handle = nullptr;
    if (!ok) {
        return io_error(
            fmt::format("{}: cannot {} {}: {}", shown, reading ? "read" : "write", label, message));
    }
    if (!closed && !reading) {
        return io_error(fmt::format("{}: cannot write: disk full or I/O error", shown));
    }
    return Status::ok();
}

/// The conventional channel names for `count` channels of an integer file: Y, Y A, R G B,
/// R G B A, then "channel4", "channel5", ... for extra channels.
std::vector<std::string> default_channel_names(int count);

}  // namespace exemplar::io_detail
