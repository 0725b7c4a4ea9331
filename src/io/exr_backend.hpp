#pragma once
// The interface between exemplar::io and its OpenEXR plugin, libexemplar_openexr.so
// (exr_plugin.cpp): the only code that uses the OpenEXR library. Linking OpenEXR, Iex, Imath
// and IlmThread costs every process about 1.9 MB resident before main() runs, so `exemplar`
// loads the plugin on the first EXR file instead (src/plugin/plugin_loader.hpp); libexemplar.so
// and the Python module link it in. Errors are Status values (header-only); OpenEXR's own errors
// are exceptions, caught by image_io.cpp as for every codec. Both sides are compiled from this
// header by one build; kAbiVersion rejects a plugin from another build.

#include <string>
#include <vector>

#include "exemplar/core/status.hpp"

namespace exemplar::io_detail::exr {

/// Raise whenever the types below change.
inline constexpr int kAbiVersion = 1;
inline constexpr const char* kPluginFileName = "libexemplar_openexr.so";
inline constexpr const char* kEntrySymbol = "exemplar_openexr_entry";

/// Memory for `width` x `height` pixels of `channels` interleaved floats, from the caller.
using Allocate = float* (*)(void* context, int width, int height, int channels);

/// What the plugin's entry point returns; `abi_version` first (plugin_loader.hpp).
struct Entry {
    int abi_version;
    /// Channel names in reading order (codecs.hpp: read_exr_channel_names).
    Result<std::vector<std::string>> (*channel_names)(const std::string& file);
    /// The named channels (every channel if `channels` is empty) into `allocate`'s memory; their
    /// names into `names`.
    Status (*read)(const std::string& file, const std::vector<std::string>& channels,
                   Allocate allocate, void* context, std::vector<std::string>* names);
    /// A scanline, ZIP-compressed file of half (else float) channels.
    Status (*write)(const float* values, int width, int height,
                    const std::vector<std::string>& names, const std::string& file, bool half);
};

}  // namespace exemplar::io_detail::exr
