// EXR and TIFF files through their codec plugins (codec_plugin.hpp): linked in (libexemplar.so,
// the Python module) or loaded on the first file of the format (the `exemplar` command).

#include <fmt/format.h>

#include "codec_plugin.hpp"
#include "codecs.hpp"

// Defined by exr_plugin.cpp and tiff_plugin.cpp where they are linked in; null in the
// `exemplar` executable.
extern "C" const exemplar::io_detail::codec_plugin::Entry* exemplar_openexr_entry()
    __attribute__((weak));
extern "C" const exemplar::io_detail::codec_plugin::Entry* exemplar_tiff_entry()
    __attribute__((weak));

namespace exemplar::io_detail {

namespace {

using codec_plugin::Entry;

// The plugin of `codec` (Exr or Tiff), or its error naming `file`.
Result<const Entry*> plugin_for(Codec codec, const std::string& file) {
    auto entry = codec == Codec::Exr
                     ? plugin::linked_or_loaded(exemplar_openexr_entry, codec_plugin::kOpenExr)
                     : plugin::linked_or_loaded(exemplar_tiff_entry, codec_plugin::kTiff);
    if (!entry.ok()) return Status(entry.status().code(), file + ": " + entry.status().message());
    return entry;
}

Result<Image> read_with(Codec codec, const std::string& file,
                        const std::vector<std::string>& channels) {
    auto backend = plugin_for(codec, file);
    if (!backend.ok()) return backend.status();
    Image image;
    const codec_plugin::Allocate allocate = [](void* context, int width, int height, int count) {
        Image& out = *static_cast<Image*>(context);
        out = Image(width, height, count);
        return out.data().data();
    };
    std::vector<std::string> names;
    EXEMPLAR_RETURN_IF_ERROR((*backend)->read(file, channels, allocate, &image, &names));
    image.set_channel_names(names);
    return image;
}

Status write_with(Codec codec, const Image& image, const std::string& file,
                  const std::string& shown, PixelFormat format) {
    auto backend = plugin_for(codec, shown);
    if (!backend.ok()) return backend.status();
    return (*backend)->write(image.data().data(), image.width(), image.height(),
                             image.channel_names(), file, shown, format);
}

}  // namespace

Result<std::vector<std::string>> read_exr_channel_names(const std::string& file) {
    auto backend = plugin_for(Codec::Exr, file);
    if (!backend.ok()) return backend.status();
    return (*backend)->channel_names(file);
}

Result<Image> read_exr(const std::string& file, const std::vector<std::string>& channels) {
    return read_with(Codec::Exr, file, channels);
}

Result<Image> read_tiff(const std::string& file) {
    return read_with(Codec::Tiff, file, {});
}

Status write_exr(const Image& image, const std::string& file, const std::string& shown,
                 PixelFormat format) {
    return write_with(Codec::Exr, image, file, shown, format);
}

Status write_tiff(const Image& image, const std::string& file, const std::string& shown,
                  PixelFormat format) {
    return write_with(Codec::Tiff, image, file, shown, format);
}

}  // namespace exemplar::io_detail
