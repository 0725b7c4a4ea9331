// Image files through OpenImageIO.
//
// OpenImageIO does most of the work; this file adds what the library promises on top of it:
// - errors are Status values of one line naming the file (OIIO's messages may span lines), and
//   no exception leaves this file: every public function catches them (e.g. std::bad_alloc);
// - nothing is printed: OIIO errors are always retrieved (so none is left pending), and PNG files
//   are validated before libpng sees them (see png_check.hpp);
// - alpha is kept unassociated (OIIO would premultiply PNG/TIFF alpha on read and divide on write);
// - each output format accepts only the channel counts and sample formats it can store; anything
//   else is rejected instead of being converted silently (OIIO would write a 5-channel image to
//   JPEG as RGB, or floats to PNG as 8-bit);
// - writes are atomic (atomic_file.hpp).

#include "exemplar/io/image_io.hpp"

#include <OpenImageIO/imageio.h>
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
#include "png_check.hpp"

namespace exemplar {

namespace {

namespace fs = std::filesystem;
using io_detail::TempFile;

constexpr const char* kKnownExtensions = ".png, .jpg, .tif, .exr, .ppm or .pgm";

// Joins the lines of an OpenImageIO message into one ("a; b") and trims it.
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

std::string lowercase_extension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    return ext;
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

// Checks what OIIO reports badly or not at all: missing files, folders, permissions, and PNG
// files that would make libpng print to stderr.
Status check_readable(const std::string& path) {
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
        std::vector<char> buffer(std::size_t{1} << 16);
        std::size_t n = 0;
        while ((n = std::fread(buffer.data(), 1, buffer.size(), file)) > 0) {
            bytes.append(buffer.data(), n);
        }
        problem = io_detail::check_png(bytes);
    }
    const bool read_failed = std::ferror(file) != 0;
    std::fclose(file);
    if (read_failed) return io_error(fmt::format("{}: read error", path));
    if (!problem.empty()) return io_error(fmt::format("{}: {}", path, problem));
    return Status::ok();
}

// Opens `path` for reading with alpha left unassociated, and checks that it is an ordinary 2D
// image.
Result<std::unique_ptr<OIIO::ImageInput>> open_input(const std::string& path) {
    EXEMPLAR_RETURN_IF_ERROR(check_readable(path));
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path, &config);
    if (!in) {
        const std::string error = one_line(OIIO::geterror());
        if (error.find("could not find a format reader") != std::string::npos) {
            // No reader accepted the file. If one exists for its extension, the file is damaged;
            // otherwise the format is unknown.
            if (!OIIO::ImageInput::create(path, false)) {
                OIIO::geterror();
                return unsupported(fmt::format("{}: unknown or unsupported image format", path));
            }
            return io_error(fmt::format("{}: cannot read image: not a valid {} file", path,
                                        lowercase_extension(path)));
        }
        return io_error(fmt::format("{}: cannot read image: {}", path,
                                    error.empty() ? "unknown error" : error));
    }
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.deep) return unsupported(fmt::format("{}: deep images are not supported", path));
    if (spec.depth > 1)
        return unsupported(fmt::format("{}: volume images are not supported", path));
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
        return io_error(fmt::format("{}: corrupt: image is {}x{} with {} channels", path,
                                    spec.width, spec.height, spec.nchannels));
    }
    return in;
}

// Reads channels `channels` (indices into the file's channels, ascending) of the first subimage.
Result<Image> read_channels(OIIO::ImageInput& in, const std::string& path,
                            const std::vector<int>& channels) {
    const OIIO::ImageSpec& spec = in.spec();
    const int first = channels.front();
    const int count = channels.back() - first + 1;
    Image block(spec.width, spec.height, count);
    if (!in.read_image(0, 0, first, first + count, OIIO::TypeDesc::FLOAT, block.data().data())) {
        const std::string error = one_line(in.geterror());
        return io_error(fmt::format("{}: cannot read pixels: {}", path,
                                    error.empty() ? "file is truncated or corrupt" : error));
    }
    std::vector<std::string> names;
    for (int c = first; c < first + count; ++c) {
        names.push_back(c < static_cast<int>(spec.channelnames.size()) &&
                                !spec.channelnames[static_cast<std::size_t>(c)].empty()
                            ? spec.channelnames[static_cast<std::size_t>(c)]
                            : fmt::format("c{}", c));
    }
    block.set_channel_names(std::move(names));
    if (static_cast<int>(channels.size()) == count) return block;

    // Keep only the requested channels of the contiguous block.
    std::vector<int> in_block;
    for (int c : channels) in_block.push_back(c - first);
    return select_channels(block, in_block);
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

// What an output format can hold. Empty lists mean "whatever OpenImageIO accepts".
struct FormatRules {
    std::string label;                 ///< Format name for messages ("PNG").
    std::vector<int> channel_counts;   ///< Storable channel counts.
    std::vector<PixelFormat> formats;  ///< Storable sample formats.
    PixelFormat natural = PixelFormat::Auto;
    bool named_channels = false;  ///< Stores channel names (so they must be unique).
};

FormatRules rules_for(const std::string& format_name, const std::string& extension) {
    using P = PixelFormat;
    if (format_name == "png") return {"PNG", {1, 2, 3, 4}, {P::UInt8, P::UInt16}, P::UInt8, false};
    if (format_name == "jpeg") return {"JPEG", {1, 3}, {P::UInt8}, P::UInt8, false};
    if (format_name == "tiff") {
        // OIIO 2.4 writes half-float TIFF as 32-bit float, so Half is not offered.
        return {"TIFF", {}, {P::UInt8, P::UInt16, P::Float}, P::UInt16, false};
    }
    if (format_name == "openexr") return {"EXR", {}, {P::Half, P::Float}, P::Half, true};
    if (format_name == "pnm") {
        // OIIO picks PGM or PPM from the channel count, whatever the extension says. Its 2.4
        // writer declares 16-bit files but fills them from 8-bit data, so only 8-bit is offered
        // (16-bit PNM files are read correctly).
        std::vector<int> counts = {1, 3};
        if (extension == ".pgm" || extension == ".pbm") counts = {1};
        if (extension == ".ppm") counts = {3};
        std::string label = extension.size() > 1 ? extension.substr(1) : "PNM";
        std::transform(label.begin(), label.end(), label.begin(),
                       [](unsigned char ch) { return static_cast<char>(std::toupper(ch)); });
        return {label, counts, {P::UInt8}, P::UInt8, false};
    }
    std::string label = format_name;
    std::transform(label.begin(), label.end(), label.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::toupper(ch)); });
    return {label, {}, {}, P::Auto, false};
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

OIIO::TypeDesc type_of(PixelFormat format) {
    switch (format) {
        case PixelFormat::UInt8: return OIIO::TypeDesc::UINT8;
        case PixelFormat::UInt16: return OIIO::TypeDesc::UINT16;
        case PixelFormat::Half: return OIIO::TypeDesc::HALF;
        case PixelFormat::Float:
        case PixelFormat::Auto: break;
    }
    return OIIO::TypeDesc::FLOAT;
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

// Values for an integer file: clamped to [0, 1], NaN written as 0.
std::vector<float> clamped_copy(const Image& image) {
    std::vector<float> values(image.data().begin(), image.data().end());
    for (float& v : values) v = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
    return values;
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
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path);
    if (!out) {
        OIIO::geterror();  // consume OIIO's message: ours says the same in one line
        return unsupported(fmt::format("{}: unknown image file extension \"{}\" (use {})", path,
                                       extension, kKnownExtensions));
    }

    // Check the request against what the format can hold.
    const FormatRules rules = rules_for(out->format_name(), extension);
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

    OIIO::ImageSpec spec(image.width(), image.height(), channels, type_of(format));
    spec.channelnames = image.channel_names();
    spec.alpha_channel = find_channel(image, "A");
    spec.attribute("oiio:UnassociatedAlpha", 1);
    if (format == PixelFormat::UInt8 || format == PixelFormat::UInt16) {
        spec.attribute("oiio:BitsPerSample", format == PixelFormat::UInt8 ? 8 : 16);
    }
    if (rules.label == "JPEG") {
        spec.attribute("Compression", fmt::format("jpeg:{}", options.jpeg_quality));
    }

    // Write the temporary file.
    TempFile temp(path);
    EXEMPLAR_RETURN_IF_ERROR(temp.status());
    if (!out->open(temp.path(), spec)) {
        return io_error(fmt::format("{}: cannot write: {}", path, one_line(out->geterror())));
    }
    const OIIO::ImageSpec& opened = out->spec();
    if (opened.nchannels != channels ||
        (format != PixelFormat::Auto && opened.format != type_of(format))) {
        out->close();
        out->geterror();
        return unsupported(fmt::format("{}: {} cannot store {} {} channels", path, rules.label,
                                       channels, describe(format)));
    }
    bool written = false;
    if (opened.format.is_floating_point()) {
        written = out->write_image(OIIO::TypeDesc::FLOAT, image.data().data());
    } else {
        const std::vector<float> values = clamped_copy(image);
        written = out->write_image(OIIO::TypeDesc::FLOAT, values.data());
    }
    const bool closed = out->close();
    if (!written || !closed) {
        const std::string error = one_line(out->geterror());
        return io_error(
            fmt::format("{}: cannot write: {}", path, error.empty() ? "unknown error" : error));
    }
    out.reset();
    return temp.commit();
}

}  // namespace

Result<Image> load_image(const std::string& path) {
    return guarded(path, [&]() -> Result<Image> {
        auto in = open_input(path);
        if (!in.ok()) return in.status();
        std::vector<int> all((*in)->spec().nchannels);
        for (int c = 0; c < static_cast<int>(all.size()); ++c) all[static_cast<std::size_t>(c)] = c;
        return read_channels(**in, path, all);
    });
}

Result<Image> load_image_layer(const std::string& path, const std::string& layer) {
    return guarded(path, [&]() -> Result<Image> {
        auto in = open_input(path);
        if (!in.ok()) return in.status();
        const std::vector<std::string>& names = (*in)->spec().channelnames;
        std::vector<int> channels;
        std::vector<std::string> short_names;
        for (int c = 0; c < static_cast<int>(names.size()); ++c) {
            const std::string& name = names[static_cast<std::size_t>(c)];
            const bool whole = !layer.empty() && name == layer;  // single-channel layer
            if (whole || layer_of(name) == layer) {
                channels.push_back(c);
                short_names.push_back(name_in_layer(name));
            }
        }
        if (channels.empty()) {
            return io_error(fmt::format("{}: layer \"{}\" not found (layers in the file: {})", path,
                                        layer, quoted_list(layers_of(names))));
        }
        auto image = read_channels(**in, path, channels);
        if (image.ok()) image->set_channel_names(std::move(short_names));
        return image;
    });
}

Result<std::vector<std::string>> read_channel_names(const std::string& path) {
    return guarded(path, [&]() -> Result<std::vector<std::string>> {
        auto in = open_input(path);
        if (!in.ok()) return in.status();
        return (*in)->spec().channelnames;
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
