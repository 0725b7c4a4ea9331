// Rigid moving-least-squares deformation (Schaefer, McPhail and Warren 2006, §2.3) and the random
// lattice pre-deformation of Color Me Noisy (Fišer et al. 2014; thesis §4.3.2: a 50 px lattice,
// points moved 15-25 px in random directions).
//
// Deviations from Schaefer et al.: weights 1 / (d^2 + smoothing^2) instead of 1 / d^2 (see
// lattice_smoothing_px in the header: the unsmoothed map folds over at the chapter's offsets).
// The rigid solution is written as the weighted Procrustes
// rotation R applied to v - p* (f(v) = R (v - p*) + q*). Their formula |v - p*| f_r/|f_r| + q*
// is the same map (f_r is v - p* rotated by R and scaled), but this form makes "rigid motions
// are reproduced exactly" evident and needs no normalisation of a vector that vanishes at p*.

#include "exemplar/noisy/mls.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "exemplar/core/check.hpp"
#include "exemplar/core/parallel.hpp"
#include "exemplar/core/rng.hpp"

namespace exemplar::noisy {

Point mls_rigid(const ControlPoints& points, Point v, double smoothing_px) {
    return mls_rigid_sample(points, v, smoothing_px).position;
}

MlsSample mls_rigid_sample(const ControlPoints& points, Point v, double smoothing_px) {
    EXEMPLAR_CHECK_EQ(points.from.size(), points.to.size());
    EXEMPLAR_CHECK(!points.from.empty());
    EXEMPLAR_CHECK(smoothing_px >= 0.0);
    const std::size_t n = points.from.size();
    const double smoothing2 = smoothing_px * smoothing_px;

    // Weighted centroids p* and q* (w_i = 1 / (|p_i - v|^2 + smoothing^2)). Without smoothing
    // a control point hit exactly maps to its target; its rotation, direction-dependent there,
    // is taken as that of the other points' fit.
    std::size_t hit = n;
    for (std::size_t i = 0; i < n && smoothing2 == 0.0; ++i) {
        if (points.from[i].x == v.x && points.from[i].y == v.y) hit = i;
    }
    auto weight = [&](std::size_t i) {
        if (hit != n) return i == hit ? 0.0 : 1.0;
        const double dx = points.from[i].x - v.x, dy = points.from[i].y - v.y;
        return 1.0 / (dx * dx + dy * dy + smoothing2);
    };
    double weight_sum = 0.0, px = 0.0, py = 0.0, qx = 0.0, qy = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double w = weight(i);
        weight_sum += w;
        px += w * points.from[i].x;
        py += w * points.from[i].y;
        qx += w * points.to[i].x;
        qy += w * points.to[i].y;
    }
    if (weight_sum == 0.0) return {points.to[hit], 0.0};  // the only point
    px /= weight_sum;
    py /= weight_sum;
    qx /= weight_sum;
    qy /= weight_sum;

    // Weighted Procrustes rotation: cos and sin proportional to the sums of dot and cross
    // products of the centred point pairs.
    double dot = 0.0, cross = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double w = weight(i);
        const double ax = points.from[i].x - px, ay = points.from[i].y - py;
        const double bx = points.to[i].x - qx, by = points.to[i].y - qy;
        dot += w * (ax * bx + ay * by);
        cross += w * (ax * by - ay * bx);
    }
    const double norm = std::hypot(dot, cross);
    const double c = norm > 0.0 ? dot / norm : 1.0;
    const double s = norm > 0.0 ? cross / norm : 0.0;
    const double ux = v.x - px, uy = v.y - py;
    if (hit != n) return {points.to[hit], std::atan2(s, c)};
    return {{qx + c * ux - s * uy, qy + s * ux + c * uy}, std::atan2(s, c)};
}

ControlPoints jittered_lattice(int width, int height, double spacing_px, double min_offset_px,
                               double max_offset_px, std::uint64_t key) {
    EXEMPLAR_CHECK_GE(width, 1);
    EXEMPLAR_CHECK_GE(height, 1);
    EXEMPLAR_CHECK(spacing_px > 0.0);
    EXEMPLAR_CHECK(min_offset_px >= 0.0 && min_offset_px <= max_offset_px);
    const int columns = static_cast<int>(std::ceil((width - 1) / spacing_px)) + 1;
    const int rows = static_cast<int>(std::ceil((height - 1) / spacing_px)) + 1;
    ControlPoints points;
    for (int j = 0; j < rows; ++j) {
        for (int i = 0; i < columns; ++i) {
            KeyedRng rng(key, static_cast<std::uint64_t>(j), static_cast<std::uint64_t>(i));
            const double length = min_offset_px + (max_offset_px - min_offset_px) *
                                                      static_cast<double>(rng.uniform());
            const double angle = 2.0 * std::numbers::pi * static_cast<double>(rng.uniform());
            const Point p{i * spacing_px, j * spacing_px};
            points.from.push_back(p);
            points.to.push_back({p.x + length * std::cos(angle), p.y + length * std::sin(angle)});
        }
    }
    return points;
}

Image mls_rigid_map(const ControlPoints& points, int width, int height, double smoothing_px,
                    int threads) {
    Image map(width, height, 2);
    parallel_for(0, height, threads, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const Point f =
                mls_rigid(points, {static_cast<double>(x), static_cast<double>(y)}, smoothing_px);
            map.at(x, y, 0) = static_cast<float>(f.x);
            map.at(x, y, 1) = static_cast<float>(f.y);
        }
    });
    return map;
}

namespace {

// Reflects t into [0, n - 1] (mirror without repeating the edge pixel).
double mirror(double t, int n) {
    if (n == 1) return 0.0;
    const double period = 2.0 * (n - 1);
    t = std::fmod(t, period);
    if (t < 0.0) t += period;
    return t > n - 1 ? period - t : t;
}

}  // namespace

Image deform_rigid(const Image& image, const ControlPoints& points, double smoothing_px,
                   int threads) {
    // Backward mapping: the inverse deformation is approximated by the MLS map with the roles of
    // the control points swapped (Schaefer et al. deform images the same way).
    const ControlPoints inverse{points.to, points.from};
    const int w = image.width(), h = image.height(), channels = image.channels();
    Image out(w, h, channels);
    out.set_channel_names(image.channel_names());
    parallel_for(0, h, threads, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const Point p =
                mls_rigid(inverse, {static_cast<double>(x), static_cast<double>(y)}, smoothing_px);
            const double sx = mirror(p.x, w), sy = mirror(p.y, h);
            const int x0 = std::min(static_cast<int>(sx), w - 1);
            const int y0 = std::min(static_cast<int>(sy), h - 1);
            const int x1 = std::min(x0 + 1, w - 1), y1 = std::min(y0 + 1, h - 1);
            const float fx = static_cast<float>(sx - x0), fy = static_cast<float>(sy - y0);
            for (int c = 0; c < channels; ++c) {
                const float top = image.at(x0, y0, c) * (1 - fx) + image.at(x1, y0, c) * fx;
                const float bottom = image.at(x0, y1, c) * (1 - fx) + image.at(x1, y1, c) * fx;
                out.at(x, y, c) = top * (1 - fy) + bottom * fy;
            }
        }
    });
    return out;
}

Image deform_rigid_angles(const Image& angles, const ControlPoints& points, double smoothing_px,
                          int threads) {
    EXEMPLAR_CHECK_EQ(angles.channels(), 1);
    // The backward map g rotates by ψ locally; the forward deformation by about -ψ.
    const ControlPoints inverse{points.to, points.from};
    const int w = angles.width(), h = angles.height();
    Image out(w, h, 1);
    parallel_for(0, h, threads, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const MlsSample g = mls_rigid_sample(
                inverse, {static_cast<double>(x), static_cast<double>(y)}, smoothing_px);
            const int sx = std::min(static_cast<int>(std::lround(mirror(g.position.x, w))), w - 1);
            const int sy = std::min(static_cast<int>(std::lround(mirror(g.position.y, h))), h - 1);
            out.at(x, y, 0) = static_cast<float>(angles.at(sx, sy, 0) - g.angle_rad);
        }
    });
    return out;
}

}  // namespace exemplar::noisy
