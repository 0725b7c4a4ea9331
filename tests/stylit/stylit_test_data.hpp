#pragma once
// Shared helpers of the stylit tests: the bundled StyLit example (examples/stylit, 600x456) and
// small image measures.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/filters/resample.hpp"
#include "exemplar/io/image_io.hpp"

namespace exemplar::testing {

inline std::string example_path(const std::string& name) {
    return std::string(EXEMPLAR_SOURCE_DIR) + "/examples/stylit/" + name;
}

/// Loads a bundled example image, optionally shrunk by an integer factor (area average).
inline Image load_example(const std::string& name, int shrink = 1) {
    auto image = load_image(example_path(name));
    EXPECT_TRUE(image.ok()) << image.status().message();
    if (!image.ok()) return {};
    if (shrink == 1) return std::move(image).value();
    return resize(*image, image->width() / shrink, image->height() / shrink, ResampleFilter::Box);
}

/// Mean of the colour channels' luminance-like average at a pixel.
inline float grey_at(const Image& image, int x, int y) {
    const int colour = image.channels() >= 3 ? 3 : 1;
    float sum = 0.0f;
    for (int c = 0; c < colour; ++c) sum += image.at(x, y, c);
    return sum / static_cast<float>(colour);
}

inline double mean_abs_diff(const Image& a, const Image& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) sum += std::abs(a.data()[i] - b.data()[i]);
    return sum / static_cast<double>(a.size());
}

inline double peak_snr(const Image& a, const Image& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const double d = a.data()[i] - b.data()[i];
        sum += d * d;
    }
    return 10.0 * std::log10(1.0 / (sum / static_cast<double>(a.size())));
}

}  // namespace exemplar::testing
