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

// A row's vector of weighted squared differences, whose lanes add up to the row's sum. A row is
// processed as one run of bytes, whatever the pixel stride: Lanes(df) bytes per step, the last
// step masked by zero weights (the bytes and floats it reads past the row are finite: see
// kSsdSlack).
template <class DF>
HWY_INLINE hn::Vec<DF> RowTerms(DF df, const std::uint8_t* a, const std::uint8_t* b, const float* w,
                                int row_bytes) {
    const hn::RebindToSigned<DF> di;
    const hn::Rebind<std::uint8_t, DF> d8;
    const int lanes = static_cast<int>(hn::Lanes(df));
    const int full = row_bytes / lanes * lanes;
    auto acc0 = hn::Zero(df);
    auto acc1 = hn::Zero(df);
    auto diff = [&](int i) {
        return hn::ConvertTo(df, hn::Sub(hn::PromoteTo(di, hn::LoadU(d8, a + i)),
                                         hn::PromoteTo(di, hn::LoadU(d8, b + i))));
    };
    int i = 0;
    // Two accumulators to shorten the dependency chain.
    for (; i + 2 * lanes <= full; i += 2 * lanes) {
        const auto d0 = diff(i);
        const auto d1 = diff(i + lanes);
        acc0 = hn::MulAdd(hn::Mul(hn::LoadU(df, w + i), d0), d0, acc0);
        acc1 = hn::MulAdd(hn::Mul(hn::LoadU(df, w + i + lanes), d1), d1, acc1);
    }
    if (i < full) {
        const auto d0 = diff(i);
        acc0 = hn::MulAdd(hn::Mul(hn::LoadU(df, w + i), d0), d0, acc0);
        i += lanes;
    }
    if (i < row_bytes) {
        const auto d1 = diff(i);
        const auto tail_mask = hn::FirstN(df, static_cast<std::size_t>(row_bytes - full));
        const auto wt = hn::IfThenElseZero(tail_mask, hn::LoadU(df, w + i));
        acc1 = hn::MulAdd(hn::Mul(wt, d1), d1, acc1);
    }
    return hn::Add(acc0, acc1);
}

// GetLane(SumOfLanes(v)): on 512-bit targets the intrinsic SumOfLanes broadcasts, without the
// broadcast (one instruction less per row).
template <class DF>
HWY_INLINE float LaneSum(DF df, hn::Vec<DF> v) {
#if HWY_TARGET == HWY_AVX3 || HWY_TARGET == HWY_AVX3_DL
    if constexpr (hn::MaxLanes(df) == 16) return _mm512_reduce_add_ps(v.raw);
#endif
    return hn::GetLane(hn::SumOfLanes(df, v));
}

// Row after row: each row's lanes summed, added to the running sum, and the bound checked.
template <class DF>
HWY_INLINE float SumRows(DF df, const std::uint8_t* a, std::size_t a_stride, const std::uint8_t* b,
                         std::size_t b_stride, int rows, int row_bytes, SsdWeights weights,
                         float bound) {
    if (rows <= 0) return 0.0f;
    // The first row's sum starts the running sum: adding it to 0 would change no bit (every
    // lane is a sum of products w·d·d >= +0, never -0).
    float sum = LaneSum(df, RowTerms(df, a, b, weights.data, row_bytes));
    if (sum > bound) return sum;
    const float* w = weights.data;
    for (int r = 1; r < rows; ++r) {
        a += a_stride;
        b += b_stride;
        w += weights.row_step;
        sum += LaneSum(df, RowTerms(df, a, b, w, row_bytes));
        if (sum > bound) return sum;
    }
    return sum;
}

// SumRows for any shape: the definition of ssd_rows' SIMD value.
template <class DF>
HWY_NOINLINE float SsdRowsPerRowT(DF df, const std::uint8_t* a, std::size_t a_stride,
                                  const std::uint8_t* b, std::size_t b_stride, int rows,
                                  int row_bytes, SsdWeights weights, float bound) {
    return SumRows(df, a, a_stride, b, b_stride, rows, row_bytes, weights, bound);
}

// The same operations with the shape known when compiling: the row loop unrolled, the vector
// steps and the tail's mask fixed, no loop counters.
template <int kRows, int kRowBytes, class DF>
HWY_NOINLINE float SsdRowsFixedT(DF df, const std::uint8_t* a, std::size_t a_stride,
                                 const std::uint8_t* b, std::size_t b_stride, SsdWeights weights,
                                 float bound) {
    return SumRows(df, a, a_stride, b, b_stride, kRows, kRowBytes, weights, bound);
}

// 5x5 patches of 3, 4 and 6 channels (colour; colour and one guide; colour and a colour guide),
// most of a search's distances; every other shape takes the loops.
template <class DF>
float SsdRowsT(DF df, const std::uint8_t* a, std::size_t a_stride, const std::uint8_t* b,
               std::size_t b_stride, int rows, int row_bytes, SsdWeights weights, float bound) {
    if (rows == 5) {
        switch (row_bytes) {
            case 15: return SsdRowsFixedT<5, 15>(df, a, a_stride, b, b_stride, weights, bound);
            case 20: return SsdRowsFixedT<5, 20>(df, a, a_stride, b, b_stride, weights, bound);
            case 30: return SsdRowsFixedT<5, 30>(df, a, a_stride, b, b_stride, weights, bound);
            default: break;
        }
    }
    return SsdRowsPerRowT(df, a, a_stride, b, b_stride, rows, row_bytes, weights, bound);
}

float SsdRows(const std::uint8_t* a, std::size_t a_stride, const std::uint8_t* b,
              std::size_t b_stride, int rows, int row_bytes, SsdWeights weights, float bound) {
    const hn::ScalableTag<float> df;
    return SsdRowsT(df, a, a_stride, b, b_stride, rows, row_bytes, weights, bound);
}

float SsdRowsPerRow(const std::uint8_t* a, std::size_t a_stride, const std::uint8_t* b,
                    std::size_t b_stride, int rows, int row_bytes, SsdWeights weights,
                    float bound) {
    const hn::ScalableTag<float> df;
    return SsdRowsPerRowT(df, a, a_stride, b, b_stride, rows, row_bytes, weights, bound);
}

// Two roundings per term, (w * d) * d, as the scalar expression: Mul, never MulAdd.
void SsdTerms(const std::uint8_t* a, const std::uint8_t* b, const float* w, int n, float* out) {
    const hn::ScalableTag<float> df;
    const hn::RebindToSigned<decltype(df)> di;
    const hn::Rebind<std::uint8_t, decltype(df)> d8;
    const int lanes = static_cast<int>(hn::Lanes(df));
    for (int i = 0; i < n; i += lanes) {
        const auto d = hn::ConvertTo(df, hn::Sub(hn::PromoteTo(di, hn::LoadU(d8, a + i)),
                                                 hn::PromoteTo(di, hn::LoadU(d8, b + i))));
        hn::StoreU(hn::Mul(hn::Mul(hn::LoadU(df, w + i), d), d), df, out + i);
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace exemplar::synth
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace exemplar::synth {

HWY_EXPORT(SsdRows);
HWY_EXPORT(SsdTerms);
HWY_EXPORT(SsdRowsPerRow);

namespace {
std::atomic<bool> g_simd{true};
}

namespace detail {

std::atomic<SsdRowsFn> g_ssd_kernel{nullptr};
std::atomic<SsdTermsFn> g_terms_kernel{nullptr};

SsdRowsFn resolve_ssd_kernel() {
    SsdRowsFn kernel = &ssd_rows_scalar;
    SsdTermsFn terms = &ssd_terms_scalar;
    if (g_simd.load(std::memory_order_relaxed)) {
        // The entries HWY_DYNAMIC_DISPATCH would call, once the target has been chosen.
        hwy::ChosenTarget& chosen = hwy::GetChosenTarget();
        if (!chosen.IsInitialized()) chosen.Update(hwy::SupportedTargets());
        kernel = HWY_DISPATCH_TABLE(SsdRows)[chosen.GetIndex()];
        terms = HWY_DISPATCH_TABLE(SsdTerms)[chosen.GetIndex()];
    }
    g_terms_kernel.store(terms, std::memory_order_relaxed);
    g_ssd_kernel.store(kernel, std::memory_order_relaxed);
    return kernel;
}

SsdTermsFn resolve_terms_kernel() {
    resolve_ssd_kernel();
    return g_terms_kernel.load(std::memory_order_relaxed);
}

}  // namespace detail

float ssd_rows_scalar(const std::uint8_t* a, std::size_t a_stride, const std::uint8_t* b,
                      std::size_t b_stride, int rows, int row_bytes, SsdWeights weights,
                      float bound) {
    float sum = 0.0f;
    const float* w = weights.data;
    for (int r = 0; r < rows; ++r, a += a_stride, b += b_stride, w += weights.row_step) {
        float row = 0.0f;
        for (int i = 0; i < row_bytes; ++i) {
            const auto d = static_cast<float>(static_cast<int>(a[i]) - static_cast<int>(b[i]));
            row += w[i] * d * d;
        }
        sum += row;
        if (sum > bound) return sum;
    }
    return sum;
}

float ssd_rows_per_row(const std::uint8_t* a, std::size_t a_stride, const std::uint8_t* b,
                       std::size_t b_stride, int rows, int row_bytes, SsdWeights weights,
                       float bound) {
    return HWY_DYNAMIC_DISPATCH(SsdRowsPerRow)(a, a_stride, b, b_stride, rows, row_bytes, weights,
                                               bound);
}

void ssd_terms_scalar(const std::uint8_t* a, const std::uint8_t* b, const float* w, int n,
                      float* out) {
    for (int i = 0; i < n; ++i) {
        const auto d = static_cast<float>(static_cast<int>(a[i]) - static_cast<int>(b[i]));
        out[i] = w[i] * d * d;
    }
}

void set_simd_enabled(bool enabled) {
    g_simd.store(enabled, std::memory_order_relaxed);
    detail::resolve_ssd_kernel();
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
