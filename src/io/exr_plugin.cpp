// OpenEXR through the OpenEXR library: any number of named channels, half or float (uint
// channels are read as float), scanline or tiled, the data window of the first part. Written
// files are scanline, ZIP-compressed. Built as the plugin libexemplar_openexr.so
// (codec_plugin.hpp says why); it links no exemplar library.

#include <Imath/half.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfPartType.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <string>
#include <vector>

#include "codec_plugin.hpp"

namespace exemplar::io_detail::codec_plugin {

namespace {

bool same_name(const std::string& a, const char* b) {
    return a.size() == std::strlen(b) && std::equal(a.begin(), a.end(), b, [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) ==
                      std::tolower(static_cast<unsigned char>(y));
           });
}

// Rank of a channel within its layer (names compared without case): colour, luminance, complex,
// alpha, depth first, in OpenImageIO's order; in a layer with both X and Y (a position, normal or
// vector pass), X, Y, Z, W right after the colour. Others after these. Checked against
// OpenImageIO 2.4 on, e.g., {x, y, angle, error}, {R, G, B, x, y, Z, A}, {Y, real, A, Z, W}.
int special_rank(const std::string& name, bool vector_layer) {
    static const std::array<const char*, 20> kOrder = {
        "R",     "Red", "G",  "Green", "B",  "Blue", "Y",  "real", "imag",  "A",
        "Alpha", "AR",  "RA", "AG",    "GA", "AB",   "BA", "Z",    "Depth", "Zback"};
    if (vector_layer) {
        static const std::array<const char*, 4> kVector = {"X", "Y", "Z", "W"};
        for (std::size_t i = 0; i < kVector.size(); ++i) {
            if (same_name(name, kVector[i])) return 2 * 6 + static_cast<int>(i);  // after Blue
        }
    }
    for (std::size_t i = 0; i < kOrder.size(); ++i) {
        if (same_name(name, kOrder[i])) return 2 * static_cast<int>(i) + (i >= 6 ? 10 : 0);
    }
    return 100;
}

// Channel names of a header in reading order (see codecs.hpp).
std::vector<std::string> ordered_names(const Imf::Header& header) {
    struct Entry {
        std::string name, layer, suffix;
        int rank, index;
    };
    std::vector<Entry> entries;
    int index = 0;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it, ++index) {
        const std::string name = it.name();
        const auto dot = name.rfind('.');
        const std::string layer = dot == std::string::npos ? "" : name.substr(0, dot + 1);
        const std::string suffix = dot == std::string::npos ? name : name.substr(dot + 1);
        entries.push_back({name, layer, suffix, 0, index});
    }
    for (Entry& e : entries) {
        bool has_x = false, has_y = false;
        for (const Entry& other : entries) {
            if (other.layer != e.layer) continue;
            has_x = has_x || same_name(other.suffix, "X");
            has_y = has_y || same_name(other.suffix, "Y");
        }
        e.rank = special_rank(e.suffix, has_x && has_y);
    }
    std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
        if (a.layer != b.layer) return a.layer < b.layer;
        if (a.rank != b.rank) return a.rank < b.rank;
        return a.suffix < b.suffix;
    });
    std::vector<std::string> names;
    for (const Entry& e : entries) names.push_back(e.name);
    return names;
}

Status check_flat(const Imf::Header& header, const std::string& file) {
    if (header.hasType() && (header.type() == Imf::DEEPSCANLINE || header.type() == Imf::DEEPTILE))
        return unsupported(fmt::format("{}: deep images are not supported", file));
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
        if (it.channel().xSampling != 1 || it.channel().ySampling != 1) {
            return unsupported(
                fmt::format("{}: subsampled channel \"{}\" is not supported", file, it.name()));
        }
    }
    return Status::ok();
}

Result<std::vector<std::string>> channel_names(const std::string& file) {
    Imf::InputFile in(file.c_str());
    EXEMPLAR_RETURN_IF_ERROR(check_flat(in.header(), file));
    return ordered_names(in.header());
}

Status read(const std::string& file, const std::vector<std::string>& channels, Allocate allocate,
            void* context, std::vector<std::string>* names_read) {
    Imf::InputFile in(file.c_str());
    const Imf::Header& header = in.header();
    EXEMPLAR_RETURN_IF_ERROR(check_flat(header, file));
    const std::vector<std::string> names = channels.empty() ? ordered_names(header) : channels;
    const Imath::Box2i window = header.dataWindow();
    const int width = window.max.x - window.min.x + 1;
    const int height = window.max.y - window.min.y + 1;
    if (width <= 0 || height <= 0 || names.empty()) {
        return io_error(fmt::format("{}: corrupt: image is {}x{} with {} channels", file, width,
                                    height, names.size()));
    }
    float* values = allocate(context, width, height, static_cast<int>(names.size()));
    const std::size_t x_stride = sizeof(float) * names.size();
    const std::size_t y_stride = x_stride * static_cast<std::size_t>(width);
    Imf::FrameBuffer frame;
    for (std::size_t c = 0; c < names.size(); ++c) {
        frame.insert(names[c],
                     Imf::Slice::Make(Imf::FLOAT, values + c, window, x_stride, y_stride));
    }
    in.setFrameBuffer(frame);
    in.readPixels(window.min.y, window.max.y);
    *names_read = names;
    return Status::ok();
}

Status write(const float* values, int width, int height, const std::vector<std::string>& names,
             const std::string& file, const std::string&, PixelFormat format) {
    const bool half = format != PixelFormat::Float;
    Imf::Header header(width, height);
    header.compression() = Imf::ZIP_COMPRESSION;
    const std::size_t count =
        static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * names.size();
    // OpenEXR writes a slice only to a channel of its own type, so half channels are converted
    // here (to the nearest half, as Imath rounds).
    std::vector<Imath::half> halves;
    if (half) halves.assign(values, values + count);
    const std::size_t sample = half ? sizeof(Imath::half) : sizeof(float);
    const std::size_t x_stride = sample * names.size();
    const std::size_t y_stride = x_stride * static_cast<std::size_t>(width);
    char* base = half ? reinterpret_cast<char*>(halves.data())
                      : const_cast<char*>(reinterpret_cast<const char*>(values));
    Imf::FrameBuffer frame;
    for (std::size_t c = 0; c < names.size(); ++c) {
        header.channels().insert(names[c], Imf::Channel(half ? Imf::HALF : Imf::FLOAT));
        frame.insert(names[c], Imf::Slice(half ? Imf::HALF : Imf::FLOAT, base + sample * c,
                                          x_stride, y_stride));
    }
    Imf::OutputFile out(file.c_str(), header);
    out.setFrameBuffer(frame);
    out.writePixels(height);
    return Status::ok();
}

constexpr Entry kEntry{kOpenExr.abi_version, &channel_names, &read, &write};

}  // namespace
}  // namespace exemplar::io_detail::codec_plugin

// The plugin's one exported symbol; also linked into libexemplar.so and the Python module,
// where codec_plugins.cpp calls it directly.
extern "C" __attribute__((visibility("default"))) const exemplar::io_detail::codec_plugin::Entry*
exemplar_openexr_entry() {
    return &exemplar::io_detail::codec_plugin::kEntry;
}
