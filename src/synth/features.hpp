#pragma once
// Patch features: the style and guide channels of one image as 8-bit codes. Channel c maps a
// value v to q = round((v - offset_c) / step_c), clamped to 0..255, with the same offset and step
// on the source and the target side, so that
//     sum_c weight_c * (v_source - v_target)^2  ~=  sum_c (weight_c * step_c^2) * (q_s - q_t)^2
// up to rounding each value by at most step_c / 2. Values on the 1/255 grid of 8-bit images
// are coded exactly. Quarter the memory of floats: a megapixel level's source and target
// features fit the L3 cache, which decides the speed of the random patch reads of PatchMatch
// (docs/PERFORMANCE.md). Internal to the synth module.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "ssd.hpp"

namespace exemplar::synth {

/// Interleaved 8-bit feature codes, one byte per channel and no padding (a patch row is one run
/// of bytes for the kernel, see ssd.hpp), with kSsdSlack readable bytes after the last pixel.
class FeatureImage {
public:
    FeatureImage() = default;
    FeatureImage(int width, int height, int channels)
        : width_(width),
          height_(height),
          channels_(channels),
          stride_(channels),
          data_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) *
                        static_cast<std::size_t>(stride_) +
                    kSsdSlack,
                0) {}

    int width() const { return width_; }
    int height() const { return height_; }
    int channels() const { return channels_; }
    int stride() const { return stride_; }
    bool empty() const { return width_ == 0 || height_ == 0; }
    std::size_t row_bytes() const {
        return static_cast<std::size_t>(width_) * static_cast<std::size_t>(stride_);
    }
    const std::uint8_t* pixel(int x, int y) const { return data_.data() + offset(x, y); }
    std::uint8_t* pixel(int x, int y) { return data_.data() + offset(x, y); }
    std::uint8_t* pixel(std::size_t index) {
        return data_.data() + index * static_cast<std::size_t>(stride_);
    }

private:
    std::size_t offset(int x, int y) const {
        return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                static_cast<std::size_t>(x)) *
               static_cast<std::size_t>(stride_);
    }

    int width_ = 0, height_ = 0, channels_ = 0, stride_ = 0;
    std::vector<std::uint8_t> data_;
};

/// The 8-bit code of one channel.
struct ChannelQuantizer {
    float offset = 0.0f;
    float step = 1.0f;

    /// round((v - offset) / step) clamped to 0..255, rounding halves to even.
    std::uint8_t code(float v) const {
        const float q = (v - offset) / step;
        if (!(q > 0.0f)) return 0;
        if (!(q < 255.5f)) return 255;
        // std::nearbyint without its libm call (every feature value of every level passes here):
        // q + 2^23 lies where floats are integers, so the sum is q rounded to nearest even
        // (2^23 is even) and subtracting 2^23 again is exact.
        constexpr float kInteger = 8388608.0f;
        return static_cast<std::uint8_t>((q + kInteger) - kInteger);
    }
    /// The definition code() computes: the test oracle.
    std::uint8_t code_reference(float v) const {
        const float q = std::nearbyint((v - offset) / step);
        return static_cast<std::uint8_t>(std::clamp(q, 0.0f, 255.0f));
    }
};

/// Quantizer for values in [lo, hi]: the 1/255 grid of 8-bit images when the range fits 256 of
/// its steps (exact for 8-bit inputs), else 255 equal steps over the range.
inline ChannelQuantizer quantizer_for_range(float lo, float hi) {
    ChannelQuantizer q;
    if (!(hi > lo)) {
        q.offset = std::isfinite(lo) ? lo : 0.0f;
        return q;
    }
    const float grid = 1.0f / 255.0f;
    const float offset = std::floor(lo * 255.0f) * grid;
    if ((hi - offset) * 255.0f <= 255.25f) {
        q.offset = offset;
        q.step = grid;
    } else {
        q.offset = lo;
        q.step = (hi - lo) / 255.0f;
    }
    return q;
}

}  // namespace exemplar::synth
