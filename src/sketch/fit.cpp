// Schneider's least-squares cubic fitting (Graphics Gems 1990): chord-length parameters, a
// least-squares solve for the two handle lengths along fixed end tangents, Newton–Raphson
// reparameterization, and a split at the worst point when the error stays too large. Deviation:
// the pieces between detected corners are fitted independently (one-sided end tangents), which
// the original leaves to the caller.

#include "exemplar/sketch/fit.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace exemplar::sketch {

namespace {

constexpr int kMaxReparameterizations = 4;

std::vector<double> chord_parameters(const std::vector<Vec2>& pts, std::size_t first,
                                     std::size_t last) {
    std::vector<double> u(last - first + 1, 0.0);
    for (std::size_t i = first + 1; i <= last; ++i) {
        u[i - first] = u[i - first - 1] + distance(pts[i], pts[i - 1]);
    }
    const double total = u.back();
    for (double& v : u) v = total > 0.0 ? v / total : 0.0;
    return u;
}

// Handles along the unit tangents t1 (out of the start) and t2 (into the end, pointing back).
Cubic generate(const std::vector<Vec2>& pts, std::size_t first, std::size_t last,
               const std::vector<double>& u, Vec2 t1, Vec2 t2) {
    const Vec2 p0 = pts[first], p3 = pts[last];
    double c00 = 0, c01 = 0, c11 = 0, x0 = 0, x1 = 0;
    for (std::size_t i = 0; i < u.size(); ++i) {
        const double t = u[i], s = 1 - t;
        const double b0 = s * s * s, b1 = 3 * s * s * t, b2 = 3 * s * t * t, b3 = t * t * t;
        const Vec2 a1 = t1 * b1, a2 = t2 * b2;
        c00 += dot(a1, a1);
        c01 += dot(a1, a2);
        c11 += dot(a2, a2);
        const Vec2 tmp = pts[first + i] - (p0 * (b0 + b1) + p3 * (b2 + b3));
        x0 += dot(a1, tmp);
        x1 += dot(a2, tmp);
    }
    const double det = c00 * c11 - c01 * c01;
    double alpha1 = 0.0, alpha2 = 0.0;
    if (std::abs(det) > 1e-12) {
        alpha1 = (x0 * c11 - x1 * c01) / det;
        alpha2 = (c00 * x1 - c01 * x0) / det;
    }
    const double seg = distance(p0, p3);
    const double eps = 1e-6 * seg;
    if (alpha1 < eps || alpha2 < eps) {  // Wu/Barsky heuristic: fall back to a third of the chord
        alpha1 = alpha2 = seg / 3.0;
    }
    return {p0, p0 + t1 * alpha1, p3 + t2 * alpha2, p3};
}

double max_error(const std::vector<Vec2>& pts, std::size_t first, const Cubic& c,
                 const std::vector<double>& u, std::size_t* split) {
    double worst = 0.0;
    *split = first + u.size() / 2;
    for (std::size_t i = 1; i + 1 < u.size(); ++i) {
        const double d = distance(c.point(u[i]), pts[first + i]);
        if (d > worst) {
            worst = d;
            *split = first + i;
        }
    }
    return worst;
}

void reparameterize(const std::vector<Vec2>& pts, std::size_t first, const Cubic& c,
                    std::vector<double>& u) {
    for (std::size_t i = 0; i < u.size(); ++i) {
        const double t = u[i];
        const Vec2 d = c.point(t) - pts[first + i];
        const Vec2 d1 = c.derivative(t), d2 = c.second_derivative(t);
        const double num = dot(d, d1);
        const double den = dot(d1, d1) + dot(d, d2);
        if (std::abs(den) > 1e-12) u[i] = std::clamp(t - num / den, 0.0, 1.0);
    }
}

Vec2 center_tangent(const std::vector<Vec2>& pts, std::size_t i) {
    const Vec2 t = normalized(pts[i - 1] - pts[i + 1]);
    if (norm(t) > 0.0) return t;
    return normalized(perpendicular(pts[i] - pts[i - 1]));
}

void fit_cubic(const std::vector<Vec2>& pts, std::size_t first, std::size_t last, Vec2 t1, Vec2 t2,
               double tolerance, std::vector<Cubic>& out) {
    if (last - first == 1) {
        const double dist = distance(pts[first], pts[last]) / 3.0;
        out.push_back({pts[first], pts[first] + t1 * dist, pts[last] + t2 * dist, pts[last]});
        return;
    }
    std::vector<double> u = chord_parameters(pts, first, last);
    Cubic c = generate(pts, first, last, u, t1, t2);
    std::size_t split = 0;
    double error = max_error(pts, first, c, u, &split);
    if (error < tolerance) {
        out.push_back(c);
        return;
    }
    if (error < 4 * tolerance) {
        for (int k = 0; k < kMaxReparameterizations; ++k) {
            reparameterize(pts, first, c, u);
            c = generate(pts, first, last, u, t1, t2);
            error = max_error(pts, first, c, u, &split);
            if (error < tolerance) {
                out.push_back(c);
                return;
            }
        }
    }
    split = std::clamp(split, first + 1, last - 1);
    const Vec2 tc = center_tangent(pts, split);
    fit_cubic(pts, first, split, t1, tc, tolerance, out);
    fit_cubic(pts, split, last, -tc, t2, tolerance, out);
}

// One-sided tangent from pts[i] towards the samples after it (step +1) or before it (step −1),
// using the first sample at least `reach` away so that jitter does not dominate.
Vec2 end_direction(const std::vector<Vec2>& pts, std::size_t i, std::size_t stop, int step,
                   double reach) {
    std::size_t j = i;
    while (j != stop) {
        j = static_cast<std::size_t>(static_cast<long>(j) + step);
        if (distance(pts[j], pts[i]) >= reach) break;
    }
    return normalized(pts[j] - pts[i]);
}

}  // namespace

Path fit_path(const std::vector<Vec2>& samples, const FitOptions& options) {
    std::vector<Vec2> pts;
    for (Vec2 p : samples) {
        if (pts.empty() || distance(p, pts.back()) > 1e-9) pts.push_back(p);
    }
    Path path;
    if (pts.size() < 2) return path;
    const double tolerance = std::max(options.tolerance, 1e-6);
    const bool closed = pts.size() > 3 && distance(pts.front(), pts.back()) <= tolerance;
    if (closed) pts.back() = pts.front();

    // Corners: samples where the chords to the neighbours a window away turn sharply.
    std::vector<std::size_t> breaks{0};
    const double reach = std::max(options.corner_window, 1e-6);
    for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
        const Vec2 back = end_direction(pts, i, 0, -1, reach);
        const Vec2 ahead = end_direction(pts, i, pts.size() - 1, +1, reach);
        const double turn = std::numbers::pi - angle_between(back, ahead);
        if (turn <= options.corner_angle_rad) continue;
        // Keep only the sharpest sample of a run of corner samples.
        if (breaks.back() != 0 && i - breaks.back() <= 2) {
            const std::size_t prev = breaks.back();
            const double prev_turn =
                std::numbers::pi -
                angle_between(end_direction(pts, prev, 0, -1, reach),
                              end_direction(pts, prev, pts.size() - 1, +1, reach));
            if (turn > prev_turn) breaks.back() = i;
            continue;
        }
        breaks.push_back(i);
    }
    breaks.push_back(pts.size() - 1);

    const double tangent_reach = std::min(reach, 3.0 * tolerance);
    for (std::size_t k = 1; k < breaks.size(); ++k) {
        const std::size_t first = breaks[k - 1], last = breaks[k];
        if (last <= first) continue;
        Vec2 t1 = end_direction(pts, first, last, +1, tangent_reach);
        Vec2 t2 = end_direction(pts, last, first, -1, tangent_reach);
        if (closed && breaks.size() == 2) {  // smooth closed curve: a shared tangent at the seam
            const Vec2 seam = normalized(pts[1] - pts[pts.size() - 2]);
            if (norm(seam) > 0.0) {
                t1 = seam;
                t2 = -seam;
            }
        }
        fit_cubic(pts, first, last, t1, t2, tolerance, path.segments);
    }
    path.closed = closed;
    return path;
}

// `exemplar beautify --fit` and the Python module refit with this one function.
Path refit_polyline(const Path& path, double tolerance) {
    if (path.segments.size() < 3) return path;
    std::vector<Vec2> samples{path.start()};
    for (const Cubic& c : path.segments) {
        const Cubic line = line_cubic(c.p0, c.p3);
        if (distance(c.c1, line.c1) > 1e-9 || distance(c.c2, line.c2) > 1e-9) {
            return path;  // already has curves
        }
        samples.push_back(c.p3);
    }
    FitOptions fit;
    fit.tolerance = tolerance;
    Path smooth = fit_path(samples, fit);
    if (smooth.empty()) return path;
    smooth.closed = smooth.closed || path.closed;
    return smooth;
}

}  // namespace exemplar::sketch
