// Step transform snapping (§7.3.5, Fig. 7.9): every accepted copy stores the relative transform
// to the copy it was matched with (its step transform). For a new copy of the same template, the
// transform from each copy D to the candidate is compared with D's step transform by how far
// applying the step to D would move the candidate (relative to its length); a close match places
// the candidate exactly one step further; the likelihood is also capped by the absolute move
// (`shape_tolerance_px`, ours). Fixes the transformation.

#include <algorithm>

#include "rule_util.hpp"
#include "rules.hpp"

namespace exemplar::sketch::rules {

namespace {

class StepRule final : public Rule {
public:
    const char* name() const override { return "step"; }
    double threshold(const BeautifyOptions& o) const override { return o.step.threshold; }

    std::vector<RuleOutput> apply(const Candidate& input,
                                  const RuleContext& context) const override {
        std::vector<RuleOutput> out;
        if (!input.instance || input.fixed.transform || input.fixed.start || input.fixed.end) {
            return out;
        }
        const int n = context.options->match_samples;
        const double length = polyline_length(samples(input, n));
        for (int j : copies_of(context, input.instance->template_path)) {
            const ResolvedPath& copy = *context.paths[static_cast<std::size_t>(j)];
            if (!copy.step) continue;
            const Affine rel = compose(input.instance->from_template, copy.from_template.inverse());
            const Affine correction = compose(*copy.step, rel.inverse());
            Candidate c = moved(input, correction);
            const double moved_by = move_distance(c, input, n);
            const double likelihood =
                std::min(falloff(moved_by / length, context.options->step.tolerance),
                         falloff(context.px(moved_by), context.options->shape_tolerance_px));
            if (likelihood < context.options->step.threshold) continue;
            c.instance->relative_to = j;
            c.instance->relative = *copy.step;
            c.fixed.transform = true;
            Relation r{name(), std::string("step:") + std::to_string(j), {copy.stroke}, likelihood,
                       std::string("one step on from stroke ") + std::to_string(copy.stroke) + " (moved " +
                           fixed1(context.px(moved_by)) + " px)"};
            out.push_back({with_relation(std::move(c), std::move(r)), likelihood});
        }
        keep_best(out, 3);
        return out;
    }
};

}  // namespace

std::unique_ptr<Rule> make_step_rule() { return std::make_unique<StepRule>(); }

}  // namespace exemplar::sketch::rules
