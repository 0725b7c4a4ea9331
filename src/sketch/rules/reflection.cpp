// Reflection (§7.3.5, translation snapping for reflected copies, and reflection axis snapping):
// for a candidate that is a mirrored copy of a template, the similarity from each copy C to the
// candidate gives the axis of reflection (direction half the rotation angle; through the midpoint
// of C's centroid and its image). C is reflected exactly across that axis, across the axes used
// before (boosted by 1 − (1 − s)^ln i for an axis used i times) and across resolved line segments
// when the axis is close to them. Likelihood from how far the candidate moves, relative to its
// length (and capped by `shape_tolerance_px`, ours). Fixes the transformation; the axis is recorded
// for later strokes.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rule_util.hpp"
#include "rules.hpp"

namespace exemplar::sketch::rules {

namespace {

constexpr double kMaxScaleError = 0.15;  // a mirror keeps the size

class ReflectionRule final : public Rule {
public:
    const char* name() const override { return "reflection"; }
    double threshold(const BeautifyOptions& o) const override { return o.reflection.threshold; }

    std::vector<RuleOutput> apply(const Candidate& input,
                                  const RuleContext& context) const override {
        std::vector<RuleOutput> out;
        if (!adjustable_copy(input)) return out;
        const BeautifyOptions& o = *context.options;
        const int n = o.match_samples;
        const double length = polyline_length(samples(input, n));
        for (int j : copies_of(context, input.instance->template_path)) {
            const ResolvedPath& copy = *context.paths[static_cast<std::size_t>(j)];
            const Affine rel = relative_to(input, copy);
            const SimilarityParts parts = decompose_similarity(rel);
            if (!parts.reflected || std::abs(parts.scale - 1.0) > kMaxScaleError) continue;
            const double axis_angle = parts.rotation_rad / 2.0;
            const Vec2 c0 = centroid(copy.match);
            Axis own{(c0 + rel.apply(c0)) / 2.0, {std::cos(axis_angle), std::sin(axis_angle)}, 0};

            // The axes to try: the computed one, and existing axes / lines close to it.
            struct Option {
                Axis axis;
                double snap_score;
                std::string what;
            };
            std::vector<Option> options{{own, 1.0, "its own axis"}};
            auto near_axis = [&](const Axis& a) -> double {
                const double angle = line_angle_between(a.direction, own.direction);
                const Vec2 normal = perpendicular(normalized(a.direction));
                const double offset = context.px(std::abs(dot(own.point - a.point, normal)));
                return std::min(falloff(angle, o.axis_snap_rad), falloff(offset, o.axis_snap_px));
            };
            for (std::size_t k = 0; k < context.axes.size(); ++k) {
                const double s = near_axis(context.axes[k]);
                if (s > 0.0) {
                    options.push_back({context.axes[k], repeat_boost(s, context.axes[k].uses + 1),
                                       std::string("axis ") + std::to_string(k) + " used before"});
                }
            }
            for (std::size_t i = 0; i < context.paths.size(); ++i) {
                const ResolvedPath& p = *context.paths[i];
                if (!p.geometric || p.kind != ShapeKind::Line) continue;
                const Axis line{p.path.start(), normalized(p.path.end() - p.path.start()), 0};
                const double s = near_axis(line);
                if (s > 0.0) {
                    options.push_back(
                        {line, s, "the line of " + stroke_name(context, static_cast<int>(i))});
                }
            }
            for (const Option& option : options) {
                const Affine mirror = Affine::reflection(option.axis.point, option.axis.direction);
                const Affine correction = compose(mirror, rel.inverse());
                Candidate c = moved(input, correction);
                const double moved_by = move_distance(c, input, n);
                const double likelihood =
                    std::min(falloff(moved_by / length, o.reflection.tolerance),
                             falloff(context.px(moved_by), o.shape_tolerance_px)) *
                    option.snap_score;
                if (likelihood < o.reflection.threshold) continue;
                c.instance->relative_to = j;
                c.instance->relative = mirror;
                c.fixed.transform = true;
                c.axis = option.axis;
                const double axis_deg =
                    std::fmod(std::atan2(option.axis.direction.y, option.axis.direction.x) * 180 /
                                      std::numbers::pi +
                                  360.0,
                              180.0);
                Relation r{name(),
                           std::string("reflection:") + std::to_string(j) + ":" + option.what,
                           {copy.stroke},
                           likelihood,
                           "mirror of " + stroke_name(context, j) + " across " + option.what +
                               std::string(" (axis at ") + fixed1(axis_deg) + "°)"};
                out.push_back({with_relation(std::move(c), std::move(r)), likelihood});
            }
        }
        keep_best(out, 3);
        return out;
    }
};

}  // namespace

std::unique_ptr<Rule> make_reflection_rule() {
    return std::make_unique<ReflectionRule>();
}

}  // namespace exemplar::sketch::rules
