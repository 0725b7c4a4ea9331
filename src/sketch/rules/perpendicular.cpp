// Line perpendicularity (§7.3.1): like parallelism with a right angle to the resolved line.

#include <numbers>

#include "rule_util.hpp"
#include "rules.hpp"

namespace exemplar::sketch::rules {

namespace {

class PerpendicularRule final : public Rule {
public:
    const char* name() const override { return "perpendicular"; }
    double threshold(const BeautifyOptions& o) const override { return o.perpendicular.threshold; }
    std::vector<RuleOutput> apply(const Candidate& input,
                                  const RuleContext& context) const override {
        return snap_line_angle(input, context, context.options->perpendicular, std::numbers::pi / 2,
                               name());
    }
};

}  // namespace

std::unique_ptr<Rule> make_perpendicular_rule() {
    return std::make_unique<PerpendicularRule>();
}

}  // namespace exemplar::sketch::rules
