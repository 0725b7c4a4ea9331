// Line detection (§7.3.1): the ratio of the distance between the endpoints to the path length,
// as in QuickDraw (Cheema et al. 2012). Likelihood 1 − (1 − ratio)/tolerance. The line keeps the
// path's endpoints (so snapped endpoints stay snapped).

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
        const double likelihood = falloff(1.0 - ratio, params.tolerance);
        if (likelihood < params.threshold) return {};
        Candidate c = as_line(input, input.path.start(), input.path.end());
        Relation r{name(), "line", {}, likelihood,
                   std::string("straightened to a line (chord/length ") + fixed1(100 * ratio) + "%)"};
        return {{with_relation(std::move(c), std::move(r)), likelihood}};
    }
};

}  // namespace

std::unique_ptr<Rule> make_line_rule() { return std::make_unique<LineRule>(); }

}  // namespace exemplar::sketch::rules
