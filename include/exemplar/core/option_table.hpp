#pragma once
/// \file
/// Helpers for a module's table of numeric options (noisy, npr): each table entry names an
/// option (kebab-case), documents it, gives its inclusive range and points at its field in the
/// module's options struct (`std::variant` of `int Options::*`, `float Options::*`, ...). The
/// CLI flags, job-file keys, Python keywords and docs are made from the table; these read and
/// set a field through an entry with the same range check and message everywhere.

#include <cmath>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>

#include "exemplar/core/status.hpp"

namespace exemplar {

/// A number as the tables' ranges and messages write it: "12", "0.5" (no trailing zeros).
std::string format_option_number(double value);

/// InvalidArgument unless `value` is finite and in [min, max] (an integer if `integral`, odd if
/// `odd`): `patch-size: 4 is invalid (must be odd, 3..31)`, `levels: 9 is invalid (must be an
/// integer, 1..6)`, `noise: -1 is invalid (must be 0..256)`.
Status check_option_value(std::string_view name, double value, double min, double max,
                          bool integral, bool odd = false);

/// True for an entry whose field is not a float (int, integer seeds ...).
template <class Options, class Spec>
bool is_integral_option(const Spec& spec) {
    return !std::holds_alternative<float Options::*>(spec.field);
}

/// The value of an entry's field as a double.
template <class Options, class Spec>
double get_table_option(const Options& options, const Spec& spec) {
    return std::visit([&](auto field) { return static_cast<double>(options.*field); }, spec.field);
}

/// Stores `value` (already checked) in an entry's field, converted to the field's type.
template <class Options, class Spec>
void assign_table_option(Options& options, const Spec& spec, double value) {
    std::visit(
        [&](auto field) {
            using T = std::remove_reference_t<decltype(options.*field)>;
            options.*field = static_cast<T>(value);
        },
        spec.field);
}

/// Sets an entry's field after check_option_value against the entry's range.
template <class Options, class Spec>
Status set_table_option(Options& options, const Spec& spec, double value, bool odd = false) {
    EXEMPLAR_RETURN_IF_ERROR(check_option_value(spec.name, value, spec.min, spec.max,
                                                is_integral_option<Options>(spec), odd));
    assign_table_option(options, spec, value);
    return Status::ok();
}

/// The module's own `set_option(options, spec, value)`, found by argument-dependent lookup in the
/// options' namespace (so its own rules, such as odd patch sizes, apply): the setter that the
/// table loops (validation here, the CLI's flags, Python's keywords) use unless given another.
struct ModuleSetOption {
    template <class Options, class Spec>
    Status operator()(Options& options, const Spec& spec, double value) const {
        return set_option(options, spec, value);
    }
};

/// Checks every entry's current value with `set(copy, spec, value)` (by default the module's
/// set_option) on a copy of `options`: the first error.
template <class Options, class Spec, class Set = ModuleSetOption>
Status validate_table_options(const Options& options, std::span<const Spec> specs, Set set = {}) {
    for (const Spec& spec : specs) {
        Options copy = options;
        EXEMPLAR_RETURN_IF_ERROR(set(copy, spec, get_table_option(options, spec)));
    }
    return Status::ok();
}

}  // namespace exemplar
