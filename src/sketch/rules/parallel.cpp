// Line parallelism (§7.3.1): the angle between the candidate's chord and a resolved line;
// nearby lines slightly preferred. The candidate is rotated about its fixed endpoint (or its
// chord midpoint) to be exactly parallel. Fixes the direction.

#include "rule_util.hpp"
#include "rules.hpp"

namespace exemplar::sketch::rules {

namespace {

class ParallelRule final : public Rule {
public:
    const char* name() const override { return "parallel"; }
    double threshold(const BeautifyOptions& o) const override { return o.parallel.threshold; }
    std::vector<RuleOutput> apply(const Candidate& input,
                                  const RuleContext& context) const override {
        return snap_line_angle(input, context, context.options->parallel, 0.0, name());
    }
};

}  // namespace

std::unique_ptr<Rule> make_parallel_rule() {
    return std::make_unique<ParallelRule>();
}

}  // namespace exemplar::sketch::rules
