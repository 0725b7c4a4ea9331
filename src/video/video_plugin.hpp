#pragma once
// Finding and loading the video codec plugin (video_codec.hpp) on first use.

#include <filesystem>
#include <vector>

#include "exemplar/core/status.hpp"
#include "video_codec.hpp"

namespace exemplar::video::codec {

/// The environment variable that, when set and not empty, names the only folder searched for
/// the plugin (tests point it at the build tree, or at an empty folder).
inline constexpr const char* kPluginDirVariable = "EXEMPLAR_PLUGIN_DIR";

/// The folders searched for the plugin, in order: `$EXEMPLAR_PLUGIN_DIR` alone if it is set and
/// not empty; otherwise the folder of the binary that holds exemplar::video (the executable, as
/// the library is linked statically: the build tree keeps the plugin next to `exemplar`), then
/// that folder joined with EXEMPLAR_PLUGIN_RELATIVE_DIR (the install layout: `bin/exemplar`
/// finds `lib/exemplar/libexemplar_video_mp4.so`).
std::vector<std::filesystem::path> plugin_folders();

/// The codec plugin, loaded from the first of `plugin_folders()` that holds it on the first call
/// (thread-safe) and kept for the life of the process; later calls return the same plugin or the
/// same error. Unsupported `video support is not available (libexemplar_video_mp4.so: <reason>)`
/// if it is missing, cannot be loaded (the reason is dlerror's) or comes from another build;
/// callers put the name of the video file in front.
Result<const Entry*> load_plugin();

}  // namespace exemplar::video::codec
