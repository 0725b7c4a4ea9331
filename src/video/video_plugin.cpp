// The video codec plugin through the common loader (see video_codec.hpp for why a plugin).

#include "video_plugin.hpp"

#include "plugin_loader.hpp"

namespace exemplar::video::codec {

Result<const Entry*> load_plugin() {
    return plugin::load<Entry>({kPluginFileName, kEntrySymbol, kCodecAbiVersion, "video support"});
}

}  // namespace exemplar::video::codec
