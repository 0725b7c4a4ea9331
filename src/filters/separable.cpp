#include "separable.hpp"

#include <algorithm>
#include <utility>

#include "exemplar/core/check.hpp"
#include "exemplar/core/parallel.hpp"

namespace exemplar::filters_detail {

void AxisWeights::add_output(std::vector<std::pair<int, double>> taps, int input_size) {
    EXEMPLAR_CHECK_GE(input_size, 1);
    // Clamp, then merge taps that clamped onto the same border sample. Taps arrive in increasing
    // index order, so equal indices are adjacent.
    std::vector<std::pair<int, double>> merged;
    for (auto [i, w] : taps) {
        i = std::clamp(i, 0, input_size - 1);
        if (w == 0.0) continue;
        if (!merged.empty() && merged.back().first == i) {
            merged.back().second += w;
        } else {
            merged.emplace_back(i, w);
        }
    }
    double sum = 0.0;
    for (const auto& tap : merged) sum += tap.second;
    EXEMPLAR_CHECK(sum > 0.0);
    for (const auto& [i, w] : merged) {
        index.push_back(i);
        weight.push_back(w / sum);
    }
    begin.push_back(static_cast<int>(index.size()));
}

namespace {

// One row of filter_rows; kChannels > 0 fixes the channel count at compile time (the
// accumulators then live in registers), 0 takes it from `channels`. Same sums either way.
template <int kChannels>
void filter_row(const float* src, float* dst, int channels, const AxisWeights& weights) {
    constexpr int kMax = kChannels > 0 ? kChannels : 1;
    const int C = kChannels > 0 ? kChannels : channels;
    std::vector<double> heap(kChannels > 0 ? 0 : static_cast<std::size_t>(C));
    double fixed[kMax];
    double* acc = kChannels > 0 ? fixed : heap.data();
    for (int x = 0; x < weights.size(); ++x) {
        std::fill(acc, acc + C, 0.0);
        for (int t = weights.begin[x]; t < weights.begin[x + 1]; ++t) {
            const double w = weights.weight[static_cast<std::size_t>(t)];
            const float* s =
                src + static_cast<std::size_t>(weights.index[t]) * static_cast<std::size_t>(C);
            for (int c = 0; c < C; ++c) acc[c] += w * s[c];
        }
        for (int c = 0; c < C; ++c) *dst++ = static_cast<float>(acc[c]);
    }
}

}  // namespace

Image filter_rows(const Image& image, const AxisWeights& weights, int threads) {
    const int out_width = weights.size();
    const int channels = image.channels();
    Image out(out_width, image.height(), channels);
    out.set_channel_names(image.channel_names());
    parallel_for(0, image.height(), threads, [&](int y) {
        const float* src = image.pixel(0, y);
        float* dst = out.pixel(0, y);
        switch (channels) {
            case 1: filter_row<1>(src, dst, channels, weights); break;
            case 2: filter_row<2>(src, dst, channels, weights); break;
            case 3: filter_row<3>(src, dst, channels, weights); break;
            case 4: filter_row<4>(src, dst, channels, weights); break;
            default: filter_row<0>(src, dst, channels, weights); break;
        }
    });
    return out;
}

Image filter_columns(const Image& image, const AxisWeights& weights, int threads) {
    const int out_height = weights.size();
    Image out(image.width(), out_height, image.channels());
    out.set_channel_names(image.channel_names());
    const std::size_t row_size =
        static_cast<std::size_t>(image.width()) * static_cast<std::size_t>(image.channels());
    parallel_for(0, out_height, threads, [&](int y) {
        std::vector<double> acc(row_size, 0.0);
        for (int t = weights.begin[y]; t < weights.begin[y + 1]; ++t) {
            const double w = weights.weight[static_cast<std::size_t>(t)];
            const float* src = image.pixel(0, weights.index[static_cast<std::size_t>(t)]);
            for (std::size_t i = 0; i < row_size; ++i) acc[i] += w * src[i];
        }
        float* dst = out.pixel(0, y);
        for (std::size_t i = 0; i < row_size; ++i) dst[i] = static_cast<float>(acc[i]);
    });
    return out;
}

}  // namespace exemplar::filters_detail
