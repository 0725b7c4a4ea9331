// Endpoint snapping (§7.3.1): the distance from each free endpoint to the endpoints of resolved
// paths and to their inner points (the closest point on each path; endpoints are preferred).
// The endpoint is moved by a similarity about the other endpoint (rotation + scale, so the rest
// of the stroke keeps its shape and the other end stays put), or by a translation when the
// direction, length or transformation is fixed (or slid along its fixed direction when the other
// end is fixed too and the target lies on that line). Paths are not joined (round caps hide the
// seam). Fixes the endpoint and records what it is attached to (for end-tangent alignment).

#include <cmath>

#include "rule_util.hpp"
#include "rules.hpp"

namespace exemplar::sketch::rules {

namespace {

constexpr double kInnerPreference = 0.85;  // inner points score below endpoints at equal distance
constexpr std::size_t kPerEndpoint = 3;
constexpr double kOnLine = 1e-6;  // drawing units: "on the line" for sliding a fixed-direction end

// The map that moves one endpoint onto `target` without breaking fixed properties.
std::optional<Affine> endpoint_move(const Candidate& c, bool at_start, Vec2 target) {
    const Vec2 p = at_start ? c.path.start() : c.path.end();
    const Vec2 other = at_start ? c.path.end() : c.path.start();
    const bool other_fixed = at_start ? c.fixed.end : c.fixed.start;
    const bool rigid = c.fixed.direction || c.fixed.length || c.fixed.transform;
    if (!rigid) {
        const Vec2 u = p - other, v = target - other;
        if (norm(u) < 1e-9 || norm(v) < 1e-9) {
            return other_fixed ? std::nullopt
                               : std::optional<Affine>(Affine::translation(target - p));
        }
        const double scale = norm(v) / norm(u);
        if (scale < 0.5 || scale > 2.0) return std::nullopt;
        return Affine::similarity(std::atan2(cross(u, v), dot(u, v)), scale, other);
    }
    if (!other_fixed) return Affine::translation(target - p);
    // Both the direction and the other end are fixed: the endpoint may still slide along the
    // line if the target lies on it (closing a rectangle after a perpendicularity snap).
    if (c.fixed.length || c.fixed.transform) return std::nullopt;
    const Vec2 u = p - other, v = target - other;
    if (norm(u) < 1e-9 || dot(u, v) <= 0.0) return std::nullopt;
    const double off_line = std::abs(cross(normalized(u), v));
    if (off_line > kOnLine) return std::nullopt;
    return Affine::similarity(0.0, dot(normalized(u), v) / norm(u), other);
}

class EndpointRule final : public Rule {
public:
    const char* name() const override { return "endpoint"; }
    bool repeatable() const override { return true; }
    double threshold(const BeautifyOptions& o) const override { return o.endpoint.threshold; }

    std::vector<RuleOutput> apply(const Candidate& input,
                                  const RuleContext& context) const override {
        std::vector<RuleOutput> out;
        if (input.path.closed || input.kind == ShapeKind::Circle) return out;
        for (bool at_start : {true, false}) {
            if (at_start ? input.fixed.start : input.fixed.end) continue;
            std::vector<RuleOutput> mine = snaps(input, context, at_start);
            keep_best(mine, kPerEndpoint);
            for (RuleOutput& o : mine) out.push_back(std::move(o));
        }
        return out;
    }

private:
    std::vector<RuleOutput> snaps(const Candidate& input, const RuleContext& context,
                                  bool at_start) const {
        const RuleParams& params = context.options->endpoint;
        const Vec2 p = at_start ? input.path.start() : input.path.end();
        const Vec2 other = at_start ? input.path.end() : input.path.start();
        const std::string which = at_start ? "start" : "end";
        std::vector<RuleOutput> out;
        auto propose = [&](int path, Vec2 target, Vec2 tangent, bool endpoint, double likelihood,
                           const std::string& where) {
            if (likelihood < params.threshold) return;
            if (context.px(distance(target, other)) < 2.0) return;  // would collapse the path
            const std::optional<Affine> m = endpoint_move(input, at_start, target);
            if (!m) return;
            Candidate c = moved(input, *m);
            // Exact position despite rounding in the similarity.
            if (at_start) {
                c.path.segments.front().p0 = target;
                c.fixed.start = true;
                c.start_attachment = Attachment{path, target, tangent, endpoint};
            } else {
                c.path.segments.back().p3 = target;
                c.fixed.end = true;
                c.end_attachment = Attachment{path, target, tangent, endpoint};
            }
            const int stroke = stroke_of(context, path);
            Relation r{name(),
                       "snap-" + which + std::string(":") + std::to_string(path) + where,
                       {stroke},
                       likelihood,
                       which + " snapped to " + (endpoint ? "an endpoint" : "a point") + " of " +
                           stroke_name(context, path) + " (moved " +
                           fixed1(context.px(distance(p, target))) + " px)"};
            out.push_back({with_relation(std::move(c), std::move(r)), likelihood});
        };
        for (std::size_t i = 0; i < context.paths.size(); ++i) {
            const ResolvedPath& target = *context.paths[i];
            if (!target.geometric || target.dense.empty()) continue;
            const int index = static_cast<int>(i);
            const double radius = context.units(params.tolerance);
            if (target.box.distance_to(p) >= radius) continue;
            bool near_end = false;
            if (!target.path.closed) {
                const Vec2 ends[2] = {target.path.start(), target.path.end()};
                const Vec2 tangents[2] = {start_tangent(target.path), end_tangent(target.path)};
                for (int k = 0; k < 2; ++k) {
                    const double d = distance(p, ends[k]);
                    if (d >= radius) continue;
                    near_end = true;
                    propose(index, ends[k], tangents[k], true,
                            falloff(context.px(d), params.tolerance), k == 0 ? ".s" : ".e");
                }
            }
            if (near_end) continue;
            const ClosestPoint inner = closest_point(target.dense, p);
            if (inner.distance >= radius) continue;
            propose(index, inner.point, inner.tangent, false,
                    kInnerPreference * falloff(context.px(inner.distance), params.tolerance),
                    std::string("@") + std::to_string(static_cast<long>(
                                           std::lround(context.px(inner.arc_position)))));
        }
        return out;
    }
};

}  // namespace

std::unique_ptr<Rule> make_endpoint_rule() {
    return std::make_unique<EndpointRule>();
}

}  // namespace exemplar::sketch::rules
