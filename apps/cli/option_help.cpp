#include "option_help.hpp"

#include <cmath>
#include <cstdio>

namespace exemplar::cli {

std::string format_number(double value) {
    char text[64];
    if (std::isfinite(value) && value == std::floor(value) && std::fabs(value) < 1e17) {
        std::snprintf(text, sizeof text, "%lld", static_cast<long long>(value));
    } else {
        std::snprintf(text, sizeof text, "%g", value);
    }
    return text;
}

std::string format_range(const OptionSpec& spec) {
    std::string text = format_number(spec.min);
    text.append("..").append(format_number(spec.max));
    if (!spec.unit.empty()) text.append(" ").append(spec.unit);
    return text;
}

std::string format_default(const OptionSpec& spec) {
    return format_number(get_option(SynthesisOptions{}, spec));
}

bool is_integer_option(const OptionSpec& spec) {
    return !std::holds_alternative<float SynthesisOptions::*>(spec.field);
}

std::string describe(const OptionSpec& spec) {
    std::string text(spec.doc);
    text.append(" [").append(format_range(spec));
    text.append(", default ").append(format_default(spec)).append("]");
    return text;
}

}  // namespace exemplar::cli
