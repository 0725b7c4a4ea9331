// Cubic Bézier paths and sampled-geometry tools (ShipShape §7.3.3–7.3.4).

#include "exemplar/sketch/path.hpp"

#include <algorithm>
#include <limits>
#include <numbers>

namespace exemplar::sketch {

double angle_between(Vec2 a, Vec2 b) {
    if (norm(a) == 0.0 || norm(b) == 0.0) return 0.0;
    return std::abs(std::atan2(cross(a, b), dot(a, b)));
}

double line_angle_between(Vec2 a, Vec2 b) {
    const double angle = angle_between(a, b);
    return std::min(angle, std::numbers::pi - angle);
}

Affine Affine::inverse() const {
    const double det = determinant();
    if (det == 0.0 || !std::isfinite(det)) return {};
    Affine inv{d / det, -b / det, -c / det, a / det, 0.0, 0.0};
    const Vec2 t = inv.apply_vector({tx, ty});
    inv.tx = -t.x;
    inv.ty = -t.y;
    return inv;
}

Affine compose(const Affine& outer, const Affine& inner) {
    Affine m;
    m.a = outer.a * inner.a + outer.c * inner.b;
    m.b = outer.b * inner.a + outer.d * inner.b;
    m.c = outer.a * inner.c + outer.c * inner.d;
    m.d = outer.b * inner.c + outer.d * inner.d;
    const Vec2 t = outer.apply({inner.tx, inner.ty});
    m.tx = t.x;
    m.ty = t.y;
    return m;
}

Affine Affine::rotation(double angle_rad, Vec2 center) {
    return similarity(angle_rad, 1.0, center);
}

Affine Affine::similarity(double angle_rad, double scale, Vec2 center) {
    const double cs = scale * std::cos(angle_rad);
    const double sn = scale * std::sin(angle_rad);
    Affine m{cs, sn, -sn, cs, 0.0, 0.0};
    const Vec2 moved = m.apply_vector(center);
    m.tx = center.x - moved.x;
    m.ty = center.y - moved.y;
    return m;
}

Affine Affine::reflection(Vec2 point, Vec2 direction) {
    const Vec2 u = normalized(direction);
    // I − 2·n·nᵀ with n ⟂ u equals 2·u·uᵀ − I.
    Affine m{2 * u.x * u.x - 1, 2 * u.x * u.y, 2 * u.x * u.y, 2 * u.y * u.y - 1, 0.0, 0.0};
    const Vec2 moved = m.apply_vector(point);
    m.tx = point.x - moved.x;
    m.ty = point.y - moved.y;
    return m;
}

Vec2 Cubic::point(double t) const {
    const double s = 1.0 - t;
    return p0 * (s * s * s) + c1 * (3 * s * s * t) + c2 * (3 * s * t * t) + p3 * (t * t * t);
}

Vec2 Cubic::derivative(double t) const {
    const double s = 1.0 - t;
    return (c1 - p0) * (3 * s * s) + (c2 - c1) * (6 * s * t) + (p3 - c2) * (3 * t * t);
}

Vec2 Cubic::second_derivative(double t) const {
    return (c2 - c1 * 2 + p0) * (6 * (1 - t)) + (p3 - c2 * 2 + c1) * (6 * t);
}

std::array<Cubic, 2> Cubic::split(double t) const {
    const Vec2 a = lerp(p0, c1, t), b = lerp(c1, c2, t), c = lerp(c2, p3, t);
    const Vec2 ab = lerp(a, b, t), bc = lerp(b, c, t);
    const Vec2 mid = lerp(ab, bc, t);
    return {Cubic{p0, a, ab, mid}, Cubic{mid, bc, c, p3}};
}

Cubic line_cubic(Vec2 a, Vec2 b) {
    return {a, lerp(a, b, 1.0 / 3.0), lerp(a, b, 2.0 / 3.0), b};
}

Path polyline_path(const std::vector<Vec2>& points, bool closed) {
    Path path;
    for (std::size_t i = 1; i < points.size(); ++i) {
        path.segments.push_back(line_cubic(points[i - 1], points[i]));
    }
    if (closed && points.size() > 2 && !(points.back() == points.front())) {
        path.segments.push_back(line_cubic(points.back(), points.front()));
    }
    path.closed = closed && !path.segments.empty();
    return path;
}

Path transformed(const Path& path, const Affine& m) {
    Path out = path;
    for (Cubic& c : out.segments) {
        c = {m.apply(c.p0), m.apply(c.c1), m.apply(c.c2), m.apply(c.p3)};
    }
    return out;
}

Path reversed(const Path& path) {
    Path out;
    out.closed = path.closed;
    for (auto it = path.segments.rbegin(); it != path.segments.rend(); ++it) {
        out.segments.push_back({it->p3, it->c2, it->c1, it->p0});
    }
    return out;
}

Path ellipse_arc_path(Vec2 center, double rx, double ry, double rotation_rad,
                      double start_angle_rad, double sweep_rad) {
    Path path;
    const int pieces = std::max(
        1, static_cast<int>(std::ceil(std::abs(sweep_rad) / (std::numbers::pi / 2) - 1e-9)));
    const double step = sweep_rad / pieces;
    const double k = 4.0 / 3.0 * std::tan(step / 4.0);
    const double cr = std::cos(rotation_rad), sr = std::sin(rotation_rad);
    auto map = [&](double ux, double uy) {  // unit-circle point to the rotated ellipse
        const double x = rx * ux, y = ry * uy;
        return Vec2{center.x + cr * x - sr * y, center.y + sr * x + cr * y};
    };
    for (int i = 0; i < pieces; ++i) {
        const double t0 = start_angle_rad + step * i, t1 = t0 + step;
        const double c0 = std::cos(t0), s0 = std::sin(t0), c1 = std::cos(t1), s1 = std::sin(t1);
        path.segments.push_back({map(c0, s0), map(c0 - k * s0, s0 + k * c0),
                                 map(c1 + k * s1, s1 - k * c1), map(c1, s1)});
    }
    path.closed = std::abs(std::abs(sweep_rad) - 2 * std::numbers::pi) < 1e-9;
    if (path.closed) path.segments.back().p3 = path.segments.front().p0;
    return path;
}

Path arc_path(Vec2 center, double radius, double start_angle_rad, double sweep_rad) {
    return ellipse_arc_path(center, radius, radius, 0.0, start_angle_rad, sweep_rad);
}

std::vector<Vec2> flatten(const Path& path, double max_step) {
    std::vector<Vec2> points;
    if (path.empty()) return points;
    max_step = std::max(max_step, 1e-6);
    points.push_back(path.start());
    for (const Cubic& c : path.segments) {
        const double hull = distance(c.p0, c.c1) + distance(c.c1, c.c2) + distance(c.c2, c.p3);
        const int n = std::clamp(static_cast<int>(std::ceil(hull / max_step)), 1, 4096);
        for (int i = 1; i <= n; ++i) points.push_back(c.point(static_cast<double>(i) / n));
    }
    return points;
}

double polyline_length(const std::vector<Vec2>& polyline) {
    double length = 0.0;
    for (std::size_t i = 1; i < polyline.size(); ++i) {
        length += distance(polyline[i - 1], polyline[i]);
    }
    return length;
}

double arc_length(const Path& path) {
    return polyline_length(flatten(path, 0.25));
}

namespace {

// Points at the given increasing arc positions along the polyline.
std::vector<Vec2> points_at(const std::vector<Vec2>& polyline, const std::vector<double>& at) {
    std::vector<Vec2> out;
    out.reserve(at.size());
    std::size_t i = 1;
    double before = 0.0;  // arc length at polyline[i - 1]
    for (double s : at) {
        while (i + 1 < polyline.size() && before + distance(polyline[i - 1], polyline[i]) < s) {
            before += distance(polyline[i - 1], polyline[i]);
            ++i;
        }
        const double len = distance(polyline[i - 1], polyline[i]);
        const double t = len > 0.0 ? std::clamp((s - before) / len, 0.0, 1.0) : 0.0;
        out.push_back(lerp(polyline[i - 1], polyline[i], t));
    }
    return out;
}

}  // namespace

std::vector<Vec2> resample(const std::vector<Vec2>& polyline, int count) {
    if (polyline.empty() || count <= 0) return {};
    if (polyline.size() == 1 || count == 1) {
        return std::vector<Vec2>(static_cast<std::size_t>(count), polyline.front());
    }
    const double length = polyline_length(polyline);
    std::vector<double> at(static_cast<std::size_t>(count));
    for (int k = 0; k < count; ++k) at[k] = length * k / (count - 1);
    std::vector<Vec2> out = points_at(polyline, at);
    out.back() = polyline.back();
    return out;
}

std::vector<Vec2> resample_by_step(const std::vector<Vec2>& polyline, double step) {
    if (polyline.size() < 2) return polyline;
    const double length = polyline_length(polyline);
    const int count = std::max(2, static_cast<int>(std::ceil(length / std::max(step, 1e-9))) + 1);
    return resample(polyline, count);
}

std::vector<Vec2> sample_path(const Path& path, int count) {
    const double hull_step = 0.5;
    std::vector<Vec2> dense = flatten(path, hull_step);
    return resample(dense, count);
}

namespace {

double point_segment_distance(Vec2 p, Vec2 a, Vec2 b, double* t_out = nullptr) {
    const Vec2 ab = b - a;
    const double len2 = dot(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    if (t_out != nullptr) *t_out = t;
    return distance(p, a + ab * t);
}

void rdp(const std::vector<Vec2>& pts, std::size_t first, std::size_t last, double eps,
         std::vector<bool>& keep) {
    double worst = -1.0;
    std::size_t index = first;
    for (std::size_t i = first + 1; i < last; ++i) {
        const double d = point_segment_distance(pts[i], pts[first], pts[last]);
        if (d > worst) {
            worst = d;
            index = i;
        }
    }
    if (worst > eps) {
        keep[index] = true;
        rdp(pts, first, index, eps, keep);
        rdp(pts, index, last, eps, keep);
    }
}

}  // namespace

std::vector<Vec2> simplify_rdp(const std::vector<Vec2>& polyline, double epsilon) {
    if (polyline.size() < 3) return polyline;
    std::vector<bool> keep(polyline.size(), false);
    keep.front() = keep.back() = true;
    rdp(polyline, 0, polyline.size() - 1, epsilon, keep);
    std::vector<Vec2> out;
    for (std::size_t i = 0; i < polyline.size(); ++i) {
        if (keep[i]) out.push_back(polyline[i]);
    }
    return out;
}

Vec2 start_tangent(const Path& path) {
    if (path.empty()) return {};
    for (const Cubic& c : path.segments) {
        for (Vec2 q : {c.c1, c.c2, c.p3}) {
            if (distance(q, c.p0) > 1e-9) return normalized(q - path.start());
        }
    }
    return {};
}

Vec2 end_tangent(const Path& path) {
    return -start_tangent(reversed(path));
}

ClosestPoint closest_point(const std::vector<Vec2>& polyline, Vec2 p) {
    ClosestPoint best;
    best.distance = std::numeric_limits<double>::infinity();
    if (polyline.empty()) return best;
    if (polyline.size() == 1) return {polyline.front(), distance(p, polyline.front()), 0.0, {}};
    // Squared distances in the loop; the arc position is summed only up to the winner.
    double best_d2 = std::numeric_limits<double>::infinity();
    std::size_t best_i = 1;
    double best_t = 0.0;
    for (std::size_t i = 1; i < polyline.size(); ++i) {
        const Vec2 a = polyline[i - 1], ab = polyline[i] - a;
        const double len2 = dot(ab, ab);
        const double t = len2 > 0.0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
        const Vec2 q = a + ab * t - p;
        const double d2 = dot(q, q);
        if (d2 < best_d2) {
            best_d2 = d2;
            best_i = i;
            best_t = t;
        }
    }
    double before = 0.0;
    for (std::size_t i = 1; i < best_i; ++i) before += distance(polyline[i - 1], polyline[i]);
    const Vec2 a = polyline[best_i - 1], b = polyline[best_i];
    best = {lerp(a, b, best_t), std::sqrt(best_d2), before + best_t * distance(a, b),
            normalized(b - a)};
    return best;
}

double discrete_frechet(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
    if (a.empty() || b.empty()) return std::numeric_limits<double>::infinity();
    // Row-by-row dynamic programming: ca[j] = coupling distance of (a[0..i], b[0..j]).
    std::vector<double> row(b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        double left = 0.0;  // row[j - 1] of the current row
        double diagonal = 0.0;
        for (std::size_t j = 0; j < b.size(); ++j) {
            const double d = distance(a[i], b[j]);
            double value;
            if (i == 0 && j == 0) {
                value = d;
            } else if (i == 0) {
                value = std::max(left, d);
            } else if (j == 0) {
                value = std::max(row[0], d);
            } else {
                value = std::max(std::min({row[j], diagonal, left}), d);
            }
            diagonal = row[j];
            row[j] = value;
            left = value;
        }
    }
    return row.back();
}

double max_pointwise_distance(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
    double worst = 0.0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
        worst = std::max(worst, distance(a[i], b[i]));
    }
    return worst;
}

Affine fit_similarity(const std::vector<Vec2>& from, const std::vector<Vec2>& to) {
    const std::size_t n = std::min(from.size(), to.size());
    if (n < 2) return {};
    // Centre both point sets; then scos and ssin have a closed form (Procrustes without
    // reflection), and the translation maps centroid to centroid.
    Vec2 cf, ct;
    for (std::size_t i = 0; i < n; ++i) {
        cf += from[i];
        ct += to[i];
    }
    cf = cf / static_cast<double>(n);
    ct = ct / static_cast<double>(n);
    double sxx = 0.0, num_cos = 0.0, num_sin = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec2 p = from[i] - cf, q = to[i] - ct;
        sxx += dot(p, p);
        num_cos += dot(p, q);
        num_sin += cross(p, q);
    }
    if (sxx <= 0.0) return Affine::translation(ct - cf);
    const double scos = num_cos / sxx, ssin = num_sin / sxx;
    Affine m{scos, ssin, -ssin, scos, 0.0, 0.0};
    const Vec2 moved = m.apply_vector(cf);
    m.tx = ct.x - moved.x;
    m.ty = ct.y - moved.y;
    return m;
}

SimilarityParts decompose_similarity(const Affine& m) {
    SimilarityParts parts;
    parts.reflected = m.determinant() < 0.0;
    // m = R(θ)·s·F where F = diag(1, −1) when reflected: the first column is s·(cos θ, sin θ).
    parts.rotation_rad = std::atan2(m.b, m.a);
    parts.scale = std::sqrt(std::abs(m.determinant()));
    parts.translation = {m.tx, m.ty};
    return parts;
}

Circle fit_circle(const std::vector<Vec2>& points) {
    const std::size_t n = points.size();
    if (n < 3) return {};
    // Kåsa: minimize Σ (x² + y² + D·x + E·y + F)² over centred coordinates for conditioning.
    Vec2 mean;
    for (Vec2 p : points) mean += p;
    mean = mean / static_cast<double>(n);
    double suu = 0, suv = 0, svv = 0, suuu = 0, svvv = 0, suvv = 0, svuu = 0;
    for (Vec2 p : points) {
        const double u = p.x - mean.x, v = p.y - mean.y;
        suu += u * u;
        suv += u * v;
        svv += v * v;
        suuu += u * u * u;
        svvv += v * v * v;
        suvv += u * v * v;
        svuu += v * u * u;
    }
    const double det = suu * svv - suv * suv;
    const double scale = suu + svv;
    if (scale <= 0.0 || std::abs(det) <= 1e-12 * scale * scale) return {};
    const double r1 = 0.5 * (suuu + suvv), r2 = 0.5 * (svvv + svuu);
    const double uc = (r1 * svv - r2 * suv) / det;
    const double vc = (r2 * suu - r1 * suv) / det;
    Circle circle;
    circle.center = {uc + mean.x, vc + mean.y};
    circle.radius = std::sqrt(uc * uc + vc * vc + scale / static_cast<double>(n));
    return circle;
}

Box bounding_box(const std::vector<Vec2>& points) {
    if (points.empty()) return {};
    Box box{points.front(), points.front()};
    for (Vec2 p : points) {
        box.lo = {std::min(box.lo.x, p.x), std::min(box.lo.y, p.y)};
        box.hi = {std::max(box.hi.x, p.x), std::max(box.hi.y, p.y)};
    }
    return box;
}

double bounding_diagonal(const std::vector<Vec2>& points) {
    if (points.empty()) return 0.0;
    Vec2 lo = points.front(), hi = points.front();
    for (Vec2 p : points) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    return distance(lo, hi);
}

}  // namespace exemplar::sketch
