// End tangent alignment (§7.3.1): for a snapped endpoint, the angle between the path's tangent
// there and the tangent of the point it is attached to (as undirected lines, so a stroke may
// continue or turn back along the target). The path is rotated about that endpoint to align
// exactly; the other endpoint must be free. Lines and arcs turn about that endpoint; a free-form
// curve only turns its end handle (ours: rotating a long curve would swing its far end).
// Fixes the direction.

#include <cmath>
#include <numbers>

#include "rule_util.hpp"
#include "rules.hpp"

namespace exemplar::sketch::rules {

namespace {

// A free-form curve keeps its endpoints and turns only the handle at that end, so that a long
// stroke does not swing around.
Candidate with_end_handle(const Candidate& input, bool at_start, Vec2 direction) {
    Candidate c = input;
    Cubic& seg = at_start ? c.path.segments.front() : c.path.segments.back();
    if (at_start) {
        double length = distance(seg.c1, seg.p0);
        if (length < 1e-9) length = distance(seg.p3, seg.p0) / 3.0;
        seg.c1 = seg.p0 + direction * length;
    } else {
        double length = distance(seg.p3, seg.c2);
        if (length < 1e-9) length = distance(seg.p3, seg.p0) / 3.0;
        seg.c2 = seg.p3 - direction * length;
    }
    return c;
}

class TangentRule final : public Rule {
public:
    const char* name() const override { return "tangent"; }
    double threshold(const BeautifyOptions& o) const override { return o.tangent.threshold; }

    std::vector<RuleOutput> apply(const Candidate& input,
                                  const RuleContext& context) const override {
        std::vector<RuleOutput> out;
        if (input.fixed.direction || input.kind == ShapeKind::Circle) return out;
        for (bool at_start : {true, false}) {
            const std::optional<Attachment>& a =
                at_start ? input.start_attachment : input.end_attachment;
            const bool other_fixed = at_start ? input.fixed.end : input.fixed.start;
            if (!a || norm(a->tangent) == 0.0) continue;
            if (other_fixed && input.kind != ShapeKind::Curve) continue;
            const Vec2 own = at_start ? start_tangent(input.path) : end_tangent(input.path);
            // Smallest signed rotation making `own` parallel (either way) to the target tangent.
            double rotation = wrap_angle(std::atan2(cross(own, a->tangent), dot(own, a->tangent)));
            if (std::abs(rotation) > std::numbers::pi / 2) {
                rotation = wrap_angle(rotation + std::numbers::pi);
            }
            const double likelihood =
                falloff(std::abs(rotation), context.options->tangent.tolerance);
            if (likelihood < context.options->tangent.threshold) continue;
            const Vec2 center = at_start ? input.path.start() : input.path.end();
            Candidate c =
                input.kind == ShapeKind::Curve
                    ? with_end_handle(input, at_start, Affine::rotation(rotation).apply_vector(own))
                    : moved(input, Affine::rotation(rotation, center));
            c.fixed.direction = true;
            const std::string which = at_start ? "start" : "end";
            const int stroke = stroke_of(context, a->path);
            Relation r{name(),
                       "tangent-" + which,
                       {stroke},
                       likelihood,
                       which + " tangent aligned with " + stroke_name(context, a->path) +
                           std::string(" (was ") + degrees(std::abs(rotation)) + "° off)"};
            out.push_back({with_relation(std::move(c), std::move(r)), likelihood});
        }
        return out;
    }
};

}  // namespace

std::unique_ptr<Rule> make_tangent_rule() {
    return std::make_unique<TangentRule>();
}

}  // namespace exemplar::sketch::rules
