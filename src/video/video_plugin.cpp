// The video codec plugin through the common loader (see video_codec.hpp for why a plugin).

#include "video_plugin.hpp"

namespace exemplar::video::codec {

Result<const Entry*> load_plugin() {
    return plugin::load<Entry>(kPlugin);
}

}  // namespace exemplar::video::codec
