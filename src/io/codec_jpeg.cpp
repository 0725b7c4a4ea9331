// JPEG through libjpeg(-turbo): 8-bit grey or RGB. CMYK files (Adobe's inverted convention,
// what Photoshop writes) are converted to RGB on reading.

#include <fmt/format.h>

#include <csetjmp>
#include <cstdio>
#include <memory>
#include <vector>

// jpeglib.h needs FILE and size_t declared first.
#include <jerror.h>
#include <jpeglib.h>

#include "codecs.hpp"

namespace exemplar::io_detail {

namespace {

struct JpegState {
    jpeg_error_mgr error{};
    std::jmp_buf jump{};
    char message[JMSG_LENGTH_MAX] = {};
    std::FILE* file = nullptr;
    int width = 0, height = 0, channels = 0;
    bool cmyk = false;
    int quality = 95;
    std::vector<unsigned char> pixels;
};

void on_error(j_common_ptr info) {
    auto* state = reinterpret_cast<JpegState*>(info->err);  // `error` is the first member
    (*info->err->format_message)(info, state->message);
    std::longjmp(state->jump, 1);
}

// Warnings and traces are silent, except a file that ends early: libjpeg would fill the rest
// with grey and call it a warning; here it is an error.
void on_message(j_common_ptr info, int level) {
    if (level < 0 && info->err->msg_code == JWRN_JPEG_EOF) {
        auto* state = reinterpret_cast<JpegState*>(info->err);
        std::snprintf(state->message, sizeof(state->message),
                      "truncated: the file ends before its last scanline");
        std::longjmp(state->jump, 1);
    }
}

// The state's error manager, reporting through on_error and on_message.
jpeg_error_mgr* errors(JpegState* s) {
    jpeg_error_mgr* manager = jpeg_std_error(&s->error);
    manager->error_exit = on_error;
    manager->emit_message = on_message;
    return manager;
}

bool allocate(JpegState& s) {
    try {
        s.pixels.resize(static_cast<std::size_t>(s.width) * s.height * s.channels);
        return true;
    } catch (...) {
        std::snprintf(s.message, sizeof(s.message), "out of memory");
        return false;
    }
}

bool decode(JpegState* s) {
    jpeg_decompress_struct info{};
    info.err = errors(s);
    if (setjmp(s->jump)) {
        jpeg_destroy_decompress(&info);
        return false;
    }
    jpeg_create_decompress(&info);
    jpeg_stdio_src(&info, s->file);
    jpeg_read_header(&info, TRUE);
    if (info.jpeg_color_space == JCS_GRAYSCALE) {
        info.out_color_space = JCS_GRAYSCALE;
    } else if (info.jpeg_color_space == JCS_CMYK || info.jpeg_color_space == JCS_YCCK) {
        info.out_color_space = JCS_CMYK;
        s->cmyk = true;
    } else {
        info.out_color_space = JCS_RGB;
    }
    jpeg_start_decompress(&info);
    s->width = static_cast<int>(info.output_width);
    s->height = static_cast<int>(info.output_height);
    s->channels = info.output_components;
    if (!allocate(*s)) {
        jpeg_destroy_decompress(&info);
        return false;
    }
    while (info.output_scanline < info.output_height) {
        JSAMPROW row = s->pixels.data() +
                       static_cast<std::size_t>(info.output_scanline) * s->width * s->channels;
        jpeg_read_scanlines(&info, &row, 1);
    }
    jpeg_finish_decompress(&info);
    jpeg_destroy_decompress(&info);
    return true;
}

bool encode(JpegState* s) {
    jpeg_compress_struct info{};
    info.err = errors(s);
    if (setjmp(s->jump)) {
        jpeg_destroy_compress(&info);
        return false;
    }
    jpeg_create_compress(&info);
    jpeg_stdio_dest(&info, s->file);
    info.image_width = static_cast<JDIMENSION>(s->width);
    info.image_height = static_cast<JDIMENSION>(s->height);
    info.input_components = s->channels;
    info.in_color_space = s->channels == 1 ? JCS_GRAYSCALE : JCS_RGB;
    jpeg_set_defaults(&info);
    jpeg_set_quality(&info, s->quality, TRUE);
    info.optimize_coding = TRUE;
    jpeg_start_compress(&info, TRUE);
    while (info.next_scanline < info.image_height) {
        JSAMPROW row = s->pixels.data() +
                       static_cast<std::size_t>(info.next_scanline) * s->width * s->channels;
        jpeg_write_scanlines(&info, &row, 1);
    }
    jpeg_finish_compress(&info);
    jpeg_destroy_compress(&info);
    return true;
}

}  // namespace

Result<Image> read_jpeg(const std::string& file) {
    auto state = std::make_unique<JpegState>();
    JpegState& s = *state;
    EXEMPLAR_RETURN_IF_ERROR(
        run_file_codec(file, file, "rb", "JPEG", s.file, s.message, [&] { return decode(&s); }));
    const int channels = s.cmyk ? 3 : s.channels;
    Image image(s.width, s.height, channels);
    float* out = image.data().data();
    if (s.cmyk) {
        // Adobe CMYK is stored inverted: 255 means no ink. R = (1 - C)(1 - K) = c' k' / 255².
        for (std::size_t i = 0; i < image.pixel_count(); ++i) {
            const unsigned char* p = &s.pixels[4 * i];
            for (int c = 0; c < 3; ++c)
                out[3 * i + c] = static_cast<float>(p[c]) * static_cast<float>(p[3]) / 65025.0f;
        }
    } else {
        samples_to_floats(s.pixels.data(), 8, image.size(), out);
    }
    image.set_channel_names(default_channel_names(channels));
    return image;
}

Status write_jpeg(const Image& image, const std::string& file, const std::string& shown,
                  int quality) {
    auto state = std::make_unique<JpegState>();
    JpegState& s = *state;
    s.width = image.width();
    s.height = image.height();
    s.channels = image.channels();
    s.quality = quality;
    if (!allocate(s)) return io_error(fmt::format("{}: out of memory", shown));
    floats_to_samples(image.data().data(), image.size(), 8, s.pixels.data());
    return run_file_codec(file, shown, "wb", "JPEG", s.file, s.message, [&] { return encode(&s); });
}

}  // namespace exemplar::io_detail
