#pragma once
// Structural validation of PNG files before they reach libpng.
//
// OpenImageIO 2.4 installs a libpng error handler that returns instead of jumping, so libpng
// falls back to its default handler and prints "libpng error: ..." to stderr for every truncated
// or corrupt PNG. The library must never print, so PNG files are checked here first: a file that
// passes has a valid signature, well-formed chunks with correct CRCs, a sane IHDR and the chunk
// order libpng requires. What remains possible (a valid-CRC chunk holding a broken zlib stream)
// is only produced by a buggy encoder, not by truncation or bit rot.

#include <string>
#include <string_view>

namespace exemplar::io_detail {

/// True if `bytes` starts with the 8-byte PNG signature.
bool has_png_signature(std::string_view bytes);

/// Checks a whole PNG file held in memory. Returns "" if it is well-formed, otherwise a one-line
/// description of the first problem ("truncated: chunk IDAT at byte 91 runs past the end").
std::string check_png(std::string_view bytes);

}  // namespace exemplar::io_detail
