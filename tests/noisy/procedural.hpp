#pragma once
// Procedural inputs of the Color Me Noisy tests (a crayon-like drawing medium and a flat-coloured
// reference animation, so the tests need no files) and the measures the tests and bench_noisy
// share.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/rng.hpp"

namespace exemplar::noisy::testing {

// Smooth value noise in [0, 1): random values on a lattice of `cell` pixels, bicubic-smoothstep
// interpolated.
inline float value_noise(int x, int y, int cell, std::uint64_t key) {
    const int cx = x / cell, cy = y / cell;
    auto at = [&](int i, int j) {
        return KeyedRng(key, static_cast<std::uint64_t>(i), static_cast<std::uint64_t>(j))
            .uniform();
    };
    auto smooth = [](float t) { return t * t * (3.0f - 2.0f * t); };
    const float fx = smooth(static_cast<float>(x % cell) / cell);
    const float fy = smooth(static_cast<float>(y % cell) / cell);
    const float top = at(cx, cy) * (1 - fx) + at(cx + 1, cy) * fx;
    const float bottom = at(cx, cy + 1) * (1 - fx) + at(cx + 1, cy + 1) * fx;
    return top * (1 - fy) + bottom * fy;
}

// The two colours of the reference, and a medium that contains both at many brightnesses:
// large blotches blending paper and pigment, a middle octave, and a fine grain.
constexpr float kPaper[3] = {0.80f, 0.74f, 0.62f};
constexpr float kPigment[3] = {0.30f, 0.38f, 0.55f};

inline Image medium(int width, int height, std::uint64_t key = 1) {
    Image image(width, height, 3);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float blend = std::clamp(1.6f * value_noise(x, y, 24, key) - 0.3f +
                                               0.3f * (value_noise(x, y, 6, key + 1) - 0.5f),
                                           0.0f, 1.0f);
            const float grain = 0.16f * (value_noise(x, y, 2, key + 2) - 0.5f) +
                                0.08f * (KeyedRng(key + 3, static_cast<std::uint64_t>(x),
                                                  static_cast<std::uint64_t>(y))
                                             .uniform() -
                                         0.5f);
            for (int c = 0; c < 3; ++c) {
                image.at(x, y, c) = kPaper[c] * (1 - blend) + kPigment[c] * blend + grain;
            }
        }
    }
    return image;
}

// Flat-coloured cel: paper background with a pigment disc of radius `radius` at (cx, cy) and a
// pigment band along the bottom (the lowest 3/10 of the height).
inline Image cel(int width, int height, double cx, double cy, double radius) {
    Image image(width, height, 3);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const bool inside = std::hypot(x - cx, y - cy) <= radius || y >= height * 7 / 10;
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = inside ? kPigment[c] : kPaper[c];
        }
    }
    return image;
}

// Mean over pixels and channels of the temporal variance of a static-reference sequence.
inline double temporal_energy(const std::vector<Image>& frames, int x0 = 0, int y0 = 0, int x1 = -1,
                              int y1 = -1) {
    const Image& first = frames.front();
    if (x1 < 0) x1 = first.width();
    if (y1 < 0) y1 = first.height();
    const double n = static_cast<double>(frames.size());
    double sum = 0.0;
    long count = 0;
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
            for (int c = 0; c < first.channels(); ++c) {
                double mean = 0.0, square = 0.0;
                for (const Image& f : frames) {
                    mean += f.at(x, y, c);
                    square += static_cast<double>(f.at(x, y, c)) * f.at(x, y, c);
                }
                mean /= n;
                sum += square / n - mean * mean;
                ++count;
            }
        }
    }
    return sum / static_cast<double>(count);
}

// RMS difference over pixels and channels of two images of the same size.
inline double rms_difference(const Image& a, const Image& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const double d = a.data()[i] - b.data()[i];
        sum += d * d;
    }
    return std::sqrt(sum / static_cast<double>(a.size()));
}

// The image with every channel replaced by its mean.
inline Image uniform_like(const Image& image) {
    Image flat = image;
    for (int c = 0; c < image.channels(); ++c) {
        double mean = 0.0;
        for (int y = 0; y < image.height(); ++y) {
            for (int x = 0; x < image.width(); ++x) mean += image.at(x, y, c);
        }
        mean /= static_cast<double>(image.pixel_count());
        for (int y = 0; y < image.height(); ++y) {
            for (int x = 0; x < image.width(); ++x) flat.at(x, y, c) = static_cast<float>(mean);
        }
    }
    return flat;
}

}  // namespace exemplar::noisy::testing
