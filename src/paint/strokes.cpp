// Direction diffusion from strokes: Brushables (Lukáč et al. 2015) §3.2, eq. 1-3.
//
// Deviation: the paper's Gaussian has infinite support, yet it asks for strokes whose influence
// is "strictly limited"; we cut the kernel at 2σ and shift it down by its value there (see
// strokes.hpp), which keeps it continuous and keeps the closed-form segment integral.

#include "exemplar/paint/strokes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace exemplar::paint {

namespace {

struct Kernel {
    double sigma = 1.0;
    double support = 2.0;
    double cut = 0.0;        // exp(-support² / 2σ²), subtracted so the kernel ends at 0
    double line_weight = 1;  // integral over an infinite line through the evaluation point
};

Kernel kernel_of(const Stroke& s) {
    Kernel k;
    k.sigma = 0.5 * static_cast<double>(s.width_px);
    k.support = 2.0 * k.sigma;
    k.cut = std::exp(-0.5 * (k.support * k.support) / (k.sigma * k.sigma));
    k.line_weight = k.sigma * std::sqrt(2.0 * std::numbers::pi) *
                        std::erf(k.support / (k.sigma * std::numbers::sqrt2)) -
                    2.0 * k.support * k.cut;
    return k;
}

// ∫ over the segment a + s·u, s ∈ [0, length], of max(0, exp(-|p - k|² / 2σ²) - cut) ds, in
// closed form: the squared distance is h² + (s - s0)², so the Gaussian part is erf's.
double segment_weight(double px, double py, double ax, double ay, double ux, double uy,
                      double length, const Kernel& k) {
    const double rx = px - ax, ry = py - ay;
    const double s0 = rx * ux + ry * uy;
    const double h2 = std::max(0.0, rx * rx + ry * ry - s0 * s0);
    const double r2 = k.support * k.support;
    if (h2 >= r2) return 0.0;
    const double half = std::sqrt(r2 - h2);
    const double lo = std::max(0.0, s0 - half), hi = std::min(length, s0 + half);
    if (lo >= hi) return 0.0;
    const double scale = k.sigma * std::numbers::sqrt2;
    const double gauss = std::exp(-0.5 * h2 / (k.sigma * k.sigma)) * k.sigma *
                         std::sqrt(0.5 * std::numbers::pi) *
                         (std::erf((hi - s0) / scale) - std::erf((lo - s0) / scale));
    return std::max(0.0, gauss - k.cut * (hi - lo));
}

PixelRect bounds_of(const Stroke& s, double grow, int width, int height) {
    float x0 = s.points[0].x, x1 = x0, y0 = s.points[0].y, y1 = y0;
    for (const StrokePoint& p : s.points) {
        x0 = std::min(x0, p.x);
        x1 = std::max(x1, p.x);
        y0 = std::min(y0, p.y);
        y1 = std::max(y1, p.y);
    }
    PixelRect r;
    r.x0 = std::clamp(static_cast<int>(std::floor(x0 - grow - 0.5)), 0, width);
    r.y0 = std::clamp(static_cast<int>(std::floor(y0 - grow - 0.5)), 0, height);
    r.x1 = std::clamp(static_cast<int>(std::ceil(x1 + grow + 0.5)) + 1, 0, width);
    r.y1 = std::clamp(static_cast<int>(std::ceil(y1 + grow + 0.5)) + 1, 0, height);
    return r;
}

PixelRect unite(const PixelRect& a, const PixelRect& b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

// Distance from (px, py) to the segment from a to b (a point when they coincide).
double segment_distance(double px, double py, const StrokePoint& a, const StrokePoint& b) {
    const double ax = a.x, ay = a.y;
    const double dx = b.x - ax, dy = b.y - ay;
    const double len2 = dx * dx + dy * dy;
    double t = len2 > 0.0 ? ((px - ax) * dx + (py - ay) * dy) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    return std::hypot(px - ax - t * dx, py - ay - t * dy);
}

// Adds the stroke's swept disc (pixel centres within `radius` of the centre line) to `coverage`
// and paints its label there, segment by segment over each segment's own box: the cost grows
// with the stroke's area, not with its bounding box times its number of points.
void cover(const Stroke& s, double radius, Image& coverage, Image& labels) {
    const int w = coverage.width(), h = coverage.height();
    for (std::size_t i = 0; i < s.points.size(); ++i) {
        const StrokePoint& a = s.points[i == 0 ? 0 : i - 1];
        const StrokePoint& b = s.points[i];
        if (i > 0 && a.x == b.x && a.y == b.y) continue;  // the point is covered already
        Stroke segment;
        segment.points = {a, b};
        const PixelRect r = bounds_of(segment, radius, w, h);
        for (int y = r.y0; y < r.y1; ++y) {
            for (int x = r.x0; x < r.x1; ++x) {
                if (segment_distance(x + 0.5, y + 0.5, a, b) > radius) continue;
                coverage.at(x, y, 0) = 1.0f;
                labels.at(x, y, 0) = static_cast<float>(s.label);
            }
        }
    }
}

}  // namespace

Status validate(const Stroke& stroke) {
    if (stroke.points.empty()) return invalid_argument("points: a stroke needs at least 1 point");
    for (const StrokePoint& p : stroke.points) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
            return invalid_argument("points: coordinates must be finite numbers");
        }
    }
    if (!(stroke.width_px > 0.0f && stroke.width_px <= 4096.0f)) {
        return invalid_argument("width: " + std::to_string(stroke.width_px) +
                                " is invalid (must be > 0 and <= 4096 px)");
    }
    if (stroke.label < 0 || stroke.label > max_stroke_label) {
        return invalid_argument("label: " + std::to_string(stroke.label) +
                                " is invalid (must be 0.." + std::to_string(max_stroke_label) +
                                ")");
    }
    if (stroke.comb && stroke.label != 0) {
        return invalid_argument("label: " + std::to_string(stroke.label) +
                                " on a combing stroke (it paints no segment; must be 0)");
    }
    return Status::ok();
}

Image diffuse_strokes(std::span<const Stroke> strokes, int width, int height) {
    // Accumulate eq. 1's numerator and the relative weights segment by segment.
    std::vector<double> sum(static_cast<std::size_t>(width) * height * 3, 0.0);
    for (const Stroke& s : strokes) {
        const Kernel k = kernel_of(s);
        for (std::size_t i = 1; i < s.points.size(); ++i) {
            const double ax = s.points[i - 1].x, ay = s.points[i - 1].y;
            const double dx = s.points[i].x - ax, dy = s.points[i].y - ay;
            const double length = std::hypot(dx, dy);
            if (length <= 0.0) continue;
            const double ux = dx / length, uy = dy / length;
            Stroke segment;
            segment.points = {s.points[i - 1], s.points[i]};
            const PixelRect r = bounds_of(segment, k.support, width, height);
            for (int y = r.y0; y < r.y1; ++y) {
                for (int x = r.x0; x < r.x1; ++x) {
                    const double wgt = segment_weight(x + 0.5, y + 0.5, ax, ay, ux, uy, length, k);
                    if (wgt <= 0.0) continue;
                    double* o = &sum[(static_cast<std::size_t>(y) * width + x) * 3];
                    o[0] += wgt * ux;
                    o[1] += wgt * uy;
                    o[2] += wgt / k.line_weight;
                }
            }
        }
    }

    // Normalize (eq. 1-2: dividing by w_k only scales, so the unit vector is the same).
    Image out(width, height, 3);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const double* a = &sum[(static_cast<std::size_t>(y) * width + x) * 3];
            const double len = std::hypot(a[0], a[1]);
            if (a[2] <= 0.0 || len <= 1e-12) continue;
            float* o = out.pixel(x, y);
            o[0] = static_cast<float>(a[0] / len);
            o[1] = static_cast<float>(a[1] / len);
            o[2] = static_cast<float>(std::min(1.0, a[2]));
        }
    }
    out.set_channel_names({"x", "y", "weight"});
    return out;
}

PaintCanvas::PaintCanvas(int width, int height)
    : coverage_(std::max(width, 0), std::max(height, 0), 1),
      directions_(std::max(width, 0), std::max(height, 0), 2),
      labels_(std::max(width, 0), std::max(height, 0), 1) {
    coverage_.set_channel_names({"mask"});
    labels_.set_channel_names({"label"});
    directions_.set_channel_names({"x", "y"});
}

Result<PixelRect> PaintCanvas::add_stroke(const Stroke& stroke) {
    return add_strokes(std::span<const Stroke>(&stroke, 1));
}

Result<PixelRect> PaintCanvas::add_strokes(std::span<const Stroke> strokes) {
    for (const Stroke& s : strokes) {
        if (Status st = validate(s); !st.is_ok()) return st;
        if (s.comb != strokes[0].comb) {
            return invalid_argument("comb: strokes applied together must all paint or all comb");
        }
    }
    const int w = width(), h = height();
    PixelRect changed;
    for (const Stroke& s : strokes) {
        changed = unite(changed, bounds_of(s, static_cast<double>(s.width_px), w, h));
    }
    if (strokes.empty() || changed.empty()) return changed;
    const bool comb = strokes[0].comb;

    // Painting strokes add their swept discs to the region.
    if (!comb) {
        for (const Stroke& s : strokes) {
            const double radius = 0.5 * static_cast<double>(s.width_px);
            cover(s, radius, coverage_, labels_);
        }
    }

    // Blend the diffused direction into the field (eq. 3).
    const Image diffused = diffuse_strokes(strokes, w, h);
    for (int y = changed.y0; y < changed.y1; ++y) {
        for (int x = changed.x0; x < changed.x1; ++x) {
            const float* d = diffused.pixel(x, y);
            if (d[2] <= 0.0f) continue;
            if (comb && coverage_.at(x, y, 0) == 0.0f) continue;
            float* o = directions_.pixel(x, y);
            const float vx = d[2] * d[0] + (1.0f - d[2]) * o[0];
            const float vy = d[2] * d[1] + (1.0f - d[2]) * o[1];
            const float len = std::hypot(vx, vy);
            if (len > 1e-6f) {
                o[0] = vx / len;
                o[1] = vy / len;
            } else {
                o[0] = d[0];
                o[1] = d[1];
            }
        }
    }
    return changed;
}

}  // namespace exemplar::paint
