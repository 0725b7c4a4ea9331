#pragma once
// Colour-distribution distance of the paint tests: the L1 distance between 16-bin histograms of
// R, G, B over selected pixels of two images.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "exemplar/core/image.hpp"

namespace exemplar::paint::testing {

/// The pixels of `image` where channel `mask_channel` of `mask` is above 0.5.
struct Selection {
    const Image& image;
    const Image& mask;
    int mask_channel = 0;
};

/// Mean over R, G, B of the L1 distance between the 16-bin histograms of the two selections:
/// 0 = the same colour distribution, 2 = disjoint.
inline double histogram_distance(const Selection& a, const Selection& b) {
    auto histograms = [](const Selection& s) {
        std::vector<double> h(3 * 16, 0.0);
        double n = 0.0;
        for (int y = 0; y < s.image.height(); ++y) {
            for (int x = 0; x < s.image.width(); ++x) {
                if (s.mask.at(x, y, s.mask_channel) <= 0.5f) continue;
                n += 1.0;
                for (int c = 0; c < 3; ++c) {
                    const int bin =
                        std::clamp(static_cast<int>(s.image.at(x, y, c) * 16.0f), 0, 15);
                    h[static_cast<std::size_t>(c * 16 + bin)] += 1.0;
                }
            }
        }
        for (double& v : h) v /= n;
        return h;
    };
    const std::vector<double> ha = histograms(a), hb = histograms(b);
    double d = 0.0;
    for (std::size_t i = 0; i < ha.size(); ++i) d += std::abs(ha[i] - hb[i]);
    return d / 3.0;
}

}  // namespace exemplar::paint::testing
