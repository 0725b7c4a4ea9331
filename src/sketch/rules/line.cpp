// Line detection (§7.3.1): the ratio of the distance between the endpoints to the path length,
// as in QuickDraw (Cheema et al. 2012). Likelihood 1 − (1 − ratio)/tolerance. The line keeps the
// path's endpoints (so snapped endpoints stay snapped). The likelihood is also capped by how far
// the stroke moves (Fréchet distance against `shape_tolerance_px`): long, gently curved strokes
// have ratios near 1 but are not lines.

#include <algorithm>

#include "rule_util.hpp"
#include "rules.hpp"

namespace exemplar::sketch::rules {

namespace {

class LineRule final : public Rule {
public:
    const char* name() const override { return "line"; }
    double threshold(const BeautifyOptions& o) const override { return o.line.threshold; }

    std::vector<RuleOutput> apply(const Candidate& input,
                                  const RuleContext& context) const override {
        const RuleParams& params = context.options->line;
        if (input.kind != ShapeKind::Curve || input.fixed.shape || input.path.closed) return {};
        if (context.px(distance(input.path.start(), input.path.end())) < 2.0) return {};
        const double ratio = straightness(input.path);
        double likelihood = falloff(1.0 - ratio, params.tolerance);
        if (likelihood < params.threshold) return {};
        Candidate c = as_line(input, input.path.start(), input.path.end());
        const int n = context.options->match_samples;
        const double moved_px = context.px(discrete_frechet(samples(input, n), samples(c, n)));
        likelihood = std::min(likelihood, falloff(moved_px, context.options->shape_tolerance_px));
        if (likelihood < params.threshold) return {};
        Relation r{
            name(),
            "line",
            {},
            likelihood,
            std::string("straightened to a line (chord/length ") + fixed1(100 * ratio) + "%)"};
        return {{with_relation(std::move(c), std::move(r)), likelihood}};
    }
};

}  // namespace

std::unique_ptr<Rule> make_line_rule() {
    return std::make_unique<LineRule>();
}

}  // namespace exemplar::sketch::rules
