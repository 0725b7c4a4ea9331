// Resizing with separable filters and Gaussian pyramids.
//
// Coordinates: output sample x of an axis resized from `in` to `out` samples sits at input
// position u = (x + 0.5) * in / out - 0.5 (pixel centres aligned, edges aligned). When shrinking,
// kernels are widened by the reduction factor in/out so they average over the output footprint
// (prefiltering); when enlarging they keep their input-pixel width. An axis whose size does not
// change is copied unchanged, for every filter.

#include "exemplar/filters/resample.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>

#include "exemplar/core/check.hpp"
#include "exemplar/core/parallel.hpp"
#include "separable.hpp"

namespace exemplar {

namespace {

using filters_detail::AxisWeights;

// Input index point-sampled by output sample x: floor((x + 0.5) * in / out), in exact integer
// arithmetic so that labels are picked reproducibly.
int nearest_index(int x, int in, int out) {
    const std::int64_t i =
        (2 * static_cast<std::int64_t>(x) + 1) * in / (2 * static_cast<std::int64_t>(out));
    return static_cast<int>(std::min<std::int64_t>(i, in - 1));
}

double sinc(double x) {
    if (x == 0.0) return 1.0;
    const double px = std::numbers::pi * x;
    return std::sin(px) / px;
}

// Taps of one output sample for the filter; `scale` = max(1, in / out).
std::vector<std::pair<int, double>> taps_for(ResampleFilter filter, int x, int in, int out) {
    const double ratio = static_cast<double>(in) / out;
    const double scale = std::max(1.0, ratio);
    const double u = (x + 0.5) * ratio - 0.5;
    std::vector<std::pair<int, double>> taps;
    switch (filter) {
        case ResampleFilter::Nearest: taps.emplace_back(nearest_index(x, in, out), 1.0); break;
        case ResampleFilter::Box: {
            if (ratio <= 1.0) {  // enlarging: nearest input pixel
                taps.emplace_back(nearest_index(x, in, out), 1.0);
                break;
            }
            // Overlap of input pixel i, covering [i, i + 1), with the footprint [left, right).
            const double left = x * ratio;
            const double right = (x + 1) * ratio;
            for (int i = static_cast<int>(std::floor(left)); i < right; ++i) {
                const double w = std::min(right, i + 1.0) - std::max(left, static_cast<double>(i));
                if (w > 0.0) taps.emplace_back(i, w);
            }
            break;
        }
        case ResampleFilter::Gaussian: {
            const double sigma = 0.5 * scale;
            const double radius = 3.0 * sigma;
            for (int i = static_cast<int>(std::ceil(u - radius)); i <= u + radius; ++i) {
                const double d = (i - u) / sigma;
                taps.emplace_back(i, std::exp(-0.5 * d * d));
            }
            break;
        }
        case ResampleFilter::Lanczos3: {
            const double radius = 3.0 * scale;
            for (int i = static_cast<int>(std::ceil(u - radius)); i <= u + radius; ++i) {
                const double t = (i - u) / scale;
                if (std::abs(t) < 3.0) taps.emplace_back(i, sinc(t) * sinc(t / 3.0));
            }
            break;
        }
    }
    return taps;
}

AxisWeights resample_weights(ResampleFilter filter, int in, int out) {
    AxisWeights weights;
    for (int x = 0; x < out; ++x) weights.add_output(taps_for(filter, x, in, out), in);
    return weights;
}

}  // namespace

Image resize(const Image& image, int width, int height, ResampleFilter filter, int threads) {
    EXEMPLAR_CHECK_GE(width, 1);
    EXEMPLAR_CHECK_GE(height, 1);
    if (image.empty()) return {};
    // Filter the axis that shrinks most first, so the second pass runs on fewer samples; the
    // order depends only on the sizes, so results stay deterministic. The first pass reads the
    // input in place (a copy of a full-resolution input per pyramid level was a tenth of a small
    // preview's serial time).
    const Image* current = &image;
    Image out;
    const bool columns_first =
        static_cast<double>(height) / image.height() < static_cast<double>(width) / image.width();
    auto do_rows = [&] {
        if (width != current->width()) {
            out = filters_detail::filter_rows(
                *current, resample_weights(filter, current->width(), width), threads);
            current = &out;
        }
    };
    auto do_columns = [&] {
        if (height != current->height()) {
            out = filters_detail::filter_columns(
                *current, resample_weights(filter, current->height(), height), threads);
            current = &out;
        }
    };
    if (columns_first) {
        do_columns();
        do_rows();
    } else {
        do_rows();
        do_columns();
    }
    if (current == &image) return image;
    return out;
}

int pyramid_level_size(int size, float ratio, int level) {
    EXEMPLAR_CHECK_GE(size, 1);
    EXEMPLAR_CHECK_GE(level, 0);
    EXEMPLAR_CHECK(ratio > 0.0f && ratio < 1.0f);
    const double scaled = size * std::pow(static_cast<double>(ratio), level);
    return std::max(1, static_cast<int>(std::lround(scaled)));
}

std::vector<Image> gaussian_pyramid(const Image& image, int levels, float ratio,
                                    ResampleFilter filter, int threads) {
    EXEMPLAR_CHECK_GE(levels, 1);
    EXEMPLAR_CHECK(ratio > 0.0f && ratio < 1.0f);
    std::vector<Image> pyramid;
    pyramid.reserve(static_cast<std::size_t>(levels));
    pyramid.push_back(image);
    for (int level = 1; level < levels; ++level) {
        if (image.empty()) {
            pyramid.emplace_back();
            continue;
        }
        // Every level is resampled from full resolution: the kernel widens with the reduction,
        // so each level is prefiltered once instead of accumulating blur level after level.
        pyramid.push_back(resize(image, pyramid_level_size(image.width(), ratio, level),
                                 pyramid_level_size(image.height(), ratio, level), filter,
                                 threads));
    }
    return pyramid;
}

}  // namespace exemplar
