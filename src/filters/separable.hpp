#pragma once
// Separable filtering: a 1-D weight table per axis, applied along rows and then columns.
//
// Each output sample is a weighted sum of input samples whose indices are already clamped to the
// image (clamped borders), with weights normalized to sum to 1 so that constant images stay
// constant. Sums are accumulated in double in a fixed order, one output row per task, so results
// are bit-identical for any thread count.

#include <vector>

#include "exemplar/core/image.hpp"

namespace exemplar::filters_detail {

/// Weights producing `size()` output samples from an input axis.
struct AxisWeights {
    std::vector<int> begin = {0};  ///< Taps of output i are [begin[i], begin[i + 1]).
    std::vector<int> index;        ///< Input index of each tap (clamped, strictly increasing).
    std::vector<double> weight;    ///< Weight of each tap.

    int size() const { return static_cast<int>(begin.size()) - 1; }

    /// Appends one output sample from (input index, weight) taps: indices are clamped to
    /// [0, input_size), taps landing on the same index are merged, zero weights dropped, and
    /// the weights normalized to sum 1.
    void add_output(std::vector<std::pair<int, double>> taps, int input_size);
};

/// Filters along x: output is `weights.size()` wide and as tall as `image`.
Image filter_rows(const Image& image, const AxisWeights& weights, int threads);

/// Filters along y: output is `weights.size()` tall and as wide as `image`.
Image filter_columns(const Image& image, const AxisWeights& weights, int threads);

}  // namespace exemplar::filters_detail
