// Image files: the format is chosen by content on reading and by extension on writing, and each
// format is handled by its reference library (codecs.hpp). This file adds what the library
// promises on top of them:
// - errors are Status values of one line naming the file, and no exception leaves this file:
//   every public function catches them (OpenEXR reports errors as exceptions; std::bad_alloc);
// - nothing is printed, and damaged PNG files get a precise reason (png_check.hpp);
// - alpha is kept unassociated: colour values are never multiplied or divided by alpha;
// - each output format accepts only the channel counts and sample formats it can store; anything
//   else is rejected instead of being converted silently;
// - writes are atomic (atomic_file.hpp).
//
// OpenImageIO did all of this until 2026-11: it links about 260 libraries that cost 130 MB of
// resident memory and 0.15 s in every process before main() (docs/PERFORMANCE.md), for the
// five formats used here.

#include "exemplar/io/image_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <new>
#include <set>
#include <system_error>
#include <utility>

#include "atomic_file.hpp"
#include "codecs.hpp"
#include "png_check.hpp"

namespace exemplar {

namespace {

namespace fs = std::filesystem;
using io_detail::Codec;
using io_detail::TempFile;

constexpr const char* kKnownExtensions = ".png, .jpg, .tif, .exr, .ppm or .pgm";

// Joins the lines of a library's message into one ("a; b") and trims it.
std::string one_line(const std::string& text) {
    std::string out;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t end = text.find_first_of("\r\n", start);
        if (end == std::string::npos) end = text.size();
        std::string line = text.substr(start, end - start);
        const auto first = line.find_first_not_of(" \t");
        const auto last = line.find_last_not_of(" \t");
        if (first != std::string::npos) {
            line = line.substr(first, last - first + 1);
            if (!out.empty()) out.append("; ");
            out.append(line);
        }
        start = end + 1;
    }
    return out;
}

// Runs `body`, turning any exception into an error naming `path`: the public functions never
// throw.
template <typename Body>
auto guarded(const std::string& path, Body&& body) -> decltype(body()) {
    try {
        return body();
    } catch (const std::bad_alloc&) {
        return io_error(fmt::format("{}: out of memory", path));
    } catch (const std::exception& e) {
        return io_error(fmt::format("{}: {}", path, one_line(e.what())));
    } catch (...) {
        return io_error(fmt::format("{}: unknown error", path));
    }
}

// ---------------------------------------------------------------------------------------------
// Reading

// Checks that `path` is a readable, non-empty file (PNG files also for damage) and finds its
// codec from its first bytes.
Result<Codec> open_codec(const std::string& path) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (ec && ec != std::errc::no_such_file_or_directory) {
        return io_error(fmt::format("{}: cannot access: {}", path, ec.message()));
    }
    if (!fs::exists(st)) return io_error(fmt::format("{}: no such file", path));
    if (fs::is_directory(st)) {
        return io_error(fmt::format("{}: is a folder, not an image file", path));
    }
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (file == nullptr) {
        return io_error(
            fmt::format("{}: cannot open: {}", path, std::generic_category().message(errno)));
    }
    std::string bytes(8, '\0');
    bytes.resize(std::fread(bytes.data(), 1, bytes.size(), file));
    std::string problem = bytes.empty() ? "file is empty" : "";
    if (io_detail::has_png_signature(bytes)) {
        // Whole file, for the CRC check. PNGs are compressed, so this is small next to the
        // decoded image.
        std::string whole = bytes;
        std::vector<char> buffer(std::size_t{1} << 16);
        std::size_t n = 0;
        while ((n = std::fread(buffer.data(), 1, buffer.size(), file)) > 0) {
            whole.append(buffer.data(), n);
        }
        problem = io_detail::check_png(whole);
    }
    const bool read_failed = std::ferror(file) != 0;
    std::fclose(file);
    if (read_failed) return io_error(fmt::format("{}: read error", path));
    if (!problem.empty()) return io_error(fmt::format("{}: {}", path, problem));
    Codec codec{};
    if (io_detail::codec_from_signature(bytes, codec)) return codec;
    // No format recognizes the content. If the extension names a known format, the file is
    // damaged; otherwise the format is unknown.
    static const std::set<std::string> kKnown = {".png", ".jpg", ".jpeg", ".tif", ".tiff",
                                                 ".exr", ".ppm", ".pgm",  ".pbm", ".pnm"};
    const std::string extension = lowercase_extension(path);
    if (kKnown.count(extension) == 0) {
        return unsupported(
            fmt::format("{}: unknown or unsupported image format (exemplar reads "
                        "PNG, JPEG, TIFF, OpenEXR and PNM files)",
                        path));
    }
    return io_error(fmt::format("{}: cannot read image: not a valid {} file", path, extension));
}

// Every channel of the file.
Result<Image> read_all(const std::string& path, Codec codec) {
    switch (codec) {
        case Codec::Png: return io_detail::read_png(path);
        case Codec::Jpeg: return io_detail::read_jpeg(path);
        case Codec::Tiff: return io_detail::read_tiff(path);
        case Codec::Exr: return io_detail::read_exr(path, {});
        case Codec::Pnm: return io_detail::read_pnm(path);
    }
    return unsupported(fmt::format("{}: unknown image format", path));
}

// Channel names of the file (EXR from its header, the others by decoding).
Result<std::vector<std::string>> channel_names_of(const std::string& path, Codec codec) {
    if (codec == Codec::Exr) return io_detail::read_exr_channel_names(path);
    auto image = read_all(path, codec);
    if (!image.ok()) return image.status();
    return image->channel_names();
}

// Layer of a channel name: the part before the last '.', or "" if there is no dot.
std::string layer_of(const std::string& channel) {
    const auto dot = channel.rfind('.');
    return dot == std::string::npos ? std::string() : channel.substr(0, dot);
}

// Name of a channel within its layer: the part after the last '.'.
std::string name_in_layer(const std::string& channel) {
    const auto dot = channel.rfind('.');
    return dot == std::string::npos ? channel : channel.substr(dot + 1);
}

std::vector<std::string> layers_of(const std::vector<std::string>& channels) {
    std::vector<std::string> layers;
    bool unnamed = false;
    for (const std::string& channel : channels) {
        std::string layer = layer_of(channel);
        if (layer.empty()) {
            unnamed = true;
        } else if (std::find(layers.begin(), layers.end(), layer) == layers.end()) {
            layers.push_back(std::move(layer));
        }
    }
    if (unnamed) layers.insert(layers.begin(), std::string());
    return layers;
}

std::string quoted_list(const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& item : items) {
        if (!out.empty()) out.append(", ");
        out.append(fmt::format("\"{}\"", item));
    }
    return out.empty() ? std::string("none") : out;
}

// ---------------------------------------------------------------------------------------------
// Writing

// What an output format can hold.
struct FormatRules {
    Codec codec;
    std::string label;                 ///< Format name for messages ("PNG").
    std::vector<int> channel_counts;   ///< Storable channel counts; empty: any.
    std::vector<PixelFormat> formats;  ///< Storable sample formats.
    PixelFormat natural = PixelFormat::Auto;
    bool named_channels = false;  ///< Stores channel names (so they must be unique).
};

// The format written for a (lowercase) extension; false if there is none.
bool rules_for(const std::string& extension, FormatRules& rules) {
    using P = PixelFormat;
    if (extension == ".png") {
        rules = {Codec::Png, "PNG", {1, 2, 3, 4}, {P::UInt8, P::UInt16}, P::UInt8, false};
    } else if (extension == ".jpg" || extension == ".jpeg") {
        rules = {Codec::Jpeg, "JPEG", {1, 3}, {P::UInt8}, P::UInt8, false};
    } else if (extension == ".tif" || extension == ".tiff") {
        // Half-float TIFF is valid but few readers support it, so it is not offered.
        rules = {Codec::Tiff, "TIFF", {}, {P::UInt8, P::UInt16, P::Float}, P::UInt16, false};
    } else if (extension == ".exr") {
        rules = {Codec::Exr, "EXR", {}, {P::Half, P::Float}, P::Half, true};
    } else if (extension == ".ppm") {
        rules = {Codec::Pnm, "PPM", {3}, {P::UInt8}, P::UInt8, false};
    } else if (extension == ".pgm") {
        rules = {Codec::Pnm, "PGM", {1}, {P::UInt8}, P::UInt8, false};
    } else if (extension == ".pnm") {
        rules = {Codec::Pnm, "PNM", {1, 3}, {P::UInt8}, P::UInt8, false};
    } else {
        return false;
    }
    return true;
}

const char* describe(PixelFormat format) {
    switch (format) {
        case PixelFormat::Auto: return "automatic";
        case PixelFormat::UInt8: return "8-bit";
        case PixelFormat::UInt16: return "16-bit";
        case PixelFormat::Half: return "half-float";
        case PixelFormat::Float: return "float";
    }
    return "unknown";
}

std::string join_counts(const std::vector<int>& counts) {
    std::string out;
    for (std::size_t i = 0; i < counts.size(); ++i) {
        if (i > 0) out.append(i + 1 == counts.size() ? " or " : ", ");
        out.append(std::to_string(counts[i]));
    }
    return out;
}

std::string join_formats(const std::vector<PixelFormat>& formats) {
    std::string out;
    for (std::size_t i = 0; i < formats.size(); ++i) {
        if (i > 0) out.append(i + 1 == formats.size() ? " or " : ", ");
        out.append(describe(formats[i]));
    }
    return out;
}

Status write_file(const Image& image, const std::string& path, const SaveOptions& options) {
    if (options.jpeg_quality < 1 || options.jpeg_quality > 100) {
        return invalid_argument(fmt::format("{}: jpeg_quality: {} is invalid (must be 1..100)",
                                            path, options.jpeg_quality));
    }
    if (image.empty()) {
        return invalid_argument(fmt::format("{}: cannot save an empty image ({}x{}, {} channels)",
                                            path, image.width(), image.height(), image.channels()));
    }
    const std::string extension = lowercase_extension(path);
    if (extension.empty()) {
        return unsupported(
            fmt::format("{}: no file extension to choose the image format from (use {})", path,
                        kKnownExtensions));
    }
    FormatRules rules;
    if (!rules_for(extension, rules)) {
        return unsupported(fmt::format("{}: unknown image file extension \"{}\" (use {})", path,
                                       extension, kKnownExtensions));
    }

    // Check the request against what the format can hold.
    const int channels = image.channels();
    if (!rules.channel_counts.empty() &&
        std::find(rules.channel_counts.begin(), rules.channel_counts.end(), channels) ==
            rules.channel_counts.end()) {
        return unsupported(fmt::format(
            "{}: {} cannot store {} channels (only {}); use .tif or .exr for other channel counts",
            path, rules.label, channels, join_counts(rules.channel_counts)));
    }
    const PixelFormat format = options.format == PixelFormat::Auto ? rules.natural : options.format;
    if (!rules.formats.empty() &&
        std::find(rules.formats.begin(), rules.formats.end(), format) == rules.formats.end()) {
        return unsupported(fmt::format("{}: {} cannot store {} samples (only {})", path,
                                       rules.label, describe(format), join_formats(rules.formats)));
    }
    if (rules.named_channels) {
        std::set<std::string> seen;
        for (const std::string& name : image.channel_names()) {
            if (name.empty()) {
                return invalid_argument(fmt::format("{}: a channel has an empty name", path));
            }
            if (!seen.insert(name).second) {
                return invalid_argument(
                    fmt::format("{}: channel name \"{}\" is used twice", path, name));
            }
        }
    }

    // Write the temporary file.
    TempFile temp(path);
    EXEMPLAR_RETURN_IF_ERROR(temp.status());
    Status written;
    switch (rules.codec) {
        case Codec::Png: written = io_detail::write_png(image, temp.path(), path, format); break;
        case Codec::Jpeg:
            written = io_detail::write_jpeg(image, temp.path(), path, options.jpeg_quality);
            break;
        case Codec::Tiff: written = io_detail::write_tiff(image, temp.path(), path, format); break;
        case Codec::Exr: written = io_detail::write_exr(image, temp.path(), path, format); break;
        case Codec::Pnm: written = io_detail::write_pnm(image, temp.path(), path); break;
    }
    EXEMPLAR_RETURN_IF_ERROR(written);
    return temp.commit();
}

}  // namespace

std::string lowercase_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    return ext;
}

Result<Image> load_image(const std::string& path) {
    return guarded(path, [&]() -> Result<Image> {
        auto codec = open_codec(path);
        if (!codec.ok()) return codec.status();
        return read_all(path, *codec);
    });
}

Result<Image> load_image_layer(const std::string& path, const std::string& layer) {
    return guarded(path, [&]() -> Result<Image> {
        auto codec = open_codec(path);
        if (!codec.ok()) return codec.status();
        auto names = channel_names_of(path, *codec);
        if (!names.ok()) return names.status();
        std::vector<std::string> selected;
        std::vector<int> indices;
        std::vector<std::string> short_names;
        for (int c = 0; c < static_cast<int>(names->size()); ++c) {
            const std::string& name = (*names)[static_cast<std::size_t>(c)];
            const bool whole = !layer.empty() && name == layer;  // single-channel layer
            if (whole || layer_of(name) == layer) {
                selected.push_back(name);
                indices.push_back(c);
                short_names.push_back(name_in_layer(name));
            }
        }
        if (selected.empty()) {
            return io_error(fmt::format("{}: layer \"{}\" not found (layers in the file: {})", path,
                                        layer, quoted_list(layers_of(*names))));
        }
        // EXR reads just the layer's channels; the other formats have one layer.
        Result<Image> image =
            *codec == Codec::Exr ? io_detail::read_exr(path, selected) : read_all(path, *codec);
        if (!image.ok()) return image;
        if (*codec != Codec::Exr && selected.size() != names->size()) {
            image = select_channels(*image, indices);
        }
        image->set_channel_names(std::move(short_names));
        return image;
    });
}

Result<std::vector<std::string>> read_channel_names(const std::string& path) {
    return guarded(path, [&]() -> Result<std::vector<std::string>> {
        auto codec = open_codec(path);
        if (!codec.ok()) return codec.status();
        return channel_names_of(path, *codec);
    });
}

Result<std::vector<std::string>> read_layer_names(const std::string& path) {
    return guarded(path, [&]() -> Result<std::vector<std::string>> {
        auto names = read_channel_names(path);
        if (!names.ok()) return names.status();
        return layers_of(*names);
    });
}

Status save_image(const Image& image, const std::string& path, const SaveOptions& options) {
    return guarded(path, [&] { return write_file(image, path, options); });
}

Status save_exr_layers(const std::vector<std::pair<std::string, const Image*>>& layers,
                       const std::string& path, const SaveOptions& options) {
    return guarded(path, [&]() -> Status {
        if (lowercase_extension(path) != ".exr") {
            return unsupported(
                fmt::format("{}: multi-layer images can only be saved as .exr", path));
        }
        if (layers.empty()) return invalid_argument(fmt::format("{}: no layers to save", path));
        std::vector<const Image*> images;
        std::vector<std::string> names;
        for (const auto& [layer, image] : layers) {
            if (image == nullptr || image->empty()) {
                return invalid_argument(
                    fmt::format("{}: layer \"{}\" has no image data", path, layer));
            }
            const Image& first = *layers.front().second;
            if (!image->same_size(first)) {
                return invalid_argument(fmt::format(
                    "{}: layer \"{}\" is {}x{} but layer \"{}\" is {}x{} (all layers must have "
                    "the same size)",
                    path, layer, image->width(), image->height(), layers.front().first,
                    first.width(), first.height()));
            }
            images.push_back(image);
            for (const std::string& channel : image->channel_names()) {
                names.push_back(layer.empty() ? channel : fmt::format("{}.{}", layer, channel));
            }
        }
        Image combined = concat_channels(images);
        combined.set_channel_names(std::move(names));
        return write_file(combined, path, options);
    });
}

}  // namespace exemplar
