// Arc detection (§7.3.1): a least-squares circle fit of the samples gives centre and radius; the
// angular span comes from projecting the samples on the circle; the arc is sampled again and
// compared with the input by the discrete Fréchet distance (relative to the path length). Spans
// close to 2π, or closed paths, become full circles. Deviations: spans under 30° are left to the
// line rule (a nearly straight stroke fits a huge circle), the likelihood is also capped by the
// absolute Fréchet distance (`shape_tolerance_px`), and fixed endpoints are kept by
// moving the centre onto their bisector (both fixed) or refitting the radius (one fixed).

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rule_util.hpp"
#include "rules.hpp"

namespace exemplar::sketch::rules {

namespace {

constexpr double kMinSpanRad = 0.52;    // 30°
constexpr double kCircleGapRad = 0.45;  // spans within ~26° of 2π close into circles

class ArcRule final : public Rule {
public:
    const char* name() const override { return "arc"; }
    double threshold(const BeautifyOptions& o) const override { return o.arc.threshold; }

    std::vector<RuleOutput> apply(const Candidate& input,
                                  const RuleContext& context) const override {
        const RuleParams& params = context.options->arc;
        if (input.kind != ShapeKind::Curve || input.fixed.shape) return {};
        const int n = context.options->match_samples;
        const std::vector<Vec2> pts = samples(input, n);
        const double length = polyline_length(pts);
        if (context.px(length) < 6.0) return {};
        const Circle fit = fit_circle(pts);
        if (!(fit.radius > 0.0) || fit.radius > 4.0 * length) return {};

        // Angular span: unwrap the sample angles around the centre.
        double sweep = 0.0;
        double previous = std::atan2(pts[0].y - fit.center.y, pts[0].x - fit.center.x);
        const double start_angle = previous;
        for (std::size_t i = 1; i < pts.size(); ++i) {
            const double a = std::atan2(pts[i].y - fit.center.y, pts[i].x - fit.center.x);
            sweep += wrap_angle(a - previous);
            previous = a;
        }
        if (std::abs(sweep) < kMinSpanRad) return {};
        const bool closed_input =
            input.path.closed || distance(input.path.start(), input.path.end()) < 0.08 * length;
        const bool circle = closed_input || std::abs(sweep) > 2 * std::numbers::pi - kCircleGapRad;
        if (circle && (input.fixed.start != input.fixed.end)) return {};

        ArcGeometry arc{fit.center, fit.radius, start_angle,
                        circle ? std::copysign(2 * std::numbers::pi, sweep) : sweep};
        if (!circle && !constrain_to_fixed_ends(input, arc)) return {};

        // Compared over the span that was drawn (a nearly closed stroke against the full circle
        // would count its gap as error).
        const Path shape =
            arc_path(arc.center, arc.radius, arc.start_angle_rad, circle ? sweep : arc.sweep_rad);
        const double frechet = discrete_frechet(sample_path(shape, n), pts);
        const double likelihood =
            std::min(falloff(frechet / length, params.tolerance),
                     falloff(context.px(frechet), context.options->shape_tolerance_px));
        if (likelihood < params.threshold) return {};
        Candidate c = as_arc(input, arc, circle);
        if (!circle) {  // exact endpoints for the fixed ones
            if (input.fixed.start) c.path.segments.front().p0 = input.path.start();
            if (input.fixed.end) c.path.segments.back().p3 = input.path.end();
        }
        const std::string what = circle ? "circle" : "arc";
        Relation r{name(),
                   what,
                   {},
                   likelihood,
                   "fitted a " + what + std::string(" (radius ") + fixed1(context.px(arc.radius)) +
                       std::string(" px, span ") + degrees(std::abs(arc.sweep_rad)) + "°)"};
        return {{with_relation(std::move(c), std::move(r)), likelihood}};
    }

private:
    // Adjusts the fitted arc so that it passes through the fixed endpoints exactly.
    static bool constrain_to_fixed_ends(const Candidate& input, ArcGeometry& arc) {
        const Vec2 s = input.path.start(), e = input.path.end();
        if (input.fixed.start && input.fixed.end) {
            const Vec2 mid = (s + e) / 2.0;
            const Vec2 normal = normalized(perpendicular(e - s));
            if (norm(normal) == 0.0) return false;
            arc.center = mid + normal * dot(arc.center - mid, normal);
        } else if (!input.fixed.start && !input.fixed.end) {
            return true;
        }
        const Vec2 anchor = input.fixed.start ? s : e;
        arc.radius = distance(anchor, arc.center);
        if (!(arc.radius > 0.0)) return false;
        const double sa = std::atan2(s.y - arc.center.y, s.x - arc.center.x);
        if (input.fixed.start && input.fixed.end) {
            const double ea = std::atan2(e.y - arc.center.y, e.x - arc.center.x);
            double sweep = wrap_angle(ea - sa);
            // Keep the fitted direction and roughly the fitted span (small or large arc).
            if (sweep * arc.sweep_rad < 0)
                sweep += sweep < 0 ? 2 * std::numbers::pi : -2 * std::numbers::pi;
            arc.sweep_rad = sweep;
            arc.start_angle_rad = sa;
        } else if (input.fixed.start) {
            arc.start_angle_rad = sa;
        } else {
            const double ea = std::atan2(e.y - arc.center.y, e.x - arc.center.x);
            arc.start_angle_rad = ea - arc.sweep_rad;
        }
        return true;
    }
};

}  // namespace

std::unique_ptr<Rule> make_arc_rule() {
    return std::make_unique<ArcRule>();
}

}  // namespace exemplar::sketch::rules
