// The rule set of Fig. 7.3 in its fixed evaluation order.

#include <string>

#include "rules.hpp"

namespace exemplar::sketch {

std::vector<std::unique_ptr<Rule>> make_rules() {
    std::vector<std::unique_ptr<Rule>> all;
    all.push_back(rules::make_line_rule());
    all.push_back(rules::make_arc_rule());
    all.push_back(rules::make_endpoint_rule());
    all.push_back(rules::make_tangent_rule());
    all.push_back(rules::make_parallel_rule());
    all.push_back(rules::make_perpendicular_rule());
    all.push_back(rules::make_equal_length_rule());
    all.push_back(rules::make_arc_center_rule());
    all.push_back(rules::make_identity_rule());
    all.push_back(rules::make_transform_rule());
    all.push_back(rules::make_reflection_rule());
    all.push_back(rules::make_step_rule());
    all.push_back(rules::make_offset_rule());
    return all;
}

std::unique_ptr<Rule> make_rule(const std::string& name) {
    for (auto& rule : make_rules()) {
        if (name == rule->name()) return std::move(rule);
    }
    return nullptr;
}

}  // namespace exemplar::sketch
