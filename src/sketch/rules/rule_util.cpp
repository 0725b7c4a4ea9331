// Helpers shared by the rules, the rule registry and resolved-path preparation.

#include "rule_util.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

namespace exemplar::sketch {

const char* to_string(ShapeKind kind) {
    switch (kind) {
        case ShapeKind::Line: return "line";
        case ShapeKind::Arc: return "arc";
        case ShapeKind::Circle: return "circle";
        case ShapeKind::Curve: break;
    }
    return "curve";
}

Candidate make_candidate(const Path& path) {
    Candidate c;
    c.path = path;
    return c;
}

ResolvedPath resolve_path(const Candidate& candidate, int stroke, int segment,
                          double pixels_per_unit, const BeautifyOptions& options) {
    ResolvedPath r;
    r.path = candidate.path;
    r.kind = candidate.kind;
    r.arc = candidate.arc;
    r.stroke = stroke;
    r.segment = segment;
    const double unit = 1.0 / pixels_per_unit;
    r.dense = resample_by_step(flatten(candidate.path, 0.5 * unit), 2.0 * unit);
    r.simplified = simplify_rdp(r.dense, options.rdp_epsilon_px * unit);
    r.match = resample(r.dense, options.match_samples);
    r.length = polyline_length(r.dense);
    r.box = bounding_box(r.dense);
    return r;
}

namespace rules {

Candidate moved(const Candidate& c, const Affine& m) {
    Candidate out = c;
    out.path = transformed(c.path, m);
    if (c.kind == ShapeKind::Arc || c.kind == ShapeKind::Circle) {
        const SimilarityParts parts = decompose_similarity(m);
        out.arc.center = m.apply(c.arc.center);
        out.arc.radius = c.arc.radius * parts.scale;
        // The start point's new angle; the sweep flips with a reflection.
        const Vec2 start =
            c.arc.center +
            Vec2{std::cos(c.arc.start_angle_rad), std::sin(c.arc.start_angle_rad)} * c.arc.radius;
        const Vec2 moved_start = m.apply(start) - out.arc.center;
        out.arc.start_angle_rad = std::atan2(moved_start.y, moved_start.x);
        out.arc.sweep_rad = parts.reflected ? -c.arc.sweep_rad : c.arc.sweep_rad;
    }
    if (out.instance) {
        out.instance->from_template = compose(m, c.instance->from_template);
        out.instance->relative = compose(m, c.instance->relative);
    }
    return out;
}

Candidate with_relation(Candidate c, Relation relation) {
    c.relations.push_back(std::move(relation));
    return c;
}

double straightness(const Path& path) {
    const std::vector<Vec2> pts = flatten(path, 1.0);
    const double length = polyline_length(pts);
    if (length <= 0.0) return 1.0;
    return std::min(1.0, distance(path.start(), path.end()) / length);
}

std::optional<Vec2> pivot(const Candidate& c) {
    if (c.fixed.start && c.fixed.end) return std::nullopt;
    if (c.fixed.start) return c.path.start();
    if (c.fixed.end) return c.path.end();
    return (c.path.start() + c.path.end()) / 2.0;
}

std::string stroke_name(const RuleContext& context, int path) {
    if (path < 0 || path >= static_cast<int>(context.paths.size())) return "the drawing";
    const ResolvedPath& p = *context.paths[static_cast<std::size_t>(path)];
    if (p.stroke == context.current_stroke) {
        return std::string("segment ") + std::to_string(p.segment) + " of this stroke";
    }
    return std::string("stroke ") + std::to_string(p.stroke);
}

Candidate as_line(const Candidate& c, Vec2 a, Vec2 b) {
    Candidate out = c;
    out.path = polyline_path({a, b});
    out.kind = ShapeKind::Line;
    out.fixed.shape = true;
    return out;
}

Candidate as_arc(const Candidate& c, const ArcGeometry& arc, bool circle) {
    Candidate out = c;
    out.arc = arc;
    out.kind = circle ? ShapeKind::Circle : ShapeKind::Arc;
    out.path = arc_path(arc.center, arc.radius, arc.start_angle_rad, arc.sweep_rad);
    if (circle) out.path.closed = true;
    out.fixed.shape = true;
    return out;
}

double move_distance(const Candidate& a, const Candidate& b, int count) {
    return max_pointwise_distance(sample_path(a.path, count), sample_path(b.path, count));
}

Vec2 centroid(const std::vector<Vec2>& points) {
    Vec2 sum;
    for (Vec2 p : points) sum += p;
    return points.empty() ? sum : sum / static_cast<double>(points.size());
}

double repeat_boost(double s, int i) {
    const double exponent = std::log(static_cast<double>(std::max(i, 1)));
    if (exponent <= 1.0) return s;
    return 1.0 - std::pow(1.0 - s, exponent);
}

void keep_best(std::vector<RuleOutput>& outputs, std::size_t keep) {
    std::stable_sort(outputs.begin(), outputs.end(), [](const RuleOutput& a, const RuleOutput& b) {
        return a.likelihood > b.likelihood;
    });
    if (outputs.size() > keep) outputs.resize(keep);
}

std::string fixed1(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.1f", v);
    return buffer;
}

std::vector<int> copies_of(const RuleContext& context, int template_path) {
    std::vector<int> copies;
    for (std::size_t i = 0; i < context.paths.size(); ++i) {
        const ResolvedPath& p = *context.paths[i];
        if (p.shape && p.template_path == template_path) copies.push_back(static_cast<int>(i));
    }
    return copies;
}

double wrap_angle(double a) {
    const double two_pi = 2 * std::numbers::pi;
    a = std::fmod(a, two_pi);
    if (a <= -std::numbers::pi) a += two_pi;
    if (a > std::numbers::pi) a -= two_pi;
    return a;
}

std::pair<double, double> snap_rotation(double angle_rad) {
    double best = 0.0, best_distance = std::abs(wrap_angle(angle_rad));
    for (int k = 2; k <= 12; ++k) {
        const double step = 2 * std::numbers::pi / k;
        const double snapped = std::round(angle_rad / step) * step;
        const double d = std::abs(wrap_angle(angle_rad - snapped));
        if (d < best_distance - 1e-12) {
            best = wrap_angle(snapped);
            best_distance = d;
        }
    }
    return {best, best_distance};
}

std::vector<RuleOutput> snap_line_angle(const Candidate& input, const RuleContext& context,
                                        const RuleParams& params, double offset_rad,
                                        const char* rule_name) {
    std::vector<RuleOutput> out;
    // Lines, and not yet classified paths through their chords (§7.3.1).
    const bool line_like =
        input.kind == ShapeKind::Line || (input.kind == ShapeKind::Curve && !input.fixed.shape &&
                                          !input.path.closed && straightness(input.path) >= 0.9);
    if (!line_like || input.fixed.direction) return out;
    const std::optional<Vec2> center = pivot(input);
    if (!center) return out;
    const Vec2 dir = chord(input);
    const double length = norm(dir);
    if (context.px(length) < 4.0) return out;
    std::vector<double> seen_angles;
    for (std::size_t i = 0; i < context.paths.size(); ++i) {
        const ResolvedPath& target = *context.paths[i];
        if (!target.geometric || target.kind != ShapeKind::Line) continue;
        const Vec2 target_dir = target.path.end() - target.path.start();
        // Signed rotation that makes the chord's angle to the target exactly offset_rad.
        const double current = std::atan2(cross(target_dir, dir), dot(target_dir, dir));
        double best_rotation = 0.0, best_error = 1e9;
        for (double goal : {offset_rad, -offset_rad, std::numbers::pi - offset_rad,
                            -std::numbers::pi + offset_rad}) {
            const double rotation = wrap_angle(goal - current);
            if (std::abs(rotation) < best_error) {
                best_error = std::abs(rotation);
                best_rotation = rotation;
            }
        }
        if (falloff(best_error, params.tolerance) < params.threshold) continue;
        // Nearby lines are slightly preferred (§7.3.1).
        const ClosestPoint near =
            closest_point(target.simplified, (input.path.start() + input.path.end()) / 2.0);
        const double proximity =
            1.0 -
            0.15 * std::min(1.0, context.px(near.distance) / std::max(1.0, 2 * context.px(length)));
        const double likelihood = falloff(best_error, params.tolerance) * proximity;
        if (likelihood < params.threshold) continue;
        const double new_angle = std::atan2(dir.y, dir.x) + best_rotation;
        bool duplicate = false;
        for (double a : seen_angles) duplicate |= std::abs(wrap_angle(a - new_angle)) < 1e-9;
        if (duplicate) continue;
        seen_angles.push_back(new_angle);
        Candidate c = moved(input, Affine::rotation(best_rotation, *center));
        c.fixed.direction = true;
        Relation r{rule_name,
                   std::string(rule_name) + std::string(":") + std::to_string(i),
                   {target.stroke},
                   likelihood,
                   std::string(rule_name) + " to " + stroke_name(context, static_cast<int>(i)) +
                       std::string(" (was ") + degrees(best_error) + "° off)"};
        out.push_back({with_relation(std::move(c), std::move(r)), likelihood});
    }
    keep_best(out, 3);
    return out;
}

}  // namespace rules
}  // namespace exemplar::sketch
