#pragma once
// Builders for the sketch tests: resolved drawings of known lines, arcs and curves, and jitter.

#include <cmath>
#include <cstdint>
#include <vector>

#include "exemplar/sketch/beautify.hpp"
#include "exemplar/sketch/fit.hpp"

namespace exemplar::sketch::testing {

/// Deterministic pseudo-random offsets in [-amplitude, amplitude] (a hash, no state).
inline double jitter(int i, int salt, double amplitude) {
    std::uint32_t n =
        static_cast<std::uint32_t>(i) * 2654435761u + static_cast<std::uint32_t>(salt) * 40503u;
    n ^= n >> 13;
    n *= 2246822519u;
    n ^= n >> 16;
    return amplitude * (static_cast<double>(n % 20001) / 10000.0 - 1.0);
}

/// A hand-drawn-looking path along `shape`: a smooth, low-frequency wobble of up to
/// `amplitude` units (two sinusoids per axis with hashed phases), like a slightly unsteady hand.
inline Path wobbly(const std::vector<Vec2>& shape, double amplitude, int salt) {
    std::vector<Vec2> pts = resample_by_step(shape, 1.0);
    const double n = static_cast<double>(pts.size() - 1);
    const double phase[4] = {jitter(1, salt, 3.1), jitter(2, salt, 3.1), jitter(3, salt, 3.1),
                             jitter(4, salt, 3.1)};
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const double u = static_cast<double>(i) / n;
        pts[i] += Vec2{0.6 * std::sin(2 * 3.14159265 * 1.5 * u + phase[0]) +
                           0.4 * std::sin(2 * 3.14159265 * 4 * u + phase[1]),
                       0.6 * std::sin(2 * 3.14159265 * 2 * u + phase[2]) +
                           0.4 * std::sin(2 * 3.14159265 * 3.5 * u + phase[3])} *
                  amplitude;
    }
    FitOptions fit;
    fit.tolerance = 0.3;
    return fit_path(pts, fit);
}

/// A resolved drawing (view px = units) built from already clean paths.
class Canvas {
public:
    BeautifyOptions options;
    ResolvedDrawing drawing;

    int add(const Candidate& c) {
        Suggestion s;
        s.path = c.path;
        s.segments.push_back(c);
        accept(drawing, s, options);
        return static_cast<int>(drawing.paths.size()) - 1;
    }
    int add_line(Vec2 a, Vec2 b) {
        Candidate c = make_candidate(polyline_path({a, b}));
        c.kind = ShapeKind::Line;
        return add(c);
    }
    int add_curve(const Path& p) { return add(make_candidate(p)); }
    int add_arc(Vec2 center, double radius, double start, double sweep) {
        Candidate c = make_candidate(arc_path(center, radius, start, sweep));
        c.kind = std::abs(sweep) >= 6.28 ? ShapeKind::Circle : ShapeKind::Arc;
        c.arc = {center, radius, start, sweep};
        return add(c);
    }
    RuleContext context() const { return make_context(drawing, {}, options); }
};

/// An S-shaped open curve (a template shape), points in a 100-unit box at `origin`.
inline std::vector<Vec2> s_curve(Vec2 origin) {
    std::vector<Vec2> pts;
    for (int i = 0; i <= 60; ++i) {
        const double t = i / 60.0;
        pts.push_back(origin + Vec2{100 * t, 25 * std::sin(2 * 3.14159265358979 * t) + 30 * t * t});
    }
    return pts;
}

inline std::vector<Vec2> mapped(const std::vector<Vec2>& pts, const Affine& m) {
    std::vector<Vec2> out;
    for (Vec2 p : pts) out.push_back(m.apply(p));
    return out;
}

}  // namespace exemplar::sketch::testing
