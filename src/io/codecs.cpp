#include "codecs.hpp"

#include <fmt/format.h>

#include <cstdint>

namespace exemplar::io_detail {

bool codec_from_signature(const std::string& bytes, Codec& codec) {
    auto starts = [&](std::string_view magic) {
        return bytes.compare(0, magic.size(), magic) == 0;
    };
    if (starts(std::string_view("\x89PNG\r\n\x1a\n", 8))) {
        codec = Codec::Png;
    } else if (starts("\xFF\xD8\xFF")) {
        codec = Codec::Jpeg;
    } else if (starts(std::string_view("II*\0", 4)) || starts(std::string_view("MM\0*", 4)) ||
               starts(std::string_view("II+\0", 4)) || starts(std::string_view("MM\0+", 4))) {
        codec = Codec::Tiff;  // classic and BigTIFF, either byte order
    } else if (starts("\x76\x2f\x31\x01")) {
        codec = Codec::Exr;
    } else if (bytes.size() >= 3 && bytes[0] == 'P' && bytes[1] >= '1' && bytes[1] <= '6' &&
               std::isspace(static_cast<unsigned char>(bytes[2]))) {
        codec = Codec::Pnm;
    } else {
        return false;
    }
    return true;
}

void samples_to_floats(const unsigned char* samples, int bits, std::size_t count, float* out) {
    if (bits == 16) {
        const auto* in = reinterpret_cast<const std::uint16_t*>(samples);
        for (std::size_t i = 0; i < count; ++i) out[i] = static_cast<float>(in[i]) / 65535.0f;
    } else {
        for (std::size_t i = 0; i < count; ++i) out[i] = static_cast<float>(samples[i]) / 255.0f;
    }
}

void floats_to_samples(const float* values, std::size_t count, int bits, unsigned char* out) {
    if (bits == 16) {
        auto* samples = reinterpret_cast<std::uint16_t*>(out);
        for (std::size_t i = 0; i < count; ++i)
            samples[i] = static_cast<std::uint16_t>(to_level(values[i], 65535));
    } else {
        for (std::size_t i = 0; i < count; ++i)
            out[i] = static_cast<unsigned char>(to_level(values[i], 255));
    }
}

std::vector<std::string> default_channel_names(int count) {
    static const std::vector<std::vector<std::string>> kNames = {
        {"Y"}, {"Y", "A"}, {"R", "G", "B"}, {"R", "G", "B", "A"}};
    if (count >= 1 && count <= 4) return kNames[static_cast<std::size_t>(count - 1)];
    std::vector<std::string> names = kNames[3];
    for (int c = 4; c < count; ++c) names.push_back(fmt::format("channel{}", c));
    return names;
}

}  // namespace exemplar::io_detail
