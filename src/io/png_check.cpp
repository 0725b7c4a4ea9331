#include "png_check.hpp"

#include <fmt/format.h>

#include <array>
#include <cstdint>

namespace exemplar::io_detail {

namespace {

constexpr std::string_view kSignature("\x89PNG\r\n\x1a\n", 8);

// libpng's default PNG_USER_WIDTH_MAX / PNG_USER_HEIGHT_MAX: larger images fail inside libpng.
constexpr std::uint32_t kLibpngMaxSide = 1000000;

std::array<std::uint32_t, 256> make_crc_table() {
    std::array<std::uint32_t, 256> table{};
    for (std::uint32_t n = 0; n < 256; ++n) {
        std::uint32_t c = n;
        for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        table[n] = c;
    }
    return table;
}

// CRC-32 as defined by the PNG specification (ISO 3309), over chunk type and data.
std::uint32_t crc32(std::string_view bytes) {
    static const std::array<std::uint32_t, 256> table = make_crc_table();
    std::uint32_t c = 0xFFFFFFFFu;
    for (char ch : bytes) c = table[(c ^ static_cast<unsigned char>(ch)) & 0xFFu] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

std::uint32_t read_u32(std::string_view bytes, std::size_t pos) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[pos + i]);
    return v;
}

bool is_chunk_type(std::string_view type) {
    for (char ch : type) {
        const bool letter = (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z');
        if (!letter) return false;
    }
    return true;
}

// Checks the IHDR fields libpng rejects with png_error().
std::string check_ihdr(std::string_view data) {
    if (data.size() != 13) return "corrupt: IHDR chunk has the wrong length";
    const std::uint32_t width = read_u32(data, 0);
    const std::uint32_t height = read_u32(data, 4);
    const int depth = static_cast<unsigned char>(data[8]);
    const int color = static_cast<unsigned char>(data[9]);
    if (width == 0 || height == 0 || width > 0x7FFFFFFFu || height > 0x7FFFFFFFu) {
        return "corrupt: invalid image size in IHDR";
    }
    if (width > kLibpngMaxSide || height > kLibpngMaxSide) {
        return fmt::format("image too large for libpng ({}x{}, limit {} per side)", width, height,
                           kLibpngMaxSide);
    }
    bool depth_ok = false;
    switch (color) {
        case 0:
            depth_ok = depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16;
            break;
        case 3: depth_ok = depth == 1 || depth == 2 || depth == 4 || depth == 8; break;
        case 2:
        case 4:
        case 6: depth_ok = depth == 8 || depth == 16; break;
        default: return "corrupt: invalid color type in IHDR";
    }
    if (!depth_ok) return "corrupt: invalid bit depth for the color type in IHDR";
    if (data[10] != 0 || data[11] != 0 || static_cast<unsigned char>(data[12]) > 1) {
        return "corrupt: invalid compression, filter or interlace method in IHDR";
    }
    return {};
}

}  // namespace

bool has_png_signature(std::string_view bytes) {
    return bytes.substr(0, 8) == kSignature;
}

std::string check_png(std::string_view bytes) {
    if (!has_png_signature(bytes)) return "not a PNG file (bad signature)";
    std::size_t pos = kSignature.size();
    bool palette = false;
    bool seen_plte = false;
    bool seen_idat = false;
    bool idat_ended = false;  // a non-IDAT chunk followed the IDAT run
    for (int index = 0;; ++index) {
        if (bytes.size() - pos < 12) {
            return fmt::format("truncated: file ends at byte {} before the IEND chunk",
                               bytes.size());
        }
        const std::uint32_t length = read_u32(bytes, pos);
        const std::string_view type = bytes.substr(pos + 4, 4);
        if (!is_chunk_type(type))
            return fmt::format("corrupt: invalid chunk header at byte {}", pos);
        if (length > 0x7FFFFFFFu || bytes.size() - pos - 12 < length) {
            return fmt::format("truncated: chunk {} at byte {} runs past the end of the file", type,
                               pos);
        }
        const std::string_view data = bytes.substr(pos + 8, length);
        if (crc32(bytes.substr(pos + 4, 4 + length)) != read_u32(bytes, pos + 8 + length)) {
            return fmt::format("corrupt: CRC mismatch in chunk {} at byte {}", type, pos);
        }
        if (index == 0) {
            if (type != "IHDR") return "corrupt: first chunk is not IHDR";
            if (std::string err = check_ihdr(data); !err.empty()) return err;
            palette = static_cast<unsigned char>(data[9]) == 3;
        } else if (type == "IHDR") {
            return "corrupt: more than one IHDR chunk";
        } else if (type == "PLTE") {
            seen_plte = true;
        } else if (type == "IDAT") {
            if (idat_ended) return "corrupt: IDAT chunks are not consecutive";
            if (palette && !seen_plte) return "corrupt: palette image without PLTE before IDAT";
            seen_idat = true;
        } else if (type == "IEND") {
            if (!seen_idat) return "corrupt: no image data (IDAT chunk)";
            return {};
        } else if (seen_idat) {
            idat_ended = true;
        }
        pos += 12 + static_cast<std::size_t>(length);
    }
}

}  // namespace exemplar::io_detail
