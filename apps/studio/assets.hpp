#pragma once
// The single-page app's files (web/), compiled into the binary by embed_assets.cmake.

#include <span>
#include <string_view>

namespace exemplar::studio {

struct Asset {
    std::string_view path;          ///< URL path, e.g. "/app.js" ("/" for index.html).
    std::string_view content_type;  ///< e.g. "text/javascript; charset=utf-8".
    std::string_view bytes;
};

std::span<const Asset> assets();

}  // namespace exemplar::studio
