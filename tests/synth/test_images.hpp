#pragma once
// Procedural test images shared by the synth tests.

#include <cmath>

#include "exemplar/core/image.hpp"
#include "exemplar/core/rng.hpp"

namespace exemplar::testing {

/// Smooth random texture in [0, 1] with `channels` channels (sum of a few random sinusoids plus
/// per-pixel noise), deterministic for a seed. (ox, oy) shifts the sinusoid field; the noise
/// comes from `noise_seed` (default: `seed`).
inline Image texture(int w, int h, int channels, std::uint64_t seed, float noise = 0.15f,
                     int ox = 0, int oy = 0, std::uint64_t noise_seed = 0) {
    if (noise_seed == 0) noise_seed = seed;
    Image im(w, h, channels);
    KeyedRng rng(seed, 0);
    for (int c = 0; c < channels; ++c) {
        float fx[3], fy[3], ph[3];
        for (int k = 0; k < 3; ++k) {
            fx[k] = 0.05f + 0.5f * rng.uniform();
            fy[k] = 0.05f + 0.5f * rng.uniform();
            ph[k] = 6.28f * rng.uniform();
        }
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                float v = 0.0f;
                for (int k = 0; k < 3; ++k) {
                    v += std::sin(fx[k] * static_cast<float>(x + ox) +
                                  fy[k] * static_cast<float>(y + oy) + ph[k]);
                }
                KeyedRng px(noise_seed, 1, static_cast<std::uint64_t>(c),
                            static_cast<std::uint64_t>(y * w + x));
                v = 0.5f + v / 6.0f * (1.0f - noise) + noise * (px.uniform() - 0.5f);
                im.at(x, y, c) = v;
            }
        }
    }
    return im;
}

/// Two-channel position ramp: (x / (w-1), y / (h-1)).
inline Image ramp(int w, int h) {
    Image im(w, h, 2);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            im.at(x, y, 0) = static_cast<float>(x) / static_cast<float>(w - 1);
            im.at(x, y, 1) = static_cast<float>(y) / static_cast<float>(h - 1);
        }
    }
    return im;
}

inline double psnr(const Image& a, const Image& b) {
    double se = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const double d = a.data()[i] - b.data()[i];
        se += d * d;
    }
    const double mse = se / static_cast<double>(a.size());
    return mse == 0.0 ? 1000.0 : 10.0 * std::log10(1.0 / mse);
}

}  // namespace exemplar::testing
