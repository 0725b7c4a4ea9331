#pragma once
/// \file
/// Paths of cubic Bézier segments and the sampled-geometry tools the beautification rules work
/// with (ShipShape, Fišer et al. 2016, §7.3.3): sampling, arc length, tangents, Ramer–Douglas–
/// Peucker simplification, closest points, the discrete Fréchet distance, similarity transforms.
///
/// Conventions: coordinates are doubles in the drawing's user space (SVG y points down). All
/// functions are pure; none throws. Degenerate input (an empty path, a polyline of one point) gives
/// empty or zero results as documented per function.

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace exemplar::sketch {

/// A 2D point or vector.
struct Vec2 {
    double x = 0.0;
    double y = 0.0;

    friend Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
    friend Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
    friend Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
    friend Vec2 operator*(Vec2 a, double s) { return {a.x * s, a.y * s}; }
    friend Vec2 operator*(double s, Vec2 a) { return {a.x * s, a.y * s}; }
    friend Vec2 operator/(Vec2 a, double s) { return {a.x / s, a.y / s}; }
    friend bool operator==(Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; }
    Vec2& operator+=(Vec2 b) { return *this = *this + b; }
    Vec2& operator-=(Vec2 b) { return *this = *this - b; }
};

inline double dot(Vec2 a, Vec2 b) {
    return a.x * b.x + a.y * b.y;
}
inline double cross(Vec2 a, Vec2 b) {
    return a.x * b.y - a.y * b.x;
}
/// Length of a vector (plain square root: coordinates are far from overflow, and std::hypot is
/// several times slower in the closest-point loops).
inline double norm(Vec2 a) {
    return std::sqrt(a.x * a.x + a.y * a.y);
}
inline double distance(Vec2 a, Vec2 b) {
    return norm(a - b);
}
/// `a` scaled to length 1, or (0, 0) if `a` is (0, 0).
inline Vec2 normalized(Vec2 a) {
    const double n = norm(a);
    return n > 0.0 ? a / n : Vec2{};
}
/// `a` rotated by +90° (in y-down coordinates: clockwise on screen).
inline Vec2 perpendicular(Vec2 a) {
    return {-a.y, a.x};
}
inline Vec2 lerp(Vec2 a, Vec2 b, double t) {
    return a + (b - a) * t;
}
/// Unsigned angle between two directions, in [0, π]; 0 if either is (0, 0).
double angle_between(Vec2 a, Vec2 b);
/// Unsigned angle between two undirected lines with these directions, in [0, π/2].
double line_angle_between(Vec2 a, Vec2 b);

/// An affine map p ↦ (a·x + c·y + tx, b·x + d·y + ty). Default: identity.
struct Affine {
    double a = 1.0, b = 0.0, c = 0.0, d = 1.0, tx = 0.0, ty = 0.0;

    Vec2 apply(Vec2 p) const { return {a * p.x + c * p.y + tx, b * p.x + d * p.y + ty}; }
    /// The linear part applied to a vector (no translation).
    Vec2 apply_vector(Vec2 v) const { return {a * v.x + c * v.y, b * v.x + d * v.y}; }
    double determinant() const { return a * d - b * c; }
    /// Inverse; the identity if the map is singular.
    Affine inverse() const;
    /// `outer ∘ inner`: first `inner`, then `outer`.
    friend Affine compose(const Affine& outer, const Affine& inner);

    static Affine translation(Vec2 t) { return {1.0, 0.0, 0.0, 1.0, t.x, t.y}; }
    static Affine scaling(double sx, double sy) { return {sx, 0.0, 0.0, sy, 0.0, 0.0}; }
    /// Rotation by `angle_rad` about `center`.
    static Affine rotation(double angle_rad, Vec2 center = {});
    /// Reflection across the line through `point` with direction `direction`.
    static Affine reflection(Vec2 point, Vec2 direction);
    /// Rotation by `angle_rad` and uniform `scale` about `center`.
    static Affine similarity(double angle_rad, double scale, Vec2 center);
};

/// One cubic Bézier segment.
struct Cubic {
    Vec2 p0, c1, c2, p3;

    Vec2 point(double t) const;
    /// First derivative d/dt.
    Vec2 derivative(double t) const;
    /// Second derivative d²/dt².
    Vec2 second_derivative(double t) const;
    /// The two halves of a de Casteljau split at `t`.
    std::array<Cubic, 2> split(double t) const;
};

/// A straight segment as a cubic (controls at 1/3 and 2/3).
Cubic line_cubic(Vec2 a, Vec2 b);

/// A path: end-to-end connected cubic segments (segment i's p3 is segment i+1's p0). `closed`
/// paths end where they start.
struct Path {
    std::vector<Cubic> segments;
    bool closed = false;

    bool empty() const { return segments.empty(); }
    Vec2 start() const { return segments.front().p0; }
    Vec2 end() const { return segments.back().p3; }
};

/// A path through the points joined by straight segments.
Path polyline_path(const std::vector<Vec2>& points, bool closed = false);
/// The path with every control point mapped by `m` (exact for affine maps).
Path transformed(const Path& path, const Affine& m);
/// The same curve traversed from end to start.
Path reversed(const Path& path);
/// A circular arc (centre, radius, start angle, signed sweep; radians, y-down) as cubics of at
/// most 90° each, with the standard 4/3·tan(θ/4) handles.
Path arc_path(Vec2 center, double radius, double start_angle_rad, double sweep_rad);
/// An elliptical arc: radii `rx`, `ry`, the ellipse rotated by `rotation_rad` about `center`.
Path ellipse_arc_path(Vec2 center, double rx, double ry, double rotation_rad,
                      double start_angle_rad, double sweep_rad);

/// The path flattened to a polyline whose points are at most `max_step` apart along each
/// segment's control polygon (so about `max_step` apart on the curve). Empty path: empty.
std::vector<Vec2> flatten(const Path& path, double max_step);
/// Length of a polyline.
double polyline_length(const std::vector<Vec2>& polyline);
/// Arc length of a path (flattened at 0.25 units).
double arc_length(const Path& path);
/// `count` ≥ 2 points equally spaced along the polyline by arc length, first and last included.
/// A polyline of one point repeats it; an empty one gives an empty result.
std::vector<Vec2> resample(const std::vector<Vec2>& polyline, int count);
/// Points along the polyline every `step` units of arc length (the last point always included).
std::vector<Vec2> resample_by_step(const std::vector<Vec2>& polyline, double step);
/// `count` points equally spaced by arc length along the path.
std::vector<Vec2> sample_path(const Path& path, int count);
/// Ramer–Douglas–Peucker: the subset of `polyline` (endpoints kept) within `epsilon` of it.
std::vector<Vec2> simplify_rdp(const std::vector<Vec2>& polyline, double epsilon);

/// Unit tangent at the start (pointing into the path) and at the end (pointing out of it),
/// taken from the first control point that differs from the endpoint.
Vec2 start_tangent(const Path& path);
Vec2 end_tangent(const Path& path);

/// The closest point of a polyline to `p`.
struct ClosestPoint {
    Vec2 point;
    double distance = 0.0;
    double arc_position = 0.0;  ///< Arc length from the polyline's start to `point`.
    Vec2 tangent;               ///< Unit direction of the polyline segment holding `point`.
};
ClosestPoint closest_point(const std::vector<Vec2>& polyline, Vec2 p);

/// Discrete Fréchet distance between two point sequences (Eiter and Mannila 1994), O(n·m) time,
/// O(m) memory. Either sequence empty: +infinity.
double discrete_frechet(const std::vector<Vec2>& a, const std::vector<Vec2>& b);
/// Largest distance between corresponding points of two equally long sequences.
double max_pointwise_distance(const std::vector<Vec2>& a, const std::vector<Vec2>& b);

/// The similarity transform (rotation, uniform scale, translation; Eq. 7.3) minimizing
/// Σ‖M·from_i − to_i‖² (Eq. 7.4) for equally long point lists; identity if fewer than 2 points
/// or `from` is a single repeated point.
Affine fit_similarity(const std::vector<Vec2>& from, const std::vector<Vec2>& to);

/// Rotation (radians), uniform scale and reflection of an affine map treated as a similarity
/// (Eq. 7.5). A reflected map is decomposed as (rotation·scale)∘(y ↦ −y).
struct SimilarityParts {
    double rotation_rad = 0.0;
    double scale = 1.0;
    bool reflected = false;
    Vec2 translation;
};
SimilarityParts decompose_similarity(const Affine& m);

/// A circle fitted to points (algebraic least squares, Kåsa); radius 0 if the points are
/// collinear or fewer than 3.
struct Circle {
    Vec2 center;
    double radius = 0.0;
};
Circle fit_circle(const std::vector<Vec2>& points);

/// An axis-aligned box.
struct Box {
    Vec2 lo, hi;
    /// Distance from `p` to the box (0 inside).
    double distance_to(Vec2 p) const {
        const double dx = std::max({lo.x - p.x, 0.0, p.x - hi.x});
        const double dy = std::max({lo.y - p.y, 0.0, p.y - hi.y});
        return std::sqrt(dx * dx + dy * dy);
    }
    /// True if the boxes, each grown by `margin`, overlap.
    bool near(const Box& other, double margin) const {
        return lo.x - margin <= other.hi.x && other.lo.x <= hi.x + margin &&
               lo.y - margin <= other.hi.y && other.lo.y <= hi.y + margin;
    }
};
/// Bounding box of points (all zero if empty).
Box bounding_box(const std::vector<Vec2>& points);

/// Bounding box diagonal of a polyline (a size measure); 0 if empty.
double bounding_diagonal(const std::vector<Vec2>& points);

}  // namespace exemplar::sketch
