// Highway kernels for ssd_rows; compiled once per SIMD target, dispatched at run time.
#include <atomic>

#include "ssd.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "ssd_simd.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace exemplar::synth {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// One pixel is stride / Lanes(df) whole vectors, so lane i of the k-th vector of a pixel is
// always byte k * Lanes + i and takes that byte's weight.
template <class DF>
float SsdRowsT(DF df, const std::uint8_t* a, std::size_t a_stride, const std::uint8_t* b,
               std::size_t b_stride, int rows, int pixels, int stride, SsdWeights weights,
               float bound) {
    const hn::RebindToSigned<DF> di;
    const hn::Rebind<std::uint8_t, DF> d8;
    const int lanes = static_cast<int>(hn::Lanes(df));
    const int blocks = stride / lanes;
    float sum = 0.0f;
    const float* wrow = weights.data;
    for (int r = 0; r < rows; ++r, a += a_stride, b += b_stride, wrow += weights.row_step) {
        auto acc0 = hn::Zero(df);
        auto acc1 = hn::Zero(df);
        const std::uint8_t* pa = a;
        const std::uint8_t* pb = b;
        const float* pw = wrow;
        for (int p = 0; p < pixels; ++p, pw += weights.pixel_step) {
            for (int k = 0; k < blocks; ++k, pa += lanes, pb += lanes) {
                const auto d = hn::ConvertTo(df, hn::Sub(hn::PromoteTo(di, hn::LoadU(d8, pa)),
                                                         hn::PromoteTo(di, hn::LoadU(d8, pb))));
                const auto wd = hn::Mul(hn::LoadU(df, pw + k * lanes), d);
                // Two accumulators: alternate pixels, to shorten the dependency chain.
                if (p % 2 == 0) {
                    acc0 = hn::MulAdd(wd, d, acc0);
                } else {
                    acc1 = hn::MulAdd(wd, d, acc1);
                }
            }
        }
        sum += hn::GetLane(hn::SumOfLanes(df, hn::Add(acc0, acc1)));
        if (sum > bound) return sum;
    }
    return sum;
}

float SsdRows(const std::uint8_t* a, std::size_t a_stride, const std::uint8_t* b,
              std::size_t b_stride, int rows, int pixels, int stride, SsdWeights weights,
              float bound) {
    // The widest vectors that divide the pixel stride (a multiple of 4).
    const hn::ScalableTag<float> df;
    if (stride % static_cast<int>(hn::Lanes(df)) == 0) {
        return SsdRowsT(df, a, a_stride, b, b_stride, rows, pixels, stride, weights, bound);
    }
    const hn::CappedTag<float, 8> d8;
    if (stride % static_cast<int>(hn::Lanes(d8)) == 0) {
        return SsdRowsT(d8, a, a_stride, b, b_stride, rows, pixels, stride, weights, bound);
    }
    const hn::CappedTag<float, 4> d4;
    return SsdRowsT(d4, a, a_stride, b, b_stride, rows, pixels, stride, weights, bound);
}

}  // namespace HWY_NAMESPACE
}  // namespace exemplar::synth
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace exemplar::synth {

HWY_EXPORT(SsdRows);

namespace {
std::atomic<bool> g_simd{true};
}

float ssd_rows_scalar(const std::uint8_t* a, std::size_t a_stride, const std::uint8_t* b,
                      std::size_t b_stride, int rows, int pixels, int stride, SsdWeights weights,
                      float bound) {
    float sum = 0.0f;
    const float* wrow = weights.data;
    for (int r = 0; r < rows; ++r, a += a_stride, b += b_stride, wrow += weights.row_step) {
        float row = 0.0f;
        for (int p = 0; p < pixels; ++p) {
            const float* w = wrow + static_cast<std::ptrdiff_t>(p) * weights.pixel_step;
            for (int c = 0; c < stride; ++c) {
                const int i = p * stride + c;
                const auto d = static_cast<float>(static_cast<int>(a[i]) - static_cast<int>(b[i]));
                row += w[c] * d * d;
            }
        }
        sum += row;
        if (sum > bound) return sum;
    }
    return sum;
}

float ssd_rows(const std::uint8_t* a, std::size_t a_stride, const std::uint8_t* b,
               std::size_t b_stride, int rows, int pixels, int stride, SsdWeights weights,
               float bound) {
    if (!g_simd.load(std::memory_order_relaxed)) {
        return ssd_rows_scalar(a, a_stride, b, b_stride, rows, pixels, stride, weights, bound);
    }
    return HWY_DYNAMIC_DISPATCH(SsdRows)(a, a_stride, b, b_stride, rows, pixels, stride, weights,
                                         bound);
}

void set_simd_enabled(bool enabled) {
    g_simd.store(enabled, std::memory_order_relaxed);
}
bool simd_enabled() {
    return g_simd.load(std::memory_order_relaxed);
}

const char* simd_target_name() {
    // Dispatch picks the best compiled target the CPU supports: the lowest set bit.
    const int64_t targets = hwy::SupportedTargets() & HWY_TARGETS;
    return hwy::TargetName(targets & -targets);
}

}  // namespace exemplar::synth
#endif  // HWY_ONCE
