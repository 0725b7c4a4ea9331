#pragma once
// Weighted sum of squared differences of 8-bit feature codes over a block of rows: the inner loop
// of the patch distance. A Highway kernel with runtime dispatch (SSE4/AVX2/AVX-512, picked for
// the running CPU) sits beside the always-compiled scalar reference; tests compare the two.

#include <atomic>
#include <cstddef>
#include <cstdint>

namespace exemplar::synth {

/// How many bytes (and floats) past the end of a row ssd_rows may read; the values read there
/// are multiplied by zero. Buffers passed to ssd_rows need this much readable slack after the
/// last row (FeatureImage and the weight arrays of a Level have it).
inline constexpr int kSsdSlack = 64;

/// Weights of ssd_rows: byte i of row r is weighted by data[r * row_step + i]. A patch row is a
/// run of whole pixels, so a shared per-channel weight set is tiled along the row (row_step 0),
/// and a per-pixel weight map is read in place (row_step = floats per row of the map).
struct SsdWeights {
    const float* data = nullptr;
    std::size_t row_step = 0;
};

/// The signature of the kernels below.
using SsdRowsFn = float (*)(const std::uint8_t* a, std::size_t a_stride, const std::uint8_t* b,
                            std::size_t b_stride, int rows, int row_bytes, SsdWeights weights,
                            float bound);

/// The signature of the ssd_terms kernels.
using SsdTermsFn = void (*)(const std::uint8_t* a, const std::uint8_t* b, const float* w, int n,
                            float* out);

namespace detail {
/// The kernel ssd_terms calls (resolved with the ssd_rows kernel).
extern std::atomic<SsdTermsFn> g_terms_kernel;
SsdTermsFn resolve_terms_kernel();
/// The kernel ssd_rows calls: resolved once (the SIMD target for this CPU, or the scalar
/// reference while SIMD is disabled) instead of dispatching on every call, which the search
/// makes tens of millions of times.
extern std::atomic<SsdRowsFn> g_ssd_kernel;
SsdRowsFn resolve_ssd_kernel();
}  // namespace detail

/// Sum over `rows` rows of sum over i < row_bytes of w_r[i] * (a_r[i] - b_r[i])^2, where row r
/// starts at a + r * a_stride and b + r * b_stride and w_r is row r's weights (see SsdWeights).
/// Returns as soon as the running sum exceeds `bound` (after a row). May read up to kSsdSlack
/// bytes/floats past the end of each row.
inline float ssd_rows(const std::uint8_t* a, std::size_t a_stride, const std::uint8_t* b,
                      std::size_t b_stride, int rows, int row_bytes, SsdWeights weights,
                      float bound) {
    SsdRowsFn kernel = detail::g_ssd_kernel.load(std::memory_order_relaxed);
    if (kernel == nullptr) kernel = detail::resolve_ssd_kernel();
    return kernel(a, a_stride, b, b_stride, rows, row_bytes, weights, bound);
}

/// The terms of a weighted SSD, each rounded as the scalar expression rounds it:
/// out[i] = (w[i] * d) * d with d = a[i] - b[i] as a float, for i < n (two multiplications, never
/// fused), so that adding them in any fixed order gives that order's scalar sum to the bit. May
/// read kSsdSlack bytes/floats past a + n, b + n and w + n and write as many past out + n.
inline void ssd_terms(const std::uint8_t* a, const std::uint8_t* b, const float* w, int n,
                      float* out) {
    SsdTermsFn kernel = detail::g_terms_kernel.load(std::memory_order_relaxed);
    if (kernel == nullptr) kernel = detail::resolve_terms_kernel();
    kernel(a, b, w, n, out);
}

/// The scalar reference of ssd_terms (same contract; reads and writes nothing past n).
void ssd_terms_scalar(const std::uint8_t* a, const std::uint8_t* b, const float* w, int n,
                      float* out);

/// The scalar reference of ssd_rows (same contract; reads nothing past a row).
float ssd_rows_scalar(const std::uint8_t* a, std::size_t a_stride, const std::uint8_t* b,
                      std::size_t b_stride, int rows, int row_bytes, SsdWeights weights,
                      float bound);

/// The SIMD kernel of the chosen target one row at a time: each row's lanes summed, added and
/// the bound checked before the next row. The definition of ssd_rows' SIMD value, to the bit
/// (ssd_rows runs the same operations through kernels compiled for the common 5x5 shapes).
float ssd_rows_per_row(const std::uint8_t* a, std::size_t a_stride, const std::uint8_t* b,
                       std::size_t b_stride, int rows, int row_bytes, SsdWeights weights,
                       float bound);

/// Whether ssd_rows uses the SIMD kernel (default true); false routes it to the scalar
/// reference, for benchmarks and tests. Not thread-safe: set it before running.
void set_simd_enabled(bool enabled);
bool simd_enabled();

/// Name of the SIMD target the dispatcher picked on this CPU (e.g. "AVX2").
const char* simd_target_name();

}  // namespace exemplar::synth
