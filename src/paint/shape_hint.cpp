// Shape Hints: Brushables (Lukáč et al. 2015) §3.3, Fig. 6. Deviation: bins hold √(edge fraction)
// and are compared by squared differences (≈ χ², see shape_hint.hpp) so that they can be engine
// guide channels; the paper counts edge pixels and compares by χ².

#include "exemplar/paint/shape_hint.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "exemplar/core/check.hpp"
#include "exemplar/core/parallel.hpp"

namespace exemplar::paint {

namespace {

// Edge map convolved with a disc of radius `radius`, normalized by the disc's pixel count: the
// fraction of the disc's pixels that are edges (row prefix sums, one row per task).
Image disc_fraction(const Image& edges, float radius, int threads) {
    const int w = edges.width(), h = edges.height();
    std::vector<double> prefix(static_cast<std::size_t>(w + 1) * h, 0.0);
    for (int y = 0; y < h; ++y) {
        double* row = &prefix[static_cast<std::size_t>(y) * (w + 1)];
        for (int x = 0; x < w; ++x) row[x + 1] = row[x] + edges.at(x, y, 0);
    }
    const int r = static_cast<int>(std::floor(radius));
    std::vector<int> half(static_cast<std::size_t>(2 * r + 1));
    double area = 0.0;
    for (int dy = -r; dy <= r; ++dy) {
        const int hw = static_cast<int>(std::floor(std::sqrt(radius * radius - dy * dy)));
        half[static_cast<std::size_t>(dy + r)] = hw;
        area += 2 * hw + 1;
    }
    Image out(w, h, 1);
    parallel_for(0, h, threads, [&](int y) {
        for (int x = 0; x < w; ++x) {
            double sum = 0.0;
            for (int dy = -r; dy <= r; ++dy) {
                const int v = y + dy;
                if (v < 0 || v >= h) continue;
                const int hw = half[static_cast<std::size_t>(dy + r)];
                const int x0 = std::max(x - hw, 0), x1 = std::min(x + hw + 1, w);
                if (x0 >= x1) continue;
                const double* row = &prefix[static_cast<std::size_t>(v) * (w + 1)];
                sum += row[x1] - row[x0];
            }
            out.at(x, y, 0) = static_cast<float>(sum / area);
        }
    });
    return out;
}

// Bilinear lookup with zeros outside the image.
float sample(const Image& image, float x, float y) {
    const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
    const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
    auto at = [&](int u, int v) {
        return u < 0 || v < 0 || u >= image.width() || v >= image.height() ? 0.0f
                                                                           : image.at(u, v, 0);
    };
    return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
           fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
}

}  // namespace

Status validate(const ShapeHintOptions& o) {
    if (!(o.radius_px >= 1.0f && o.radius_px <= 256.0f)) {
        return invalid_argument("edge-extent: " + std::to_string(o.radius_px) +
                                " is invalid (must be 1..256 px)");
    }
    if (o.bins < 4 || o.bins > 32) {
        return invalid_argument("shape-bins: " + std::to_string(o.bins) +
                                " is invalid (must be 4..32)");
    }
    return Status::ok();
}

Image shape_edges(const Image& mask, const Image& labels) {
    const int w = mask.width(), h = mask.height();
    Image out(w, h, 1);
    auto inside = [&](int x, int y) { return mask.at(x, y, 0) > 0.5f; };
    auto label = [&](int x, int y) { return std::lround(labels.at(x, y, 0)); };
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            if (!inside(x, y)) continue;
            bool edge = false;
            const int nx[4] = {x + 1, x - 1, x, x};
            const int ny[4] = {y, y, y + 1, y - 1};
            for (int k = 0; k < 4 && !edge; ++k) {
                if (nx[k] < 0 || ny[k] < 0 || nx[k] >= w || ny[k] >= h) continue;
                edge = !inside(nx[k], ny[k]) ||
                       (!labels.empty() && label(nx[k], ny[k]) != label(x, y));
            }
            out.at(x, y, 0) = edge ? 1.0f : 0.0f;
        }
    }
    return out;
}

namespace {

// shape_hint; with `skip_far`, pixels far from every edge are left 0 without computing them.
Image hint(const Image& edges, const Image& angles, const ShapeHintOptions& options, int threads,
           bool skip_far) {
    EXEMPLAR_CHECK(validate(options).is_ok());
    EXEMPLAR_CHECK(edges.same_size(angles));
    const int w = edges.width(), h = edges.height(), n = options.bins;
    const float ring = options.radius_px;
    const float step = 2.0f * std::numbers::pi_v<float> / static_cast<float>(n);
    const Image bins = disc_fraction(edges, std::max(1.0f, ring * std::sin(0.5f * step)), threads);
    // Pixels whose ring reads only zeros of `bins` (far from every edge: most of a canvas) have
    // all-zero descriptors, as the image starts: a summed-area table of the non-zero bins
    // finds them, and they are skipped (no sine, cosine and bilinear lookups).
    const int reach = static_cast<int>(std::ceil(ring)) + 1;  // bilinear reads one pixel more
    std::vector<std::int32_t> nonzero(static_cast<std::size_t>(w + 1) * (h + 1), 0);
    for (int y = 0; y < h; ++y) {
        std::int32_t row = 0;
        for (int x = 0; x < w; ++x) {
            row += bins.at(x, y, 0) != 0.0f ? 1 : 0;
            nonzero[static_cast<std::size_t>(y + 1) * (w + 1) + x + 1] =
                nonzero[static_cast<std::size_t>(y) * (w + 1) + x + 1] + row;
        }
    }
    auto any_nonzero = [&](int x, int y) {
        const int x0 = std::max(x - reach, 0), x1 = std::min(x + reach + 1, w);
        const int y0 = std::max(y - reach, 0), y1 = std::min(y + reach + 1, h);
        auto at = [&](int u, int v) { return nonzero[static_cast<std::size_t>(v) * (w + 1) + u]; };
        return at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0) > 0;
    };
    Image out(w, h, n);
    parallel_for(0, h, threads, [&](int y) {
        for (int x = 0; x < w; ++x) {
            if (skip_far && !any_nonzero(x, y)) continue;
            const float theta = angles.at(x, y, 0);
            for (int b = 0; b < n; ++b) {
                const float a = theta + step * static_cast<float>(b);
                // Counter-clockwise on screen: +x towards −y.
                const float value = sample(bins, static_cast<float>(x) + ring * std::cos(a),
                                           static_cast<float>(y) - ring * std::sin(a));
                out.at(x, y, b) = std::sqrt(std::max(0.0f, value));
            }
        }
    });
    std::vector<std::string> names;
    for (int b = 0; b < n; ++b) names.push_back("hint" + std::to_string(b));
    out.set_channel_names(std::move(names));
    return out;
}

}  // namespace

Image shape_hint(const Image& edges, const Image& angles, const ShapeHintOptions& options,
                 int threads) {
    return hint(edges, angles, options, threads, /*skip_far=*/true);
}

Image shape_hint_reference(const Image& edges, const Image& angles, const ShapeHintOptions& options,
                           int threads) {
    return hint(edges, angles, options, threads, /*skip_far=*/false);
}

}  // namespace exemplar::paint
