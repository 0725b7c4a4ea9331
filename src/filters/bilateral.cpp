// The bilateral filter (Tomasi and Manduchi 1998), brute force over a (4σ + 1)² window with the
// range weight from a table: the callers (the line-feature brush's base/detail split) filter
// small crops once per selection.

#include "exemplar/filters/bilateral.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "exemplar/core/check.hpp"
#include "exemplar/core/parallel.hpp"

namespace exemplar {

Image bilateral_filter(const Image& image, float sigma_space_px, float sigma_range, int threads) {
    EXEMPLAR_CHECK(std::isfinite(sigma_space_px) && std::isfinite(sigma_range));
    if (sigma_space_px <= 0.0f || sigma_range <= 0.0f || image.empty()) return image;
    const int radius = static_cast<int>(std::ceil(2.0f * sigma_space_px));
    const int side = 2 * radius + 1;
    std::vector<float> spatial(static_cast<std::size_t>(side) * side);
    for (int dy = -radius; dy <= radius; ++dy) {
        for (int dx = -radius; dx <= radius; ++dx) {
            spatial[static_cast<std::size_t>((dy + radius) * side + dx + radius)] = std::exp(
                -0.5f * static_cast<float>(dx * dx + dy * dy) / (sigma_space_px * sigma_space_px));
        }
    }
    // The range weight from a table over the squared distance, up to where it falls below 1e-6
    // (beyond: 0); an exp per tap was most of the filter's time.
    constexpr int kTable = 4096;
    const float cutoff = 2.0f * 13.8f * sigma_range * sigma_range;
    const float to_index = static_cast<float>(kTable - 1) / cutoff;
    std::vector<float> range_weight(kTable);
    for (int i = 0; i < kTable; ++i) {
        const float d2 = static_cast<float>(i) / to_index;
        range_weight[static_cast<std::size_t>(i)] =
            std::exp(-0.5f * d2 / (sigma_range * sigma_range));
    }
    const int w = image.width(), h = image.height(), channels = image.channels();
    Image out(w, h, channels);
    out.set_channel_names(image.channel_names());
    parallel_for(0, h, threads, [&](int y) {
        std::vector<double> sum(static_cast<std::size_t>(channels));
        for (int x = 0; x < w; ++x) {
            const float* centre = image.pixel(x, y);
            std::fill(sum.begin(), sum.end(), 0.0);
            double total = 0.0;
            for (int dy = -radius; dy <= radius; ++dy) {
                const int sy = std::clamp(y + dy, 0, h - 1);
                for (int dx = -radius; dx <= radius; ++dx) {
                    const float* p = image.pixel(std::clamp(x + dx, 0, w - 1), sy);
                    float d2 = 0.0f;
                    for (int c = 0; c < channels; ++c)
                        d2 += (p[c] - centre[c]) * (p[c] - centre[c]);
                    if (!(d2 < cutoff)) continue;
                    const double weight =
                        spatial[static_cast<std::size_t>((dy + radius) * side + dx + radius)] *
                        range_weight[static_cast<std::size_t>(d2 * to_index + 0.5f)];
                    total += weight;
                    for (int c = 0; c < channels; ++c)
                        sum[static_cast<std::size_t>(c)] += weight * p[c];
                }
            }
            float* o = out.pixel(x, y);
            for (int c = 0; c < channels; ++c)
                o[c] = static_cast<float>(sum[static_cast<std::size_t>(c)] / total);
        }
    });
    return out;
}

}  // namespace exemplar
