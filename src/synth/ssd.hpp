#pragma once
// Weighted sum of squared differences of 8-bit feature codes over a block of rows: the inner loop
// of the patch distance. A Highway kernel with runtime dispatch (SSE4/AVX2/AVX-512, picked for
// the running CPU) sits beside the always-compiled scalar reference; tests compare the two.

#include <cstddef>
#include <cstdint>

namespace exemplar::synth {

/// Where the weights of ssd_rows come from: pixel p of row r uses the `stride` floats at
/// data + r * row_step + p * pixel_step. Steps 0 share one set of weights (per channel); a
/// per-pixel weight map uses pixel_step = stride and row_step = floats per row of the map.
struct SsdWeights {
    const float* data = nullptr;
    std::size_t row_step = 0;
    int pixel_step = 0;
};

/// Sum over `rows` rows of sum over `pixels` pixels of sum over c < stride of
/// w[c] * (a[c] - b[c])^2 (w: that pixel's weights, see SsdWeights), where a row holds `pixels`
/// consecutive pixels of `stride` bytes, row r starts at a + r * a_stride and b + r * b_stride,
/// and stride is a multiple of 4. Returns as soon as the running sum exceeds `bound` (after a
/// row).
float ssd_rows(const std::uint8_t* a, std::size_t a_stride, const std::uint8_t* b,
               std::size_t b_stride, int rows, int pixels, int stride, SsdWeights weights,
               float bound);

/// The scalar reference of ssd_rows (same contract).
float ssd_rows_scalar(const std::uint8_t* a, std::size_t a_stride, const std::uint8_t* b,
                      std::size_t b_stride, int rows, int pixels, int stride, SsdWeights weights,
                      float bound);

/// Whether ssd_rows uses the SIMD kernel (default true); false routes it to the scalar
/// reference, for benchmarks and tests. Not thread-safe: set it before running.
void set_simd_enabled(bool enabled);
bool simd_enabled();

/// Name of the SIMD target the dispatcher picked on this CPU (e.g. "AVX2").
const char* simd_target_name();

}  // namespace exemplar::synth
