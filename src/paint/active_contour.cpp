// Line-feature selection (Painting by Feature §3.3.1): the user's rough path snapped onto the
// palette's edge by an active contour (Kass, Witkin and Terzopoulos 1988), minimized by the
// greedy algorithm of Williams and Shah (1992): every point in turn moves to the position of its
// 3 × 3 neighbourhood with the least energy
//   α · (d̄ − |v_i − v_{i−1}|)²  +  β · |v_{i−1} − 2 v_i + v_{i+1}|²  −  γ · |∇(G_σ ∗ I)|,
// each term normalized over the neighbourhood (the continuity and curvature terms by their
// largest value, the edge term to [−1, 0] with a floor on its spread so that flat regions do not
// amplify noise). d̄ is the mean point distance, so the contour keeps its spacing and does not
// shrink (Kass et al.'s elasticity would). The chapter names the method, not its parameters:
// α = 1, β = 1, γ = 1.2 are Williams and Shah's.

#include <algorithm>
#include <array>
#include <cmath>

#include "exemplar/filters/resample.hpp"
#include "feature_internal.hpp"

namespace exemplar::paint {

namespace {

// Williams and Shah's floor on the spread of the edge term (5 grey levels of 255).
constexpr float kEdgeSpreadFloor = 5.0f / 255.0f;
// Stop when fewer than this share of the points moved in an iteration.
constexpr double kSettledShare = 0.01;

// |∇(G_σ ∗ luma)| with central differences.
Image edge_strength(const Image& palette, float sigma_px) {
    const int w = palette.width(), h = palette.height(), channels = palette.channels();
    Image luma(w, h, 1);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const float* p = palette.pixel(x, y);
            luma.at(x, y, 0) = channels >= 3 ? 0.299f * p[0] + 0.587f * p[1] + 0.114f * p[2] : p[0];
        }
    }
    luma = gaussian_blur(luma, sigma_px, 1);
    Image strength(w, h, 1);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const float gx =
                0.5f * (luma.at(std::min(x + 1, w - 1), y, 0) - luma.at(std::max(x - 1, 0), y, 0));
            const float gy =
                0.5f * (luma.at(x, std::min(y + 1, h - 1), 0) - luma.at(x, std::max(y - 1, 0), 0));
            strength.at(x, y, 0) = std::sqrt(gx * gx + gy * gy);
        }
    }
    return strength;
}

float squared(float v) {
    return v * v;
}

}  // namespace

Result<std::vector<StrokePoint>> snap_to_edges(const Image& palette,
                                               std::span<const StrokePoint> rough,
                                               const FeatureBrushOptions& options) {
    EXEMPLAR_RETURN_IF_ERROR(validate(options));
    if (rough.size() < 2) {
        return invalid_argument("feature: has " + std::to_string(rough.size()) +
                                " point(s) (needs at least 2)");
    }
    if (palette.empty()) return invalid_argument("palette: is empty");
    EXEMPLAR_RETURN_IF_ERROR(check_inside(palette, rough));
    std::vector<StrokePoint> v = sample_path(rough, options.snap_spacing_px);
    // Keep the rough path's end: the last sample can fall up to a spacing short of it.
    const StrokePoint end = rough.back();
    if (v.back().x != end.x || v.back().y != end.y) v.push_back(end);
    const int n = static_cast<int>(v.size());
    if (n < 3 || options.snap_iterations == 0) return v;

    const Image strength = edge_strength(palette, options.snap_sigma_px);
    const float max_x = static_cast<float>(palette.width()),
                max_y = static_cast<float>(palette.height());
    auto edge_at = [&](StrokePoint p) {
        float s = 0.0f;
        sample_bilinear(strength, p.x, p.y, &s);
        return s;
    };
    for (int iteration = 0; iteration < options.snap_iterations; ++iteration) {
        double mean_distance = 0.0;
        for (int i = 1; i < n; ++i) {
            mean_distance +=
                std::hypot(v[static_cast<std::size_t>(i)].x - v[static_cast<std::size_t>(i - 1)].x,
                           v[static_cast<std::size_t>(i)].y - v[static_cast<std::size_t>(i - 1)].y);
        }
        mean_distance /= n - 1;
        int moved = 0;
        for (int i = 0; i < n; ++i) {
            std::array<StrokePoint, 9> candidate;
            std::array<float, 9> continuity{}, curvature{}, edge{};
            for (int k = 0; k < 9; ++k) {
                const StrokePoint c{
                    std::clamp(v[static_cast<std::size_t>(i)].x + static_cast<float>(k % 3 - 1),
                               0.0f, max_x),
                    std::clamp(v[static_cast<std::size_t>(i)].y + static_cast<float>(k / 3 - 1),
                               0.0f, max_y)};
                candidate[static_cast<std::size_t>(k)] = c;
                if (i > 0) {
                    const StrokePoint a = v[static_cast<std::size_t>(i - 1)];
                    continuity[static_cast<std::size_t>(k)] = squared(
                        static_cast<float>(mean_distance) - std::hypot(c.x - a.x, c.y - a.y));
                }
                if (i > 0 && i + 1 < n) {
                    const StrokePoint a = v[static_cast<std::size_t>(i - 1)];
                    const StrokePoint b = v[static_cast<std::size_t>(i + 1)];
                    curvature[static_cast<std::size_t>(k)] =
                        squared(a.x - 2.0f * c.x + b.x) + squared(a.y - 2.0f * c.y + b.y);
                }
                edge[static_cast<std::size_t>(k)] = edge_at(c);
            }
            const float max_cont =
                std::max(*std::max_element(continuity.begin(), continuity.end()), 1e-12f);
            const float max_curv =
                std::max(*std::max_element(curvature.begin(), curvature.end()), 1e-12f);
            const auto [lo, hi] = std::minmax_element(edge.begin(), edge.end());
            const float spread = std::max(*hi - *lo, kEdgeSpreadFloor);
            int best = 4;  // the current position wins ties
            float best_energy = 0.0f;
            for (int k = 0; k < 9; ++k) {
                const std::size_t ks = static_cast<std::size_t>(k);
                const float energy = options.snap_elasticity * continuity[ks] / max_cont +
                                     options.snap_rigidity * curvature[ks] / max_curv +
                                     options.snap_edge_weight * (*lo - edge[ks]) / spread;
                if (k == 0 || energy < best_energy || (energy == best_energy && k == 4)) {
                    best_energy = energy;
                    best = k;
                }
            }
            if (best != 4) {
                v[static_cast<std::size_t>(i)] = candidate[static_cast<std::size_t>(best)];
                ++moved;
            }
        }
        if (moved < kSettledShare * n) break;
    }
    return v;
}

}  // namespace exemplar::paint
