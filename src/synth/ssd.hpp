#pragma once
// Sum of squared differences over a block of rows of contiguous floats: the inner loop of the
// patch distance. A Highway kernel with runtime dispatch (SSE4/AVX2/AVX-512, picked for the
// running CPU) sits beside the always-compiled scalar reference; tests compare the two.

#include <cstddef>

namespace exemplar::synth {

/// Sum over `rows` rows of sum over i < n of (a[i] - b[i])^2; row r starts at a + r * a_stride
/// and b + r * b_stride. Returns as soon as the running sum exceeds `bound` (after a row).
float ssd_rows(const float* a, std::size_t a_stride, const float* b, std::size_t b_stride, int rows,
               int n, float bound);

/// The scalar reference of ssd_rows (same contract).
float ssd_rows_scalar(const float* a, std::size_t a_stride, const float* b, std::size_t b_stride,
                      int rows, int n, float bound);

/// Whether ssd_rows uses the SIMD kernel (default true); false routes it to the scalar
/// reference, for benchmarks and tests. Not thread-safe: set it before running.
void set_simd_enabled(bool enabled);
bool simd_enabled();

/// Name of the SIMD target the dispatcher picked on this CPU (e.g. "AVX2").
const char* simd_target_name();

}  // namespace exemplar::synth
