#include "keywords.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "arrays.hpp"
#include "errors.hpp"

namespace exemplar::python {

namespace {

std::string type_name(const py::handle& value) {
    return py::str(py::type::of(value).attr("__name__"));
}

// The shortest decimal that reads back as `value` (0.95, not 0.949999988079071): the default as
// the table states it, for signatures and docs.
double shortest_float(float value) {
    for (int digits = 1; digits < 9; ++digits) {
        char text[32];
        std::snprintf(text, sizeof text, "%.*g", digits, static_cast<double>(value));
        if (std::strtof(text, nullptr) == value) return std::strtod(text, nullptr);
    }
    return value;
}

}  // namespace

py::object pop(py::dict& kwargs, const char* name) {
    if (!kwargs.contains(name)) return py::none();
    return kwargs.attr("pop")(name);
}

std::string text(const py::handle& value, const std::string& name) {
    if (!py::isinstance<py::str>(value)) {
        throw py::type_error(name + ": must be a str (got " + type_name(value) + ")");
    }
    return value.cast<std::string>();
}

int integer(const py::handle& value, const std::string& name) {
    if (py::isinstance<py::bool_>(value) || !PyIndex_Check(value.ptr())) {
        throw py::type_error(name + ": must be an int (got " + type_name(value) + ")");
    }
    const long long v = py::int_(py::reinterpret_borrow<py::object>(value)).cast<long long>();
    return static_cast<int>(
        std::clamp<long long>(v, std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
}

bool pop_bool(py::dict& kwargs, const char* name, bool fallback) {
    const py::object value = pop(kwargs, name);
    if (value.is_none()) return fallback;
    if (!py::isinstance<py::bool_>(value))
        throw py::type_error(std::string(name) + ": must be a bool");
    return value.cast<bool>();
}

double number(const py::handle& value, const std::string& name) {
    // bool is an int in Python; `patch_size=True` is a mistake, not 1.
    if (py::isinstance<py::bool_>(value) || py::isinstance<py::str>(value) ||
        !PyNumber_Check(value.ptr())) {
        throw py::type_error(name + ": must be a number (got " + type_name(value) + ")");
    }
    return py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
}

SynthesisOptions pop_synthesis_options(py::dict& kwargs) {
    // The quality preset first (default when not given), so that explicit options override it
    // (as on the CLI).
    const py::object quality = pop(kwargs, "quality");
    SynthesisOptions options = SynthesisOptions::preset(
        quality.is_none() ? Quality::Default : take(parse_quality(text(quality, "quality"))));
    for (const OptionSpec& spec : synthesis_option_specs()) {
        const std::string name = python_name(spec.name);
        const py::object value = pop(kwargs, name.c_str());
        if (!value.is_none()) check(set_option(options, spec, number(value, name)));
    }
    if (const py::object usage = pop(kwargs, "usage"); !usage.is_none()) {
        options.usage = take(parse_usage_strategy(text(usage, "usage")));
    }
    if (const py::object vote = pop(kwargs, "vote"); !vote.is_none()) {
        options.vote = take(parse_vote_mode(text(vote, "vote")));
    }
    return options;
}

void reject_unknown(const py::dict& kwargs, const char* function) {
    for (const auto& item : kwargs) {
        throw py::type_error(std::string(function) + "() got an unexpected keyword argument '" +
                             std::string(py::str(item.first)) + "'");
    }
}

std::string python_option_name(const OptionSpec& spec) {
    return python_name(spec.name);
}

py::dict python_option_values(const SynthesisOptions& options) {
    py::dict out;
    for (const OptionSpec& spec : synthesis_option_specs()) {
        out[py::str(python_option_name(spec))] =
            python_option_value(spec, get_option(options, spec));
    }
    return out;
}

py::object python_option_value(const OptionSpec& spec, double value) {
    if (!std::holds_alternative<float SynthesisOptions::*>(spec.field)) {
        return py::int_(static_cast<long long>(value));
    }
    return py::float_(shortest_float(static_cast<float>(value)));
}

std::string python_name(std::string_view name) {
    std::string text(name);
    std::replace(text.begin(), text.end(), '-', '_');
    return text;
}

void pop_seed(py::dict& kwargs, std::uint64_t& seed) {
    const py::object value = pop(kwargs, "seed");
    if (value.is_none()) return;
    const int given = integer(value, "seed");
    if (given < 0)
        throw InputError("seed: " + std::to_string(given) + " is invalid (must be >= 0)");
    seed = static_cast<std::uint64_t>(given);
}

Image pop_angles(py::dict& kwargs, const char* name) {
    const py::object value = pop(kwargs, name);
    if (value.is_none()) return {};
    return angles_from(value, name);
}

Image angles_from(const py::handle& value, const std::string& name) {
    ImageArg arg = image_from_array(value, name, Shape::Grey);
    if (arg.type != SampleType::Float32) {
        throw InputError(name +
                         ": an orientation field holds angles in radians and must be float32");
    }
    return std::move(arg.image);
}

py::dict option_entry(std::string_view name, std::string_view doc, std::string_view unit,
                      bool integer, double min, double max, double value) {
    py::dict entry;
    entry["name"] = python_name(name);
    entry["doc"] = std::string(doc);
    entry["unit"] = std::string(unit);
    entry["type"] = integer ? "int" : "float";
    if (integer) {
        entry["min"] = static_cast<long long>(min);
        entry["max"] = static_cast<long long>(max);
        entry["default"] = py::int_(static_cast<long long>(value));
    } else {
        entry["min"] = min;
        entry["max"] = max;
        entry["default"] = py::float_(shortest_float(static_cast<float>(value)));
    }
    return entry;
}

py::list option_specs_for_python() {
    return table_specs_for_python<SynthesisOptions>(
        synthesis_option_specs(), [](const SynthesisOptions& options, const OptionSpec& spec) {
            return get_option(options, spec);
        });
}

}  // namespace exemplar::python
