#pragma once
// Procedural, tileable test patterns (no files): Poisson-disc stipples, hatching, halftone dots.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "exemplar/core/image.hpp"
#include "exemplar/core/rng.hpp"

namespace exemplar::npr::testing {

// Toroidal distance between two coordinates on a period n.
inline float torus_delta(float a, float b, float n) {
    float d = std::fabs(a - b);
    return std::min(d, n - d);
}

// Stipple screen: the distance to the nearest of Poisson-disc points (dart throwing with a
// minimum distance `spacing` px on the torus, keyed by `seed`), divided by `spacing`, clamped
// to 1. Thresholding it at t gives dots that grow with t (a stipple halftone screen).
inline Image stipple_pattern(int size, float spacing, std::uint64_t seed = 7) {
    std::vector<std::pair<float, float>> dots;
    KeyedRng rng(seed, 1);
    const float n = static_cast<float>(size);
    const int attempts = static_cast<int>(30.0f * n * n / (spacing * spacing));
    for (int attempt = 0; attempt < attempts; ++attempt) {
        const float x = rng.uniform() * n, y = rng.uniform() * n;
        bool far = true;
        for (const auto& [dx, dy] : dots) {
            const float ex = torus_delta(x, dx, n), ey = torus_delta(y, dy, n);
            if (ex * ex + ey * ey < spacing * spacing) {
                far = false;
                break;
            }
        }
        if (far) dots.emplace_back(x, y);
    }
    Image image(size, size, 1, 1.0f);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            for (const auto& [dx, dy] : dots) {
                const float ex = torus_delta(static_cast<float>(x) + 0.5f, dx, n);
                const float ey = torus_delta(static_cast<float>(y) + 0.5f, dy, n);
                image.at(x, y, 0) =
                    std::min(image.at(x, y, 0), std::sqrt(ex * ex + ey * ey) / spacing);
            }
    return image;
}

// Horizontal hatching: dark lines of `thickness` px every `period` px, with a slow wobble and
// a darkness ramp across each line (size must be a multiple of period to tile).
inline Image hatching_pattern(int size, int period, float thickness) {
    Image image(size, size, 1, 1.0f);
    const float pi = 3.14159265f;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float wobble = 0.6f * std::sin(2.0f * pi * static_cast<float>(x) /
                                                 static_cast<float>(size) * 2.0f);
            const float phase =
                std::fmod(static_cast<float>(y) + wobble + static_cast<float>(period),
                          static_cast<float>(period));
            const float d = std::fabs(phase - static_cast<float>(period) / 2.0f);
            image.at(x, y, 0) = std::clamp(d - thickness / 2.0f, 0.0f, 1.0f) * 0.9f +
                                0.1f * (d / static_cast<float>(period));
        }
    return image;
}

// Halftone screen: a dot grid of `period` px (0.5 + 0.25 (cos + cos)).
inline Image halftone_pattern(int size, int period) {
    Image image(size, size, 1);
    const float w = 2.0f * 3.14159265f / static_cast<float>(period);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            image.at(x, y, 0) = 0.5f + 0.25f * (std::cos(w * static_cast<float>(x)) +
                                                std::cos(w * static_cast<float>(y)));
    return image;
}

}  // namespace exemplar::npr::testing
