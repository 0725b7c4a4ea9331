#include "exemplar/synth/inpaint.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace exemplar {

Result<Image> inpainting_known(const Image& mask, const std::string& what) {
    const int channels = mask.channels();
    const bool alpha = channels == 2 || channels == 4;
    const int colours = alpha ? channels - 1 : channels;
    Image known(mask.width(), mask.height(), 1, 0.0f);
    std::size_t holes = 0;
    for (std::size_t i = 0; i < mask.pixel_count(); ++i) {
        const float* p = mask.data().data() + i * static_cast<std::size_t>(channels);
        if (alpha && p[channels - 1] != 1.0f) {
            return invalid_argument(what +
                                    ": is partly transparent; masks are read from grey values, "
                                    "not alpha (flatten it first)");
        }
        float sum = 0.0f;
        for (int c = 0; c < colours; ++c) sum += p[c];
        const bool is_known = sum > 0.5f * static_cast<float>(colours);
        known.data()[i] = is_known ? 1.0f : 0.0f;
        holes += is_known ? 0 : 1;
    }
    if (holes == 0) return invalid_argument(what + ": has no hole (no pixel <= 0.5)");
    return known;
}

Result<SynthesisInput> inpainting_input(const Image& image, const Image& known,
                                        const std::string& what) {
    if (known.width() != image.width() || known.height() != image.height()) {
        return invalid_argument(what + ": is " + std::to_string(known.width()) + "x" +
                                std::to_string(known.height()) + " but the image is " +
                                std::to_string(image.width()) + "x" +
                                std::to_string(image.height()));
    }
    if (known.channels() != 1) {
        return invalid_argument(what + ": has " + std::to_string(known.channels()) +
                                " channels (pass it through inpainting_known)");
    }
    const auto channels = static_cast<std::size_t>(image.channels());
    std::vector<double> mean(channels, 0.0);
    std::size_t count = 0;
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
        if (known.data()[i] <= 0.5f) continue;
        ++count;
        for (std::size_t c = 0; c < channels; ++c) mean[c] += image.data()[i * channels + c];
    }
    SynthesisInput in;
    in.style = image;
    in.initial_target = image;
    in.source_mask = known;
    in.target_mask = Image(image.width(), image.height(), 1, 0.0f);
    for (std::size_t i = 0; i < image.pixel_count(); ++i) {
        if (known.data()[i] > 0.5f) continue;
        in.target_mask.data()[i] = 1.0f;
        for (std::size_t c = 0; c < channels && count > 0; ++c) {
            in.initial_target.data()[i * channels + c] =
                static_cast<float>(mean[c] / static_cast<double>(count));
        }
    }
    return in;
}

}  // namespace exemplar
