// Netpbm PBM/PGM/PPM (P1-P6): a text header and samples, ASCII or binary, up to 16 bits. Too
// simple a format for a library; written as binary 8-bit PGM (P5) or PPM (P6).

#include <fmt/format.h>

#include <cctype>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "codecs.hpp"

namespace exemplar::io_detail {

namespace {

// Reads the header's whitespace-separated numbers, skipping '#' comments.
class HeaderReader {
public:
    explicit HeaderReader(const std::string& bytes) : bytes_(bytes) {}
    bool number(long& value) {
        while (pos_ < bytes_.size()) {
            const char ch = bytes_[pos_];
            if (ch == '#') {
                while (pos_ < bytes_.size() && bytes_[pos_] != '\n') ++pos_;
            } else if (std::isspace(static_cast<unsigned char>(ch))) {
                ++pos_;
            } else {
                break;
            }
        }
        if (pos_ >= bytes_.size() || !std::isdigit(static_cast<unsigned char>(bytes_[pos_])))
            return false;
        value = 0;
        while (pos_ < bytes_.size() && std::isdigit(static_cast<unsigned char>(bytes_[pos_]))) {
            value = value * 10 + (bytes_[pos_] - '0');
            if (value > 1000000000L) return false;
            ++pos_;
        }
        return true;
    }
    // Binary data start: after exactly one whitespace character following the last number.
    std::size_t data_start() const { return pos_ + 1; }
    std::size_t& pos() { return pos_; }

private:
    const std::string& bytes_;
    std::size_t pos_ = 2;
};

}  // namespace

Result<Image> read_pnm(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return io_error(fmt::format("{}: cannot open", file));
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (bytes.size() < 2 || bytes[0] != 'P' || bytes[1] < '1' || bytes[1] > '6')
        return io_error(fmt::format("{}: cannot read image: not a valid PNM file", file));
    const int kind = bytes[1] - '0';
    const bool bitmap = kind == 1 || kind == 4;
    const bool ascii = kind <= 3;
    const int channels = (kind == 3 || kind == 6) ? 3 : 1;
    HeaderReader header(bytes);
    long width = 0, height = 0, max = 1;
    if (!header.number(width) || !header.number(height) || (!bitmap && !header.number(max)) ||
        width <= 0 || height <= 0 || max <= 0 || max > 65535) {
        return io_error(fmt::format("{}: corrupt: bad PNM header", file));
    }
    Image image(static_cast<int>(width), static_cast<int>(height), channels);
    const std::size_t n = image.size();
    float* out = image.data().data();
    const float scale = 1.0f / static_cast<float>(max);
    const std::string truncated =
        fmt::format("{}: truncated: the file ends before its last pixel", file);
    if (ascii) {
        for (std::size_t i = 0; i < n; ++i) {
            long v = 0;
            if (bitmap) {  // digits need no separators
                std::size_t& p = header.pos();
                while (p < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[p]))) ++p;
                if (p >= bytes.size() || (bytes[p] != '0' && bytes[p] != '1'))
                    return io_error(truncated);
                v = bytes[p++] - '0';
                out[i] = v == 1 ? 0.0f : 1.0f;  // 1 is black
                continue;
            }
            if (!header.number(v) || v > max) return io_error(truncated);
            out[i] = static_cast<float>(v) * scale;
        }
    } else if (bitmap) {
        const std::size_t row_bytes = (static_cast<std::size_t>(width) + 7) / 8;
        const std::size_t start = header.data_start();
        if (bytes.size() < start + row_bytes * static_cast<std::size_t>(height))
            return io_error(truncated);
        for (long y = 0; y < height; ++y)
            for (long x = 0; x < width; ++x) {
                const auto byte = static_cast<unsigned char>(bytes[start + y * row_bytes + x / 8]);
                out[y * width + x] = ((byte >> (7 - x % 8)) & 1) ? 0.0f : 1.0f;
            }
    } else {
        const std::size_t sample_bytes = max > 255 ? 2 : 1;
        const std::size_t start = header.data_start();
        if (bytes.size() < start + n * sample_bytes) return io_error(truncated);
        const auto* data = reinterpret_cast<const unsigned char*>(bytes.data() + start);
        for (std::size_t i = 0; i < n; ++i) {
            const unsigned v = sample_bytes == 2 ? (data[2 * i] << 8) | data[2 * i + 1] : data[i];
            out[i] = static_cast<float>(v) * scale;
        }
    }
    image.set_channel_names(default_channel_names(channels));
    return image;
}

Status write_pnm(const Image& image, const std::string& file, const std::string& shown) {
    std::string bytes = fmt::format("P{}\n{} {}\n255\n", image.channels() == 3 ? 6 : 5,
                                    image.width(), image.height());
    const std::size_t header = bytes.size();
    bytes.resize(header + image.size());
    for (std::size_t i = 0; i < image.size(); ++i)
        bytes[header + i] = static_cast<char>(to_level(image.data()[i], 255));
    std::FILE* out = std::fopen(file.c_str(), "wb");
    if (out == nullptr) return io_error(fmt::format("{}: cannot write", shown));
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), out) == bytes.size();
    const bool closed = std::fclose(out) == 0;
    if (!written || !closed)
        return io_error(fmt::format("{}: cannot write: disk full or I/O error", shown));
    return Status::ok();
}

}  // namespace exemplar::io_detail
