// Gaussian blur: two 1-D passes of a sampled, truncated Gaussian with clamped borders.

#include <cmath>
#include <utility>

#include "exemplar/core/check.hpp"
#include "exemplar/filters/resample.hpp"
#include "separable.hpp"

namespace exemplar {

namespace {

// Sampled Gaussian of standard deviation `sigma_px`, truncated at 3 sigma, centred on each
// sample.
filters_detail::AxisWeights blur_weights(float sigma_px, int size) {
    const int radius = static_cast<int>(std::ceil(3.0 * sigma_px));
    std::vector<double> kernel;
    for (int d = -radius; d <= radius; ++d) {
        const double t = d / static_cast<double>(sigma_px);
        kernel.push_back(std::exp(-0.5 * t * t));
    }
    filters_detail::AxisWeights weights;
    std::vector<std::pair<int, double>> taps;
    for (int x = 0; x < size; ++x) {
        taps.clear();
        for (int d = -radius; d <= radius; ++d) {
            taps.emplace_back(x + d, kernel[static_cast<std::size_t>(d + radius)]);
        }
        weights.add_output(taps, size);
    }
    return weights;
}

}  // namespace

Image gaussian_blur(const Image& image, float sigma_px, int threads) {
    EXEMPLAR_CHECK(std::isfinite(sigma_px));
    if (sigma_px <= 0.0f || image.empty()) return image;
    Image rows = filters_detail::filter_rows(image, blur_weights(sigma_px, image.width()), threads);
    return filters_detail::filter_columns(rows, blur_weights(sigma_px, image.height()), threads);
}

}  // namespace exemplar
