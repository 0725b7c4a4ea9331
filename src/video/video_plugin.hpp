#pragma once
// Loading the video codec plugin (video_codec.hpp) on first use (src/plugin/plugin_loader.hpp).

#include "exemplar/core/status.hpp"
#include "video_codec.hpp"

namespace exemplar::video::codec {

/// The codec plugin, loaded on the first call and kept for the life of the process; later calls
/// return the same plugin or the same error. Unsupported `video support is not available
/// (libexemplar_video_mp4.so: <reason>)` if it is missing, cannot be loaded or comes from
/// another build; callers put the name of the video file in front.
Result<const Entry*> load_plugin();

}  // namespace exemplar::video::codec
