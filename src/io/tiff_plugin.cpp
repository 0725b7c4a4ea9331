// TIFF through libtiff: 8/16/32-bit integer or 16/32-bit float samples, grey or RGB, any
// number of extra channels, contiguous or planar, strips or tiles. Other photometric
// interpretations (palette, YCbCr, CMYK, bilevel) go through libtiff's RGBA reader (8-bit).
// Written files are contiguous strips with Deflate compression and the matching predictor.
// Built as the plugin libexemplar_tiff.so (codec_plugin.hpp says why); it links no exemplar
// library.

#include <Imath/half.h>
#include <fmt/format.h>
#include <tiffio.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "codec_plugin.hpp"
#include "codecs.hpp"

namespace exemplar::io_detail::codec_plugin {

namespace {

// Keeps the first error libtiff reports for this file (libtiff may report several).
int on_error(TIFF*, void* user, const char*, const char* format, va_list args) {
    auto* message = static_cast<std::string*>(user);
    if (message->empty()) {
        char buffer[512];
        std::vsnprintf(buffer, sizeof(buffer), format, args);
        *message = buffer;
        for (char& ch : *message)
            if (ch == '\n' || ch == '\r') ch = ' ';
    }
    return 1;  // handled: libtiff prints nothing
}

int on_warning(TIFF*, void*, const char*, const char*, va_list) {
    return 1;
}

struct TiffFile {
    TIFF* tiff = nullptr;
    std::string message;
    ~TiffFile() {
        if (tiff != nullptr) TIFFClose(tiff);
    }
    bool open(const std::string& path, const char* mode) {
        TIFFOpenOptions* options = TIFFOpenOptionsAlloc();
        TIFFOpenOptionsSetErrorHandlerExtR(options, on_error, &message);
        TIFFOpenOptionsSetWarningHandlerExtR(options, on_warning, nullptr);
        tiff = TIFFOpenExt(path.c_str(), mode, options);
        TIFFOpenOptionsFree(options);
        return tiff != nullptr;
    }
    std::string problem(const char* fallback) const { return message.empty() ? fallback : message; }
};

template <typename T>
T field(TIFF* tiff, ttag_t tag, T fallback) {
    T value = fallback;
    TIFFGetFieldDefaulted(tiff, tag, &value);
    return value;
}

// Sample `i` of a buffer of `bits`-bit samples in format `format`, as float.
float sample(const unsigned char* data, std::size_t i, int bits, int format) {
    if (format == SAMPLEFORMAT_IEEEFP) {
        if (bits == 16) {
            Imath::half h;
            h.setBits(reinterpret_cast<const std::uint16_t*>(data)[i]);
            return static_cast<float>(h);
        }
        return reinterpret_cast<const float*>(data)[i];
    }
    switch (bits) {
        case 8: return static_cast<float>(data[i]) / 255.0f;
        case 16:
            return static_cast<float>(reinterpret_cast<const std::uint16_t*>(data)[i]) / 65535.0f;
        default:
            return static_cast<float>(
                static_cast<double>(reinterpret_cast<const std::uint32_t*>(data)[i]) /
                4294967295.0);
    }
}

// Names: grey or RGB colour channels, then "A" for the first extra sample if it is alpha, then
// "channelN".
std::vector<std::string> channel_names(int channels, int colour, bool alpha) {
    std::vector<std::string> names;
    for (int c = 0; c < channels; ++c) {
        if (c < colour) {
            names.push_back(colour == 1 ? "Y" : std::string(1, "RGB"[c]));
        } else if (c == colour && alpha) {
            names.push_back("A");
        } else {
            names.push_back(fmt::format("channel{}", c));
        }
    }
    return names;
}

Status read_rgba(TiffFile& f, const std::string& file, int width, int height, Allocate allocate,
                 void* context, std::vector<std::string>* names) {
    std::vector<std::uint32_t> raster(static_cast<std::size_t>(width) * height);
    if (!TIFFReadRGBAImageOriented(f.tiff, static_cast<std::uint32_t>(width),
                                   static_cast<std::uint32_t>(height), raster.data(),
                                   ORIENTATION_TOPLEFT, 0)) {
        return io_error(fmt::format("{}: cannot read TIFF: {}", file,
                                    f.problem("unsupported or corrupt data")));
    }
    std::uint16_t extra_count = 0;
    std::uint16_t* extra = nullptr;
    TIFFGetField(f.tiff, TIFFTAG_EXTRASAMPLES, &extra_count, &extra);
    const int channels = extra_count > 0 ? 4 : 3;
    float* image = allocate(context, width, height, channels);
    for (std::size_t i = 0; i < raster.size(); ++i) {
        const std::uint32_t p = raster[i];
        const std::uint32_t values[4] = {TIFFGetR(p), TIFFGetG(p), TIFFGetB(p), TIFFGetA(p)};
        for (int c = 0; c < channels; ++c)
            image[i * channels + c] = static_cast<float>(values[c]) / 255.0f;
    }
    *names = channel_names(channels, 3, channels == 4);
    return Status::ok();
}

// Every channel (TIFF names none: `channels` is ignored, image_io.cpp selects afterwards).
Status read(const std::string& file, const std::vector<std::string>&, Allocate allocate,
            void* context, std::vector<std::string>* names) {
    TiffFile f;
    if (!f.open(file, "r")) {
        return io_error(
            fmt::format("{}: cannot read TIFF: {}", file, f.problem("not a TIFF file")));
    }
    const auto width = static_cast<int>(field<std::uint32_t>(f.tiff, TIFFTAG_IMAGEWIDTH, 0));
    const auto height = static_cast<int>(field<std::uint32_t>(f.tiff, TIFFTAG_IMAGELENGTH, 0));
    const int channels = field<std::uint16_t>(f.tiff, TIFFTAG_SAMPLESPERPIXEL, 1);
    const int bits = field<std::uint16_t>(f.tiff, TIFFTAG_BITSPERSAMPLE, 1);
    const int format = field<std::uint16_t>(f.tiff, TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_UINT);
    const int planar = field<std::uint16_t>(f.tiff, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    std::uint16_t photometric = PHOTOMETRIC_MINISBLACK;
    TIFFGetField(f.tiff, TIFFTAG_PHOTOMETRIC, &photometric);
    if (width <= 0 || height <= 0 || channels <= 0) {
        return io_error(fmt::format("{}: corrupt: image is {}x{} with {} channels", file, width,
                                    height, channels));
    }
    const int colour = photometric == PHOTOMETRIC_RGB ? 3 : 1;
    const bool direct = (photometric == PHOTOMETRIC_MINISBLACK ||
                         photometric == PHOTOMETRIC_MINISWHITE || photometric == PHOTOMETRIC_RGB) &&
                        channels >= colour &&
                        ((format == SAMPLEFORMAT_UINT && (bits == 8 || bits == 16 || bits == 32)) ||
                         (format == SAMPLEFORMAT_IEEEFP && (bits == 16 || bits == 32)));
    if (!direct) return read_rgba(f, file, width, height, allocate, context, names);

    std::uint16_t extra_count = 0;
    std::uint16_t* extra = nullptr;
    TIFFGetField(f.tiff, TIFFTAG_EXTRASAMPLES, &extra_count, &extra);
    const bool alpha = extra_count > 0 &&
                       (extra[0] == EXTRASAMPLE_ASSOCALPHA || extra[0] == EXTRASAMPLE_UNASSALPHA);
    float* image = allocate(context, width, height, channels);
    *names = channel_names(channels, colour, alpha || channels == colour + 1);
    const bool tiled = TIFFIsTiled(f.tiff) != 0;
    const tmsize_t chunk_bytes = tiled ? TIFFTileSize(f.tiff) : TIFFStripSize(f.tiff);
    const std::uint32_t chunk_w = tiled ? field<std::uint32_t>(f.tiff, TIFFTAG_TILEWIDTH, 0)
                                        : static_cast<std::uint32_t>(width);
    const std::uint32_t chunk_h = tiled ? field<std::uint32_t>(f.tiff, TIFFTAG_TILELENGTH, 0)
                                        : field<std::uint32_t>(f.tiff, TIFFTAG_ROWSPERSTRIP,
                                                               static_cast<std::uint32_t>(height));
    if (chunk_bytes <= 0 || chunk_w == 0 || chunk_h == 0) {
        return io_error(fmt::format("{}: corrupt: bad strip or tile layout", file));
    }
    std::vector<unsigned char> buffer(static_cast<std::size_t>(chunk_bytes));
    const int planes = planar == PLANARCONFIG_SEPARATE ? channels : 1;
    const int per_pixel = planes == 1 ? channels : 1;  // samples per pixel in one chunk
    for (int plane = 0; plane < planes; ++plane) {
        for (std::uint32_t y0 = 0; y0 < static_cast<std::uint32_t>(height); y0 += chunk_h) {
            for (std::uint32_t x0 = 0; x0 < static_cast<std::uint32_t>(width); x0 += chunk_w) {
                const tmsize_t got =
                    tiled ? TIFFReadTile(f.tiff, buffer.data(), x0, y0, 0,
                                         static_cast<std::uint16_t>(plane))
                          : TIFFReadEncodedStrip(
                                f.tiff,
                                TIFFComputeStrip(f.tiff, y0, static_cast<std::uint16_t>(plane)),
                                buffer.data(), chunk_bytes);
                if (got < 0) {
                    return io_error(fmt::format("{}: cannot read pixels: {}", file,
                                                f.problem("file is truncated or corrupt")));
                }
                const std::uint32_t rows =
                    std::min(chunk_h, static_cast<std::uint32_t>(height) - y0);
                const std::uint32_t cols =
                    std::min(chunk_w, static_cast<std::uint32_t>(width) - x0);
                for (std::uint32_t r = 0; r < rows; ++r) {
                    for (std::uint32_t col = 0; col < cols; ++col) {
                        const std::size_t in =
                            (static_cast<std::size_t>(r) * chunk_w + col) * per_pixel;
                        float* out =
                            image + ((static_cast<std::size_t>(y0 + r) * width + x0 + col) *
                                     static_cast<std::size_t>(channels));
                        for (int s = 0; s < per_pixel; ++s) {
                            out[plane + s] = sample(buffer.data(), in + s, bits, format);
                        }
                    }
                }
            }
        }
    }
    if (photometric == PHOTOMETRIC_MINISWHITE && format == SAMPLEFORMAT_UINT) {
        const std::size_t pixels = static_cast<std::size_t>(width) * height;
        for (std::size_t i = 0; i < pixels; ++i) image[i * channels] = 1.0f - image[i * channels];
    }
    return Status::ok();
}

Status write(const float* values, int width, int height, const std::vector<std::string>& names,
             const std::string& file, const std::string& shown, PixelFormat format) {
    const int channels = static_cast<int>(names.size());
    const int bits = format == PixelFormat::UInt8 ? 8 : format == PixelFormat::UInt16 ? 16 : 32;
    const bool floats = format == PixelFormat::Float;
    TiffFile f;
    if (!f.open(file, "w")) {
        return io_error(fmt::format("{}: cannot write: {}", shown, f.problem("cannot create")));
    }
    const int colour = channels >= 3 ? 3 : 1;
    TIFFSetField(f.tiff, TIFFTAG_IMAGEWIDTH, static_cast<std::uint32_t>(width));
    TIFFSetField(f.tiff, TIFFTAG_IMAGELENGTH, static_cast<std::uint32_t>(height));
    TIFFSetField(f.tiff, TIFFTAG_SAMPLESPERPIXEL, static_cast<std::uint16_t>(channels));
    TIFFSetField(f.tiff, TIFFTAG_BITSPERSAMPLE, static_cast<std::uint16_t>(bits));
    TIFFSetField(f.tiff, TIFFTAG_SAMPLEFORMAT,
                 static_cast<std::uint16_t>(floats ? SAMPLEFORMAT_IEEEFP : SAMPLEFORMAT_UINT));
    TIFFSetField(f.tiff, TIFFTAG_PLANARCONFIG, static_cast<std::uint16_t>(PLANARCONFIG_CONTIG));
    TIFFSetField(
        f.tiff, TIFFTAG_PHOTOMETRIC,
        static_cast<std::uint16_t>(colour == 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK));
    TIFFSetField(f.tiff, TIFFTAG_ORIENTATION, static_cast<std::uint16_t>(ORIENTATION_TOPLEFT));
    TIFFSetField(f.tiff, TIFFTAG_COMPRESSION,
                 static_cast<std::uint16_t>(COMPRESSION_ADOBE_DEFLATE));
    TIFFSetField(
        f.tiff, TIFFTAG_PREDICTOR,
        static_cast<std::uint16_t>(floats ? PREDICTOR_FLOATINGPOINT : PREDICTOR_HORIZONTAL));
    if (channels > colour) {
        // The channel named "A" right after the colour channels is (unassociated) alpha.
        std::vector<std::uint16_t> extra(static_cast<std::size_t>(channels - colour),
                                         EXTRASAMPLE_UNSPECIFIED);
        if (names[static_cast<std::size_t>(colour)] == "A") extra[0] = EXTRASAMPLE_UNASSALPHA;
        TIFFSetField(f.tiff, TIFFTAG_EXTRASAMPLES, static_cast<std::uint16_t>(extra.size()),
                     extra.data());
    }
    TIFFSetField(f.tiff, TIFFTAG_ROWSPERSTRIP, TIFFDefaultStripSize(f.tiff, 0));

    const std::size_t row_samples = static_cast<std::size_t>(width) * channels;
    std::vector<unsigned char> row(row_samples * (bits / 8));
    for (int y = 0; y < height; ++y) {
        const float* in = values + static_cast<std::size_t>(y) * row_samples;
        for (std::size_t i = 0; i < row_samples; ++i) {
            if (floats) {
                std::memcpy(row.data() + 4 * i, in + i, 4);
            } else if (bits == 16) {
                const auto v = static_cast<std::uint16_t>(to_level(in[i], 65535));
                std::memcpy(row.data() + 2 * i, &v, 2);
            } else {
                row[i] = static_cast<unsigned char>(to_level(in[i], 255));
            }
        }
        if (TIFFWriteScanline(f.tiff, row.data(), static_cast<std::uint32_t>(y), 0) < 0) {
            return io_error(fmt::format("{}: cannot write: {}", shown, f.problem("write error")));
        }
    }
    TIFF* tiff = f.tiff;
    f.tiff = nullptr;
    if (!TIFFFlush(tiff)) {
        TIFFClose(tiff);
        return io_error(fmt::format("{}: cannot write: {}", shown, f.problem("write error")));
    }
    TIFFClose(tiff);
    return Status::ok();
}

constexpr Entry kEntry{kTiff.abi_version, nullptr, &read, &write};

}  // namespace
}  // namespace exemplar::io_detail::codec_plugin

// The plugin's one exported symbol; also linked into libexemplar.so and the Python module,
// where codec_plugins.cpp calls it directly.
extern "C" __attribute__((visibility("default"))) const exemplar::io_detail::codec_plugin::Entry*
exemplar_tiff_entry() {
    return &exemplar::io_detail::codec_plugin::kEntry;
}
