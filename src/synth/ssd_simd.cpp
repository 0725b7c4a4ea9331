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

float SsdRows(const float* a, std::size_t a_stride, const float* b, std::size_t b_stride, int rows,
              int n, float bound) {
    const hn::ScalableTag<float> d;
    const std::size_t lanes = hn::Lanes(d);
    const std::size_t count = static_cast<std::size_t>(n);
    float sum = 0.0f;
    for (int r = 0; r < rows; ++r, a += a_stride, b += b_stride) {
        auto acc0 = hn::Zero(d);
        auto acc1 = hn::Zero(d);
        std::size_t i = 0;
        for (; i + 2 * lanes <= count; i += 2 * lanes) {
            const auto d0 = hn::Sub(hn::LoadU(d, a + i), hn::LoadU(d, b + i));
            const auto d1 = hn::Sub(hn::LoadU(d, a + i + lanes), hn::LoadU(d, b + i + lanes));
            acc0 = hn::MulAdd(d0, d0, acc0);
            acc1 = hn::MulAdd(d1, d1, acc1);
        }
        for (; i + lanes <= count; i += lanes) {
            const auto d0 = hn::Sub(hn::LoadU(d, a + i), hn::LoadU(d, b + i));
            acc0 = hn::MulAdd(d0, d0, acc0);
        }
        // Tail: 4-lane vectors, then scalars; nothing is read past the row.
        const hn::CappedTag<float, 4> d4;
        auto acc4 = hn::Zero(d4);
        for (; i + 4 <= count; i += 4) {
            const auto d0 = hn::Sub(hn::LoadU(d4, a + i), hn::LoadU(d4, b + i));
            acc4 = hn::MulAdd(d0, d0, acc4);
        }
        float tail = hn::GetLane(hn::SumOfLanes(d4, acc4));
        for (; i < count; ++i) {
            const float diff = a[i] - b[i];
            tail += diff * diff;
        }
        sum += hn::GetLane(hn::SumOfLanes(d, hn::Add(acc0, acc1))) + tail;
        if (sum > bound) return sum;
    }
    return sum;
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

float ssd_rows_scalar(const float* a, std::size_t a_stride, const float* b, std::size_t b_stride,
                      int rows, int n, float bound) {
    float sum = 0.0f;
    for (int r = 0; r < rows; ++r, a += a_stride, b += b_stride) {
        float row = 0.0f;
        for (int i = 0; i < n; ++i) {
            const float diff = a[i] - b[i];
            row += diff * diff;
        }
        sum += row;
        if (sum > bound) return sum;
    }
    return sum;
}

float ssd_rows(const float* a, std::size_t a_stride, const float* b, std::size_t b_stride, int rows,
               int n, float bound) {
    if (!g_simd.load(std::memory_order_relaxed)) {
        return ssd_rows_scalar(a, a_stride, b, b_stride, rows, n, bound);
    }
    return HWY_DYNAMIC_DISPATCH(SsdRows)(a, a_stride, b, b_stride, rows, n, bound);
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
