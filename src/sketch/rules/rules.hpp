#pragma once
// Factories of the rules, one per file (Fig. 7.3).

#include <memory>

#include "exemplar/sketch/rule.hpp"

namespace exemplar::sketch::rules {

std::unique_ptr<Rule> make_line_rule();
std::unique_ptr<Rule> make_arc_rule();
std::unique_ptr<Rule> make_endpoint_rule();
std::unique_ptr<Rule> make_tangent_rule();
std::unique_ptr<Rule> make_parallel_rule();
std::unique_ptr<Rule> make_perpendicular_rule();
std::unique_ptr<Rule> make_equal_length_rule();
std::unique_ptr<Rule> make_arc_center_rule();
std::unique_ptr<Rule> make_identity_rule();
std::unique_ptr<Rule> make_transform_rule();
std::unique_ptr<Rule> make_reflection_rule();
std::unique_ptr<Rule> make_step_rule();
std::unique_ptr<Rule> make_offset_rule();

}  // namespace exemplar::sketch::rules
