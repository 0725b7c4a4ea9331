#include "exemplar/core/option_table.hpp"

namespace exemplar {

std::string format_option_number(double value) {
    std::string s = std::to_string(value);
    if (s.find('.') != std::string::npos) {
        while (!s.empty() && s.back() == '0') s.pop_back();
        if (!s.empty() && s.back() == '.') s.pop_back();
    }
    return s;
}

Status check_option_value(std::string_view name, double value, double min, double max,
                          bool integral, bool odd) {
    const bool bad = !std::isfinite(value) || value < min || value > max ||
                     (integral && value != std::floor(value)) ||
                     (odd && static_cast<long long>(value) % 2 == 0);
    if (!bad) return Status::ok();
    std::string message(name);
    message.append(": ").append(format_option_number(value)).append(" is invalid (must be ");
    if (odd) message.append("odd, ");
    if (integral && !odd) message.append("an integer, ");
    message.append(format_option_number(min)).append("..").append(format_option_number(max));
    message.append(")");
    return invalid_argument(std::move(message));
}

}  // namespace exemplar
