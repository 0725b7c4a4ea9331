// Arc and circle centre snapping (§7.3.1): the distance from the centre of an arc or circle to
// candidate centres — endpoints of resolved paths, centres of resolved arcs and circles, and
// centres of rotation used so far — within the adaptive radius max(D, 2r(1 − θ/2π)) (Fig. 7.6),
// θ the span, D = 30 view px. Deviation: centres of regular polygons made of line series are not
// offered. A free arc or circle is translated; an arc with one fixed endpoint keeps it and takes
// the radius to it. Fixes the centre.

#include <cmath>
#include <numbers>

#include "rule_util.hpp"
#include "rules.hpp"

namespace exemplar::sketch::rules {

namespace {

class ArcCenterRule final : public Rule {
public:
    const char* name() const override { return "arc-center"; }
    double threshold(const BeautifyOptions& o) const override { return o.arc_center.threshold; }

    std::vector<RuleOutput> apply(const Candidate& input,
                                  const RuleContext& context) const override {
        std::vector<RuleOutput> out;
        if (input.kind != ShapeKind::Arc && input.kind != ShapeKind::Circle) return out;
        if (input.fixed.center || (input.fixed.start && input.fixed.end)) return out;
        const ArcGeometry& arc = input.arc;
        const double span = std::min(std::abs(arc.sweep_rad), 2 * std::numbers::pi);
        const double radius_px =
            std::max(context.options->center_search_px,
                     2 * context.px(arc.radius) * (1 - span / (2 * std::numbers::pi)));

        struct Target {
            Vec2 point;
            int path;
            std::string what;
        };
        std::vector<Target> targets;
        for (std::size_t i = 0; i < context.paths.size(); ++i) {
            const ResolvedPath& p = *context.paths[i];
            if (!p.geometric) continue;
            const int index = static_cast<int>(i);
            if (p.kind == ShapeKind::Arc || p.kind == ShapeKind::Circle) {
                targets.push_back({p.arc.center, index, "centre"});
            }
            if (!p.path.closed) {
                targets.push_back({p.path.start(), index, "start"});
                targets.push_back({p.path.end(), index, "end"});
            }
        }
        for (std::size_t k = 0; k < context.rotation_centers.size(); ++k) {
            targets.push_back({context.rotation_centers[k], -1, std::string("rotation centre ") + std::to_string(k)});
        }
        for (const Target& t : targets) {
            const double d = context.px(distance(t.point, arc.center));
            const double likelihood = falloff(d, radius_px);
            if (likelihood < context.options->arc_center.threshold) continue;
            std::optional<Candidate> c = recentred(input, t.point);
            if (!c) continue;
            c->fixed.center = true;
            const int stroke = stroke_of(context, t.path);
            Relation r{name(), std::string("center:") + std::to_string(t.path) + t.what,
                       t.path >= 0 ? std::vector<int>{stroke} : std::vector<int>{}, likelihood,
                       "centre snapped to the " + t.what +
                           (t.path >= 0 ? std::string(" of stroke ") + std::to_string(stroke) : "") +
                           std::string(" (moved ") + fixed1(d) + " px)"};
            out.push_back({with_relation(std::move(*c), std::move(r)), likelihood});
        }
        keep_best(out, 3);
        return out;
    }

private:
    static std::optional<Candidate> recentred(const Candidate& input, Vec2 center) {
        if (!input.fixed.start && !input.fixed.end) {
            return moved(input, Affine::translation(center - input.arc.center));
        }
        if (input.kind == ShapeKind::Circle) return std::nullopt;
        const Vec2 anchor = input.fixed.start ? input.path.start() : input.path.end();
        ArcGeometry arc = input.arc;
        arc.center = center;
        arc.radius = distance(anchor, center);
        if (!(arc.radius > 0.0)) return std::nullopt;
        const double anchor_angle = std::atan2(anchor.y - center.y, anchor.x - center.x);
        arc.start_angle_rad = input.fixed.start ? anchor_angle : anchor_angle - arc.sweep_rad;
        Candidate c = as_arc(input, arc, false);
        if (input.fixed.start) c.path.segments.front().p0 = anchor;
        if (input.fixed.end) c.path.segments.back().p3 = anchor;
        return c;
    }
};

}  // namespace

std::unique_ptr<Rule> make_arc_center_rule() { return std::make_unique<ArcCenterRule>(); }

}  // namespace exemplar::sketch::rules
