#pragma once
// Structural validation of PNG files before they reach libpng.
//
// libpng reports damage tersely ("Read Error", "IDAT: CRC error") and only once it reaches it.
// PNG files are checked here first, so the one-line error says what is wrong and where: a file
// that passes has a valid signature, well-formed chunks with correct CRCs, a sane IHDR and the
// chunk order libpng requires. What remains possible (a valid-CRC chunk holding a broken zlib
// stream) is only produced by a buggy encoder, not by truncation or bit rot, and gets libpng's
// message (codec_png.cpp; libpng never prints).

#include <string>
#include <string_view>

namespace exemplar::io_detail {

/// True if `bytes` starts with the 8-byte PNG signature.
bool has_png_signature(std::string_view bytes);

/// Checks a whole PNG file held in memory. Returns "" if it is well-formed, otherwise a one-line
/// description of the first problem ("truncated: chunk IDAT at byte 91 runs past the end").
std::string check_png(std::string_view bytes);

}  // namespace exemplar::io_detail
