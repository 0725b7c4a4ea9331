#pragma once
/// \file
/// Writing bytes atomically: a temporary file in the destination's folder
/// (".<stem>.tmp-XXXXXX<ext>"), renamed onto the destination, so readers see the old file or the
/// complete new one, never a half-written file, and a failed write leaves nothing behind.

#include <string>
#include <string_view>

#include "exemplar/core/status.hpp"

namespace exemplar {

/// Writes `bytes` to `path` atomically, creating missing parent folders. IoError names the file
/// and the reason (`out/a.json: cannot write (disk full or not writable)`).
Status write_file_atomically(std::string_view bytes, const std::string& path);

}  // namespace exemplar
