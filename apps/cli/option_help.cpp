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

bool is_expert_option(const OptionSpec& spec) {
    return spec.name != "patch-size" && spec.name != "style-weight" && spec.name != "seed";
}

std::string quality_flags(Quality quality) {
    std::string text;
    for (const QualityChange& change : quality_changes(quality)) {
        if (!text.empty()) text.append(" ");
        text.append("--").append(change.option).append(" ").append(format_number(change.value));
    }
    return text;
}

std::string expert_options_help() {
    std::string text =
        "\nSearch tuning (experts). --quality sets some of them; explicit flags override it, "
        "whatever their order:\n";
    for (Quality quality : {Quality::Fast, Quality::Best}) {
        text.append("  --quality ").append(to_string(quality)).append(" = ");
        text.append(quality_flags(quality)).append("\n");
    }
    for (const OptionSpec& spec : synthesis_option_specs()) {
        if (!is_expert_option(spec)) continue;
        text.append("  --").append(spec.name).append(is_integer_option(spec) ? " INT" : " FLOAT");
        text.append("\n      ").append(describe(spec)).append("\n");
    }
    return text;
}

}  // namespace exemplar::cli
