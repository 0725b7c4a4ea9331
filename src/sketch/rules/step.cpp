// Step transform snapping (§7.3.5, Fig. 7.9): every accepted copy stores the relative transform
// to the copy it was matched with (its step transform). For a new copy of the same template, the
// transform from each copy D to the candidate is compared with D's step transform by how far
// applying the step to D would move the candidate, relative to the larger of the step (how far it
// carries D) and the candidate's length (ours; the paper gives no measure); a close match places
// the candidate exactly one step further. The likelihood gets the boost 1 − (1 − s)^ln i with i
// the number of copies including the new one (ours, after §7.3.4). Fixes the transformation.

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
        if (!adjustable_copy(input)) return out;
        const int n = context.options->match_samples;
        const double length = polyline_length(samples(input, n));
        for (int j : copies_of(context, input.instance->template_path)) {
            const ResolvedPath& copy = *context.paths[static_cast<std::size_t>(j)];
            if (!copy.step) continue;
            const Affine rel = relative_to(input, copy);
            const Affine correction = compose(*copy.step, rel.inverse());
            Candidate c = moved(input, correction);
            const double moved_by = move_distance(c, input, n);
            // Relative to the step itself: how far the step carries the copy D.
            const std::vector<Vec2> from = copy.match;
            double step_size = 0.0;
            for (Vec2 p : from) step_size = std::max(step_size, distance(p, copy.step->apply(p)));
            // A repeated step is likelier the more copies there are (the boost of §7.3.4, with i
            // counting the new copy).
            const int copies =
                context.paths[static_cast<std::size_t>(input.instance->template_path)]->instances;
            const double likelihood = repeat_boost(
                falloff(moved_by / std::max(step_size, length), context.options->step.tolerance),
                copies + 1);
            if (likelihood < context.options->step.threshold) continue;
            c.instance->relative_to = j;
            c.instance->relative = *copy.step;
            c.fixed.transform = true;
            Relation r{name(),
                       std::string("step:") + std::to_string(j),
                       {copy.stroke},
                       likelihood,
                       "one step on from " + stroke_name(context, j) + " (moved " +
                           fixed1(context.px(moved_by)) + " px)"};
            out.push_back({with_relation(std::move(c), std::move(r)), likelihood});
        }
        keep_best(out, 3);
        return out;
    }
};

}  // namespace

std::unique_ptr<Rule> make_step_rule() {
    return std::make_unique<StepRule>();
}

}  // namespace exemplar::sketch::rules
