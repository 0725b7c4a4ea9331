// OpenEXR files through the OpenEXR plugin (exr_backend.hpp): linked in (libexemplar.so, the
// Python module) or loaded on the first EXR file (the `exemplar` command).

#include <fmt/format.h>

#include "codecs.hpp"
#include "exr_backend.hpp"
#include "plugin_loader.hpp"

// Defined by exr_plugin.cpp where that is linked in; null in the `exemplar` executable.
extern "C" const exemplar::io_detail::exr::Entry* exemplar_openexr_entry() __attribute__((weak));

namespace exemplar::io_detail {

namespace {

// The plugin, or its error naming `file`.
Result<const exr::Entry*> exr_backend(const std::string& file) {
    if (exemplar_openexr_entry != nullptr) return exemplar_openexr_entry();
    auto entry = plugin::load<exr::Entry>(
        {exr::kPluginFileName, exr::kEntrySymbol, exr::kAbiVersion, "OpenEXR"});
    if (!entry.ok()) return Status(entry.status().code(), file + ": " + entry.status().message());
    return entry;
}

}  // namespace

Result<std::vector<std::string>> read_exr_channel_names(const std::string& file) {
    auto backend = exr_backend(file);
    if (!backend.ok()) return backend.status();
    return (*backend)->channel_names(file);
}

Result<Image> read_exr(const std::string& file, const std::vector<std::string>& channels) {
    auto backend = exr_backend(file);
    if (!backend.ok()) return backend.status();
    Image image;
    const exr::Allocate allocate = [](void* context, int width, int height, int count) {
        Image& out = *static_cast<Image*>(context);
        out = Image(width, height, count);
        return out.data().data();
    };
    std::vector<std::string> names;
    EXEMPLAR_RETURN_IF_ERROR((*backend)->read(file, channels, allocate, &image, &names));
    image.set_channel_names(names);
    return image;
}

Status write_exr(const Image& image, const std::string& file, const std::string& shown,
                 PixelFormat format) {
    auto backend = exr_backend(shown);
    if (!backend.ok()) return backend.status();
    return (*backend)->write(image.data().data(), image.width(), image.height(),
                             image.channel_names(), file, format != PixelFormat::Float);
}

}  // namespace exemplar::io_detail
