#pragma once
// Procedural inputs for the LazyFluids tests: an RGBA exemplar of a "fluid element" (a soft blob
// of fiery noise on transparent ground) and target alpha masks with exact motion.

#include <algorithm>
#include <cmath>

#include "exemplar/core/image.hpp"
#include "exemplar/core/rng.hpp"

namespace exemplar::fluid::test {

// Value noise: a lattice of random values every `cell` px, bilinear in between.
inline float value_noise(float x, float y, float cell, std::uint64_t seed) {
    const float fx = x / cell, fy = y / cell;
    const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
    auto lattice = [&](int i, int j) {
        return KeyedRng(seed, static_cast<std::uint64_t>(i + 1000),
                        static_cast<std::uint64_t>(j + 1000))
            .uniform();
    };
    const float ax = fx - static_cast<float>(x0), ay = fy - static_cast<float>(y0);
    return (1 - ay) * ((1 - ax) * lattice(x0, y0) + ax * lattice(x0 + 1, y0)) +
           ay * ((1 - ax) * lattice(x0, y0 + 1) + ax * lattice(x0 + 1, y0 + 1));
}

// A size × size RGBA blob: alpha 1 inside a wobbly disc with a soft, noisy rim, 0 outside;
// colour a fire ramp of multi-scale noise (contrast at several scales, so wash-out shows).
inline Image fire_exemplar(int size, std::uint64_t seed = 5) {
    Image out(size, size, 4);
    out.set_channel_names({"R", "G", "B", "A"});
    const float c = 0.5f * static_cast<float>(size - 1);
    const float radius = 0.38f * static_cast<float>(size);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const float fx = static_cast<float>(x), fy = static_cast<float>(y);
            const float rim = radius * (0.85f + 0.3f * value_noise(fx, fy, 6.0f, seed + 1));
            const float d = std::hypot(fx - c, fy - c);
            const float alpha = std::clamp((rim - d) / 4.0f, 0.0f, 1.0f);
            const float n = 0.5f * value_noise(fx, fy, 7.0f, seed) +
                            0.3f * value_noise(fx, fy, 3.0f, seed + 2) +
                            0.2f * value_noise(fx, fy, 1.5f, seed + 3);
            const float t = std::clamp(1.6f * n - 0.3f, 0.0f, 1.0f);
            out.at(x, y, 0) = std::clamp(0.3f + 0.9f * t, 0.0f, 1.0f);
            out.at(x, y, 1) = std::clamp(1.2f * t * t, 0.0f, 1.0f);
            out.at(x, y, 2) = std::clamp(0.6f * t * t * t, 0.0f, 1.0f);
            out.at(x, y, 3) = alpha;
        }
    }
    return out;
}

// A w × h alpha mask: a soft ellipse centred at (cx, cy) with radii (rx, ry).
inline Image ellipse_alpha(int w, int h, float cx, float cy, float rx, float ry) {
    Image out(w, h, 1);
    out.set_channel_names({"A"});
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const float dx = (static_cast<float>(x) - cx) / rx;
            const float dy = (static_cast<float>(y) - cy) / ry;
            const float d = (std::sqrt(dx * dx + dy * dy) - 1.0f) * std::min(rx, ry);
            out.at(x, y, 0) = std::clamp(0.5f - d / 2.0f, 0.0f, 1.0f);
        }
    }
    return out;
}

// A uniform motion field.
inline Image uniform_motion(int w, int h, float u, float v) {
    Image out(w, h, 2);
    out.set_channel_names({"u", "v"});
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            out.at(x, y, 0) = u;
            out.at(x, y, 1) = v;
        }
    }
    return out;
}

}  // namespace exemplar::fluid::test
