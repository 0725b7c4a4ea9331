#include "exemplar/core/image.hpp"

#include <algorithm>
#include <cmath>

#include "exemplar/core/check.hpp"

namespace exemplar {

Image::Image(int width, int height, int channels, float fill)
    : width_(width), height_(height), channels_(channels) {
    EXEMPLAR_CHECK_GE(width, 0);
    EXEMPLAR_CHECK_GE(height, 0);
    EXEMPLAR_CHECK_GE(channels, 0);
    data_.assign(pixel_count() * static_cast<std::size_t>(channels), fill);
    names_ = default_channel_names(channels);
}

void Image::set_channel_names(std::vector<std::string> names) {
    EXEMPLAR_CHECK_EQ(static_cast<int>(names.size()), channels_);
    names_ = std::move(names);
}

std::vector<std::string> default_channel_names(int channels) {
    switch (channels) {
        case 1: return {"Y"};
        case 2: return {"Y", "A"};
        case 3: return {"R", "G", "B"};
        case 4: return {"R", "G", "B", "A"};
        default: break;
    }
    std::vector<std::string> names;
    for (int c = 0; c < channels; ++c) {
        std::string name(1, 'c');  // built in two steps: GCC 12 -Wrestrict false positive
        name.append(std::to_string(c));
        names.push_back(std::move(name));
    }
    return names;
}

Image extract_channels(const Image& image, int first, int count) {
    EXEMPLAR_CHECK_GE(first, 0);
    EXEMPLAR_CHECK_LE(first + count, image.channels());
    Image out(image.width(), image.height(), count);
    const std::size_t n = image.pixel_count();
    const int in_c = image.channels();
    const float* src = image.data().data();
    float* dst = out.data().data();
    // Plain loops: a memcpy call per pixel of a few bytes costs more than the copy.
    if (count == in_c) {
        std::copy(image.data().begin(), image.data().end(), out.data().begin());
    } else {
        for (std::size_t i = 0; i < n; ++i) {
            const float* s = src + i * static_cast<std::size_t>(in_c) + first;
            float* d = dst + i * static_cast<std::size_t>(count);
            for (int c = 0; c < count; ++c) d[c] = s[c];
        }
    }
    const auto& names = image.channel_names();
    out.set_channel_names({names.begin() + first, names.begin() + first + count});
    return out;
}

Image select_channels(const Image& image, std::span<const int> channels) {
    const int in_c = image.channels();
    bool all = static_cast<int>(channels.size()) == in_c;
    for (std::size_t k = 0; all && k < channels.size(); ++k) {
        all = channels[k] == static_cast<int>(k);
    }
    if (all || image.empty()) return image;
    const auto count = static_cast<int>(channels.size());
    Image out(image.width(), image.height(), count);
    std::vector<std::string> names;
    for (int c : channels) {
        EXEMPLAR_CHECK(c >= 0 && c < in_c);
        names.push_back(image.channel_names()[static_cast<std::size_t>(c)]);
    }
    out.set_channel_names(std::move(names));
    const float* src = image.data().data();
    float* dst = out.data().data();
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
        const float* s = src + i * static_cast<std::size_t>(in_c);
        float* d = dst + i * static_cast<std::size_t>(count);
        for (int k = 0; k < count; ++k) d[k] = s[channels[static_cast<std::size_t>(k)]];
    }
    return out;
}

Image concat_channels(const std::vector<const Image*>& images) {
    if (images.empty()) return {};
    int total = 0;
    for (const Image* im : images) {
        EXEMPLAR_CHECK(im->same_size(*images.front()));
        total += im->channels();
    }
    Image out(images.front()->width(), images.front()->height(), total);
    std::vector<std::string> names;
    const std::size_t n = out.pixel_count();
    int offset = 0;
    for (const Image* im : images) {
        const int c = im->channels();
        const float* src = im->data().data();
        float* dst = out.data().data();
        for (std::size_t i = 0; i < n; ++i) {
            const float* s = src + i * static_cast<std::size_t>(c);
            float* d = dst + i * static_cast<std::size_t>(total) + offset;
            for (int k = 0; k < c; ++k) d[k] = s[k];
        }
        names.insert(names.end(), im->channel_names().begin(), im->channel_names().end());
        offset += c;
    }
    out.set_channel_names(std::move(names));
    return out;
}

int find_channel(const Image& image, const std::string& name) {
    const auto& names = image.channel_names();
    auto it = std::find(names.begin(), names.end(), name);
    return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

bool all_finite(const Image& image) {
    return std::all_of(image.data().begin(), image.data().end(),
                       [](float v) { return std::isfinite(v); });
}

std::string size_str(const Image& image) {
    return std::to_string(image.width()) + "x" + std::to_string(image.height());
}

}  // namespace exemplar
