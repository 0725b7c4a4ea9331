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

/// The conventional channel names for `count` channels of an integer file: Y, Y A, R G B,
/// R G B A, then "channel4", "channel5", ... for extra channels.
std::vector<std::string> default_channel_names(int count);

}  // namespace exemplar::io_detail
