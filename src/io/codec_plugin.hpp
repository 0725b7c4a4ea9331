#pragma once
// The interface between exemplar::io and its two codec plugins, libexemplar_openexr.so
// (exr_plugin.cpp) and libexemplar_tiff.so (tiff_plugin.cpp): the only code that uses OpenEXR
// and libtiff. Linking OpenEXR (with Iex and IlmThread) costs every process about 1.9 MB
// resident before main() runs, libtiff with its compressors (Lerc, zstd, lzma, deflate, webp,
// jbig) 0.75 MB, so `exemplar` loads each plugin on the first file of its format instead
// (src/plugin/plugin_loader.hpp; codec_plugins.cpp); libexemplar.so and the Python module link
// them in. Errors are Status values (header-only); OpenEXR's own errors are exceptions, caught by
// image_io.cpp as for every codec. Both sides are compiled from this header by one build;
// abi_version rejects a plugin from another build. The plugins link no exemplar library.

#include <string>
#include <vector>

#include "exemplar/core/status.hpp"
#include "exemplar/io/image_io.hpp"
#include "plugin_loader.hpp"

namespace exemplar::io_detail::codec_plugin {

/// The plugins; raise abi_version whenever the types below change.
inline constexpr plugin::PluginSpec kOpenExr{"libexemplar_openexr.so", "exemplar_openexr_entry", 1,
                                             "OpenEXR"};
inline constexpr plugin::PluginSpec kTiff{"libexemplar_tiff.so", "exemplar_tiff_entry", 1,
                                          "libtiff"};

/// Memory for `width` x `height` pixels of `channels` interleaved floats, from the caller.
using Allocate = float* (*)(void* context, int width, int height, int channels);

/// What a codec plugin's entry point returns; `abi_version` first (plugin_loader.hpp). The
/// contract of codecs.hpp holds: messages start with the file name, values as codecs.hpp says.
struct Entry {
    int abi_version;
    /// Channel names in reading order without decoding the pixels; null if the format has none
    /// (EXR: codecs.hpp read_exr_channel_names).
    Result<std::vector<std::string>> (*channel_names)(const std::string& file);
    /// The named channels (every channel if `channels` is empty; a format without channel names
    /// reads all) into `allocate`'s memory, their names into `names`.
    Status (*read)(const std::string& file, const std::vector<std::string>& channels,
                   Allocate allocate, void* context, std::vector<std::string>* names);
    /// Writes `width` x `height` pixels of `names.size()` channels to `file` (`shown` in
    /// messages) in `format`, already checked against the format's rules.
    Status (*write)(const float* values, int width, int height,
                    const std::vector<std::string>& names, const std::string& file,
                    const std::string& shown, PixelFormat format);
};

}  // namespace exemplar::io_detail::codec_plugin
