// Line length equality (§7.3.1): the ratio of the candidate line's length to a resolved line's,
// with nearby lines slightly preferred. The line is scaled about its fixed endpoint (or its
// midpoint) to the exact length. Fixes the length.

#include <cmath>

#include "rule_util.hpp"
#include "rules.hpp"

namespace exemplar::sketch::rules {

namespace {

class EqualLengthRule final : public Rule {
public:
    const char* name() const override { return "equal-length"; }
    double threshold(const BeautifyOptions& o) const override { return o.equal_length.threshold; }

    std::vector<RuleOutput> apply(const Candidate& input,
                                  const RuleContext& context) const override {
        const RuleParams& params = context.options->equal_length;
        std::vector<RuleOutput> out;
        if (input.kind != ShapeKind::Line || input.fixed.length) return out;
        const std::optional<Vec2> center = pivot(input);
        if (!center) return out;
        const double length = norm(chord(input));
        if (context.px(length) < 4.0) return out;
        std::vector<double> seen;
        for (std::size_t i = 0; i < context.paths.size(); ++i) {
            const ResolvedPath& target = *context.paths[i];
            if (!target.geometric || target.kind != ShapeKind::Line) continue;
            const double target_length = distance(target.path.start(), target.path.end());
            const double ratio_error = std::abs(1.0 - length / target_length);
            if (falloff(ratio_error, params.tolerance) < params.threshold) continue;
            const ClosestPoint near = closest_point(target.simplified, *center);
            const double proximity =
                1.0 - 0.15 * std::min(1.0, context.px(near.distance) /
                                               std::max(1.0, 2 * context.px(length)));
            const double likelihood = falloff(ratio_error, params.tolerance) * proximity;
            if (likelihood < params.threshold) continue;
            bool duplicate = false;
            for (double s : seen) duplicate |= std::abs(s - target_length) < 1e-9;
            if (duplicate) continue;
            seen.push_back(target_length);
            const double scale = target_length / length;
            // Scale along the line only: a similarity about the pivot with no rotation.
            Candidate c = moved(input, Affine::similarity(0.0, scale, *center));
            c.fixed.length = true;
            Relation r{name(),
                       std::string("equal-length:") + std::to_string(i),
                       {target.stroke},
                       likelihood,
                       "as long as " + stroke_name(context, static_cast<int>(i)) + " (was " +
                           fixed1(100 * ratio_error) + "% off)"};
            out.push_back({with_relation(std::move(c), std::move(r)), likelihood});
        }
        keep_best(out, 3);
        return out;
    }
};

}  // namespace

std::unique_ptr<Rule> make_equal_length_rule() {
    return std::make_unique<EqualLengthRule>();
}

}  // namespace exemplar::sketch::rules
