// Arc and circle centre snapping (§7.3.1): the distance from the centre of an arc or circle to
// candidate centres — endpoints of resolved paths, centres of resolved arcs and circles, and
// centres of rotation used so far — within the adaptive radius max(D, 2r(1 − θ/2π)) (Fig. 7.6),
// θ the span, D = 30 view px. Deviation: centres of regular polygons made of line series are not
// offered. A circle is translated; an arc is refitted around the new centre through its
// endpoints' directions (mean radius of its samples, or the radius to a fixed endpoint), and the
// likelihood is capped by how far it moves (`shape_tolerance_px`). Fixes the centre.

#include <algorithm>
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
            targets.push_back({context.rotation_centers[k], -1,
                               std::string("rotation centre ") + std::to_string(k)});
        }
        for (const Target& t : targets) {
            const double d = context.px(distance(t.point, arc.center));
            double likelihood = falloff(d, radius_px);
            if (likelihood < context.options->arc_center.threshold) continue;
            const int n = context.options->match_samples;
            std::optional<Candidate> c = recentred(input, t.point, n);
            if (!c) continue;
            // The refitted arc must stay close to the drawn one.
            const double moved_px = context.px(discrete_frechet(samples(input, n), samples(*c, n)));
            likelihood =
                std::min(likelihood, falloff(moved_px, context.options->shape_tolerance_px));
            if (likelihood < context.options->arc_center.threshold) continue;
            c->fixed.center = true;
            const int stroke = stroke_of(context, t.path);
            Relation r{name(), std::string("center:") + std::to_string(t.path) + t.what,
                       t.path >= 0 ? std::vector<int>{stroke} : std::vector<int>{}, likelihood,
                       "centre snapped to the " + t.what +
                           (t.path >= 0 ? " of " + stroke_name(context, t.path) : std::string()) +
                           std::string(" (moved ") + fixed1(d) + " px)"};
            out.push_back({with_relation(std::move(*c), std::move(r)), likelihood});
        }
        keep_best(out, 3);
        return out;
    }

private:
    // The arc or circle around `center`: a circle is moved; an arc is refitted through its
    // endpoints' directions with the mean radius of its samples (or the radius to its fixed
    // endpoint), so that it stays where it was drawn (Fig. 7.6).
    static std::optional<Candidate> recentred(const Candidate& input, Vec2 center, int samples_n) {
        if (input.kind == ShapeKind::Circle) {
            if (input.fixed.start || input.fixed.end) return std::nullopt;
            return moved(input, Affine::translation(center - input.arc.center));
        }
        const Vec2 s = input.path.start(), e = input.path.end();
        ArcGeometry arc = input.arc;
        arc.center = center;
        if (input.fixed.start || input.fixed.end) {
            arc.radius = distance(input.fixed.start ? s : e, center);
        } else {
            double sum = 0.0;
            const std::vector<Vec2> pts = samples(input, samples_n);
            for (Vec2 p : pts) sum += distance(p, center);
            arc.radius = sum / static_cast<double>(pts.size());
        }
        if (!(arc.radius > 0.0)) return std::nullopt;
        const double sa = std::atan2(s.y - center.y, s.x - center.x);
        const double ea = std::atan2(e.y - center.y, e.x - center.x);
        double sweep = wrap_angle(ea - sa);
        if (sweep * input.arc.sweep_rad < 0)
            sweep += sweep < 0 ? 2 * std::numbers::pi : -2 * std::numbers::pi;
        arc.start_angle_rad = sa;
        arc.sweep_rad = sweep;
        Candidate c = as_arc(input, arc, false);
        if (input.fixed.start) c.path.segments.front().p0 = s;
        if (input.fixed.end) c.path.segments.back().p3 = e;
        return c;
    }
};

}  // namespace

std::unique_ptr<Rule> make_arc_center_rule() {
    return std::make_unique<ArcCenterRule>();
}

}  // namespace exemplar::sketch::rules
