// Direction diffusion from strokes: Brushables (Lukáč et al. 2015) §3.2, eq. 1-3.
//
// Deviation: the paper's Gaussian has infinite support, yet it asks for strokes whose influence
// is "strictly limited"; we cut the kernel at 2σ and shift it down by its value there (see
// strokes.hpp), which keeps it continuous and keeps the closed-form segment integral.

#include "exemplar/paint/strokes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "exemplar/core/parallel.hpp"

namespace exemplar::paint {

namespace {

struct Kernel {
    double sigma = 1.0;
    double support = 2.0;
    double cut = 0.0;           // exp(-support² / 2σ²), subtracted so the kernel ends at 0
    double line_weight = 1;     // integral over an infinite line through the evaluation point
    double inv_scale = 1.0;     // 1 / (σ√2), erf's argument per unit length
    double inv_support2 = 1.0;  // 1 / support²
    double gauss_norm = 1.0;  // σ·√(π/2): ∫ exp(-s² / 2σ²) ds = gauss_norm · erf(s / σ√2)
};

Kernel kernel_of(const Stroke& s) {
    Kernel k;
    k.sigma = 0.5 * static_cast<double>(s.width_px);
    k.support = 2.0 * k.sigma;
    k.cut = std::exp(-0.5 * (k.support * k.support) / (k.sigma * k.sigma));
    k.line_weight = k.sigma * std::sqrt(2.0 * std::numbers::pi) *
                        std::erf(k.support / (k.sigma * std::numbers::sqrt2)) -
                    2.0 * k.support * k.cut;
    k.inv_scale = 1.0 / (k.sigma * std::numbers::sqrt2);
    k.inv_support2 = 1.0 / (k.support * k.support);
    k.gauss_norm = k.sigma * std::sqrt(0.5 * std::numbers::pi);
    return k;
}

// ∫ over the segment a + s·u, s ∈ [0, length], of max(0, exp(-|p - k|² / 2σ²) - cut) ds, in
// closed form: the squared distance is h² + (s - s0)², so the Gaussian part is erf's. The
// reference (libm's exp and erf, every segment): the oracle of the tabulated evaluation below.
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

// erf on [-√2, √2] and exp(-2q) on q ∈ [0, 1], linearly interpolated from 4096 intervals
// (errors below 1e-7): within the support every erf argument |s - s0| / (σ√2) is at most
// 2σ / (σ√2) = √2, and the Gaussian factor exp(-h² / 2σ²) is exp(-2q) with q = h² / support².
class KernelTables {
public:
    static const KernelTables& get() {
        static const KernelTables tables;
        return tables;
    }
    double erf(double x) const { return lookup(erf_, (x + std::numbers::sqrt2) * erf_scale_); }
    double gauss(double q) const { return lookup(gauss_, q * size); }

private:
    static constexpr int size = 4096;
    static constexpr double erf_scale_ = size / (2.0 * std::numbers::sqrt2);
    KernelTables() : erf_(size + 1), gauss_(size + 1) {
        for (int i = 0; i <= size; ++i) {
            erf_[i] = std::erf(i / erf_scale_ - std::numbers::sqrt2);
            gauss_[i] = std::exp(-2.0 * i / size);
        }
    }
    static double lookup(const std::vector<double>& table, double f) {
        f = std::clamp(f, 0.0, static_cast<double>(size));
        const int i = std::min(static_cast<int>(f), size - 1);
        return table[i] + (f - i) * (table[i + 1] - table[i]);
    }
    std::vector<double> erf_, gauss_;
};

// A straight piece of the simplified centre line: from (ax, ay) along the unit vector u, cut off
// at `radius` (the support less the original line's largest distance from it, see simplify).
struct Chord {
    double ax = 0, ay = 0, ux = 0, uy = 0, length = 0, radius = 0;
};

// segment_weight for a chord, with the tables.
double chord_weight(double px, double py, const Chord& c, const Kernel& k,
                    const KernelTables& tables) {
    const double rx = px - c.ax, ry = py - c.ay;
    const double s0 = rx * c.ux + ry * c.uy;
    const double h = rx * c.uy - ry * c.ux;  // signed distance from the chord's line
    const double h2 = h * h, r2 = c.radius * c.radius;
    if (h2 >= r2) return 0.0;
    const double half = std::sqrt(r2 - h2);
    const double lo = std::max(0.0, s0 - half), hi = std::min(c.length, s0 + half);
    if (lo >= hi) return 0.0;
    // No division per pixel: the kernel's reciprocals are precomputed.
    const double gauss =
        tables.gauss(h2 * k.inv_support2) * k.gauss_norm *
        (tables.erf((hi - s0) * k.inv_scale) - tables.erf((lo - s0) * k.inv_scale));
    return std::max(0.0, gauss - k.cut * (hi - lo));
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

// The stroke's centre line with nearly collinear runs of points merged into chords
// (Douglas-Peucker): a point is dropped when it lies within `tolerance` of the chord replacing
// it. The kernel's integral over a chord is exact for a straight run, and a chord is cut off at
// the support less its largest deviation `dev`, so it reaches no pixel farther than the support
// from the original line (the original run lies within dev of the chord, and every point of the
// chord within dev of the run): the stroke stays strictly local.
std::vector<Chord> simplify(const Stroke& s, const Kernel& k, double tolerance) {
    std::vector<StrokePoint> pts;  // without repeated points
    for (const StrokePoint& p : s.points) {
        if (pts.empty() || p.x != pts.back().x || p.y != pts.back().y) pts.push_back(p);
    }
    std::vector<Chord> chords;
    if (pts.size() < 2) return chords;
    // Split [first, last] at its farthest point until every point is within the tolerance.
    std::vector<std::pair<std::size_t, std::size_t>> todo = {{0, pts.size() - 1}};
    std::vector<std::pair<std::size_t, double>> ends;  // (end index, deviation), any order
    while (!todo.empty()) {
        const auto [first, last] = todo.back();
        todo.pop_back();
        double dev = 0.0;
        std::size_t far = first;
        for (std::size_t i = first + 1; i < last; ++i) {
            const double d = segment_distance(pts[i].x, pts[i].y, pts[first], pts[last]);
            if (d > dev) dev = d, far = i;
        }
        if (dev > tolerance) {
            todo.emplace_back(first, far);
            todo.emplace_back(far, last);
        } else {
            ends.emplace_back(first, dev);
        }
    }
    std::sort(ends.begin(), ends.end());
    for (std::size_t j = 0; j < ends.size(); ++j) {
        const StrokePoint& a = pts[ends[j].first];
        const StrokePoint& b = pts[j + 1 < ends.size() ? ends[j + 1].first : pts.size() - 1];
        Chord c;
        c.ax = a.x;
        c.ay = a.y;
        const double dx = b.x - c.ax, dy = b.y - c.ay;
        c.length = std::hypot(dx, dy);
        c.ux = dx / c.length;
        c.uy = dy / c.length;
        c.radius = k.support - ends[j].second;
        chords.push_back(c);
    }
    return chords;
}

// The x range of the points of the row at height y within `radius` of the segment from a to b
// (a capsule: the union of the end discs and the band along the segment, a convex set, so
// its row is one interval); empty (lo > hi) when the row misses it.
std::pair<double, double> row_span(double y, double ax, double ay, double bx, double by,
                                   double radius) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    auto add = [&](double l, double h) {
        if (l > h) return;
        lo = std::min(lo, l);
        hi = std::max(hi, h);
    };
    for (const auto& [cx, cy] : {std::pair{ax, ay}, std::pair{bx, by}}) {
        const double dy = y - cy;
        if (dy * dy < radius * radius) {
            const double w = std::sqrt(radius * radius - dy * dy);
            add(cx - w, cx + w);
        }
    }
    const double dx = bx - ax, dy = by - ay, length = std::hypot(dx, dy);
    if (length <= 0.0) return {lo, hi};
    const double ux = dx / length, uy = dy / length, ry = y - ay;
    // The band: 0 ≤ (x - ax)·ux + ry·uy ≤ length and |(x - ax)·uy - ry·ux| ≤ radius.
    double l = -std::numeric_limits<double>::infinity(), h = -l;
    auto clip = [&](double coef, double c0, double c1) {  // c0 ≤ (x - ax)·coef ≤ c1
        if (coef == 0.0) {
            if (c0 > 0.0 || c1 < 0.0) l = 1.0, h = 0.0;
            return;
        }
        const double e0 = c0 / coef, e1 = c1 / coef;
        l = std::max(l, ax + std::min(e0, e1));
        h = std::min(h, ax + std::max(e0, e1));
    };
    clip(ux, -ry * uy, length - ry * uy);
    clip(uy, ry * ux - radius, ry * ux + radius);
    add(l, h);
    return {lo, hi};
}

// The pixels [x0, x1) of row y (clamped to [0, width)) whose centres may lie in a row_span,
// one pixel of margin either side for rounding.
std::pair<int, int> span_pixels(std::pair<double, double> span, int width) {
    if (span.first > span.second) return {0, 0};
    const int x0 = static_cast<int>(std::max(-1.0, std::floor(span.first - 0.5) - 1.0));
    const int x1 = static_cast<int>(std::min(width + 1.0, std::ceil(span.second - 0.5) + 2.0));
    return {std::clamp(x0, 0, width), std::clamp(x1, 0, width)};
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

// Adds the stroke's swept disc (pixel centres within `radius` of the centre line) to `coverage`
// and paints its label there, segment by segment and row by row over each segment's capsule:
// the cost grows with the stroke's area, not with its bounding box times its number of points.
// The ends of each row's span are settled by the distance test itself, so the pixels are
// exactly those within `radius` of a segment.
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
            auto [x0, x1] = span_pixels(row_span(y + 0.5, a.x, a.y, b.x, b.y, radius), w);
            while (x0 < x1 && segment_distance(x0 + 0.5, y + 0.5, a, b) > radius) ++x0;
            while (x1 > x0 && segment_distance(x1 - 0.5, y + 0.5, a, b) > radius) --x1;
            for (int x = x0; x < x1; ++x) {
                coverage.at(x, y, 0) = 1.0f;
                labels.at(x, y, 0) = static_cast<float>(s.label);
            }
        }
    }
}

// Eq. 1-2 summed over the strokes, then normalized, over the strokes' box: `add(box, sum)`
// accumulates (Σ w·u_x, Σ w·u_y, Σ w / w_line) per pixel of the box, stroke by stroke.
template <class Accumulate>
Image diffuse(std::span<const Stroke> strokes, int width, int height, Accumulate add) {
    PixelRect box;
    for (const Stroke& s : strokes) {
        box = unite(box, bounds_of(s, static_cast<double>(s.width_px), width, height));
    }
    Image out(width, height, 3);
    out.set_channel_names({"x", "y", "weight"});
    if (box.empty()) return out;
    const int bw = box.x1 - box.x0;
    std::vector<double> sum(static_cast<std::size_t>(bw) * (box.y1 - box.y0) * 3, 0.0);
    add(box, sum);

    // Normalize (eq. 1-2: dividing by w_k only scales, so the unit vector is the same).
    for (int y = box.y0; y < box.y1; ++y) {
        for (int x = box.x0; x < box.x1; ++x) {
            const double* a = &sum[(static_cast<std::size_t>(y - box.y0) * bw + (x - box.x0)) * 3];
            const double len = std::hypot(a[0], a[1]);
            if (a[2] <= 0.0 || len <= 1e-12) continue;
            float* o = out.pixel(x, y);
            o[0] = static_cast<float>(a[0] / len);
            o[1] = static_cast<float>(a[1] / len);
            o[2] = static_cast<float>(std::min(1.0, a[2]));
        }
    }
    return out;
}

void accumulate(double wgt, double ux, double uy, const Kernel& k, const PixelRect& box, int x,
                int y, std::vector<double>& sum) {
    if (wgt <= 0.0) return;
    double* o = &sum[(static_cast<std::size_t>(y - box.y0) * (box.x1 - box.x0) + (x - box.x0)) * 3];
    o[0] += wgt * ux;
    o[1] += wgt * uy;
    o[2] += wgt / k.line_weight;
}

// The largest distance of a dropped centre-line point from its chord: 0.25 px, less for strokes
// narrower than 100 px (0.5% of σ, so that the chord's cut-off below the support changes the
// kernel by at most ~0.15% of its peak).
double chord_tolerance(const Stroke& s) {
    return std::min(0.25, 0.0025 * static_cast<double>(s.width_px));
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

Image diffuse_strokes(std::span<const Stroke> strokes, int width, int height, int threads) {
    const KernelTables& tables = KernelTables::get();
    // Each stroke's chords and the rows each reaches.
    struct Piece {
        Chord chord;
        std::size_t stroke;
        int y0, y1;
    };
    std::vector<Kernel> kernels;
    std::vector<Piece> pieces;
    for (const Stroke& s : strokes) {
        kernels.push_back(kernel_of(s));
        for (const Chord& c : simplify(s, kernels.back(), chord_tolerance(s))) {
            const double by = c.ay + c.length * c.uy;
            pieces.push_back({c, kernels.size() - 1,
                              static_cast<int>(std::floor(std::min(c.ay, by) - c.radius)),
                              static_cast<int>(std::ceil(std::max(c.ay, by) + c.radius)) + 1});
        }
    }
    return diffuse(strokes, width, height, [&](const PixelRect& box, std::vector<double>& sum) {
        // Row by row (in parallel), every chord reaching the row in turn: a pixel's sums are
        // added in the same order for any thread count.
        parallel_for(box.y0, box.y1, threads, [&](int y) {
            for (const Piece& piece : pieces) {
                if (y < piece.y0 || y >= piece.y1) continue;
                const Chord& c = piece.chord;
                const Kernel& k = kernels[piece.stroke];
                const double bx = c.ax + c.length * c.ux, by = c.ay + c.length * c.uy;
                auto [x0, x1] = span_pixels(row_span(y + 0.5, c.ax, c.ay, bx, by, c.radius), width);
                x0 = std::max(x0, box.x0);
                x1 = std::min(x1, box.x1);
                for (int x = x0; x < x1; ++x) {
                    accumulate(chord_weight(x + 0.5, y + 0.5, c, k, tables), c.ux, c.uy, k, box, x,
                               y, sum);
                }
            }
        });
    });
}

Image diffuse_strokes_reference(std::span<const Stroke> strokes, int width, int height) {
    return diffuse(strokes, width, height, [&](const PixelRect& box, std::vector<double>& sum) {
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
                        accumulate(segment_weight(x + 0.5, y + 0.5, ax, ay, ux, uy, length, k), ux,
                                   uy, k, box, x, y, sum);
                    }
                }
            }
        }
    });
}

PaintCanvas::PaintCanvas(int width, int height)
    : coverage_(std::max(width, 0), std::max(height, 0), 1),
      directions_(std::max(width, 0), std::max(height, 0), 2),
      labels_(std::max(width, 0), std::max(height, 0), 1) {
    coverage_.set_channel_names({"mask"});
    labels_.set_channel_names({"label"});
    directions_.set_channel_names({"x", "y"});
}

Result<PixelRect> PaintCanvas::add_stroke(const Stroke& stroke, int threads) {
    return add_strokes(std::span<const Stroke>(&stroke, 1), threads);
}

Result<PixelRect> PaintCanvas::add_strokes(std::span<const Stroke> strokes, int threads) {
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
    const Image diffused = diffuse_strokes(strokes, w, h, threads);
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
