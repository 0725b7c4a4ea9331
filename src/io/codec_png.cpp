// PNG through libpng: 1-4 channels, 8 or 16 bits. Palette, low-bit grey and tRNS transparency
// are expanded on reading (to RGB(A), 8-bit grey, an alpha channel); gamma chunks are not
// applied (values are the stored code values, as in every other format here).

#include <fmt/format.h>
#include <png.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "codecs.hpp"

namespace exemplar::io_detail {

namespace {

// libpng reports errors through these; the message is kept and control jumps back to the
// setjmp in decode()/encode(), whose frames hold no C++ objects.
struct PngState {
    std::FILE* file = nullptr;
    char message[256] = {};
    int width = 0, height = 0, channels = 0, bits = 0;
    std::vector<unsigned char> pixels;  // decoded samples, native byte order for 16-bit
    std::vector<png_bytep> rows;
};

void on_error(png_structp png, png_const_charp message) {
    auto* state = static_cast<PngState*>(png_get_error_ptr(png));
    std::snprintf(state->message, sizeof(state->message), "%s", message);
    png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}

// Allocation in a frame without setjmp: std::vector may throw, which must not cross libpng.
bool allocate(PngState& s, std::size_t row_bytes) {
    try {
        s.pixels.resize(row_bytes * static_cast<std::size_t>(s.height));
        s.rows.resize(static_cast<std::size_t>(s.height));
        for (int y = 0; y < s.height; ++y) s.rows[y] = s.pixels.data() + row_bytes * y;
        return true;
    } catch (...) {
        std::snprintf(s.message, sizeof(s.message), "out of memory");
        return false;
    }
}

bool decode(PngState* s) {
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, s, on_error, on_warning);
    if (png == nullptr) return false;
    png_infop info = png_create_info_struct(png);
    if (info == nullptr || setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        return false;
    }
    png_init_io(png, s->file);
    png_read_info(png, info);
    png_set_expand(png);  // palette -> RGB, grey < 8 bits -> 8, tRNS -> alpha
    if (png_get_bit_depth(png, info) == 16) png_set_swap(png);  // little-endian hosts
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    s->width = static_cast<int>(png_get_image_width(png, info));
    s->height = static_cast<int>(png_get_image_height(png, info));
    s->channels = png_get_channels(png, info);
    s->bits = png_get_bit_depth(png, info);
    if (!allocate(*s, png_get_rowbytes(png, info))) {
        png_destroy_read_struct(&png, &info, nullptr);
        return false;
    }
    png_read_image(png, s->rows.data());
    png_read_end(png, nullptr);
    png_destroy_read_struct(&png, &info, nullptr);
    return true;
}

constexpr int kPngCompressionLevel = 2;

bool encode(PngState* s) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, s, on_error, on_warning);
    if (png == nullptr) return false;
    png_infop info = png_create_info_struct(png);
    if (info == nullptr || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    static constexpr int kColourTypes[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
                                           PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA};
    png_init_io(png, s->file);
    png_set_IHDR(png, info, static_cast<png_uint_32>(s->width), static_cast<png_uint_32>(s->height),
                 s->bits, kColourTypes[s->channels - 1], PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    // zlib level 2 instead of libpng's default 6: synthesized images are grainy and deflate
    // poorly at any level, so the files grow only 6-10% while encoding takes a quarter (stylit's
    // 1200x912 output) to two thirds (texbynum's 320x462) less CPU, which is a tenth of a
    // `--quality fast` run on the small examples (docs/PERFORMANCE.md, issue 15).
    png_set_compression_level(png, kPngCompressionLevel);
    png_write_info(png, info);
    if (s->bits == 16) png_set_swap(png);
    png_write_image(png, s->rows.data());
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

}  // namespace

Result<Image> read_png(const std::string& file) {
    auto state = std::make_unique<PngState>();
    PngState& s = *state;
    EXEMPLAR_RETURN_IF_ERROR(
        run_file_codec(file, file, "rb", "PNG", s.file, s.message, [&] { return decode(&s); }));
    Image image(s.width, s.height, s.channels);
    samples_to_floats(s.pixels.data(), s.bits, image.size(), image.data().data());
    image.set_channel_names(default_channel_names(s.channels));
    return image;
}

Status write_png(const Image& image, const std::string& file, const std::string& shown,
                 PixelFormat format) {
    auto state = std::make_unique<PngState>();
    PngState& s = *state;
    s.width = image.width();
    s.height = image.height();
    s.channels = image.channels();
    s.bits = format == PixelFormat::UInt16 ? 16 : 8;
    const std::size_t row_bytes =
        static_cast<std::size_t>(s.width) * static_cast<std::size_t>(s.channels) * (s.bits / 8);
    if (!allocate(s, row_bytes)) return io_error(fmt::format("{}: out of memory", shown));
    floats_to_samples(image.data().data(), image.size(), s.bits, s.pixels.data());
    return run_file_codec(file, shown, "wb", "PNG", s.file, s.message, [&] { return encode(&s); });
}

}  // namespace exemplar::io_detail
