#pragma once
// Keyword arguments of the verbs. The synthesis options come from the library's option table
// (synthesis_option_specs(): `patch_size`, `em_iterations`, ...) plus `quality`, `usage` and
// `vote`, parsed as the CLI parses its flags: the quality preset first, then every option given.

#include <pybind11/pybind11.h>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "errors.hpp"
#include "exemplar/core/image.hpp"
#include "exemplar/core/option_table.hpp"
#include "exemplar/synth/options.hpp"

namespace exemplar::python {

namespace py = pybind11;

/// Removes `name` from `kwargs` and returns its value, or None if it was not given.
py::object pop(py::dict& kwargs, const char* name);

/// A str keyword; TypeError naming it otherwise.
std::string text(const py::handle& value, const std::string& name);

/// An int keyword (int or numpy integer; not bool or float), clamped to int's range so that
/// the library's range check names a value far out of range; TypeError otherwise.
int integer(const py::handle& value, const std::string& name);

/// Pops a bool keyword (True or False; not 0 or 1, TypeError otherwise), or `fallback` when it
/// was not given or is None.
bool pop_bool(py::dict& kwargs, const char* name, bool fallback);

/// A number keyword (int, float or a numpy scalar; not bool or str); TypeError otherwise.
double number(const py::handle& value, const std::string& name);

/// Removes the synthesis keywords (quality, usage, vote and the table's options) from `kwargs`
/// and returns the options they describe; library errors (`patch-size: 4 is invalid (must be
/// odd, 3..31)`) raise InvalidArgumentError.
SynthesisOptions pop_synthesis_options(py::dict& kwargs);

/// Raises TypeError `<function>() got an unexpected keyword argument '<name>'` for the first
/// keyword left in `kwargs`, as Python does for a plain function.
void reject_unknown(const py::dict& kwargs, const char* function);

/// An option's name as a Python keyword (`patch_size`).
std::string python_option_name(const OptionSpec& spec);

/// An option's value as Python shows it: an int, or the shortest float that reads back as the
/// option's float (0.95, not 0.949999988079071).
py::object python_option_value(const OptionSpec& spec, double value);

/// Every option of `options` as Python shows it: {keyword name: value}.
py::dict python_option_values(const SynthesisOptions& options);

/// The option table for Python: one dict per option (name with '_', doc, unit, min, max,
/// default, type "int" or "float"), in the table's order.
py::list option_specs_for_python();

/// An option's name as a Python keyword: '-' as '_' (`patch-size` -> `patch_size`).
std::string python_name(std::string_view name);

/// Pops `seed` (an int >= 0) into `seed` when given.
void pop_seed(py::dict& kwargs, std::uint64_t& seed);

/// Pops an orientation-field keyword: HxW float32 angles in radians (uint8 would hold 0..1);
/// empty when not given.
Image pop_angles(py::dict& kwargs, const char* name);
/// One orientation field as pop_angles takes it; `name` names it in errors.
Image angles_from(const py::handle& value, const std::string& name);

/// One option-table entry for Python, as option_specs_for_python() makes them.
py::dict option_entry(std::string_view name, std::string_view doc, std::string_view unit,
                      bool integer, double min, double max, double value);

/// A module's option table (fluid, noisy: specs with name, doc, unit, min, max and a `field`
/// variant of member pointers) as option_specs_for_python() gives the engine's.
template <class Options, class Spec, class Get>
py::list table_specs_for_python(std::span<const Spec> specs, Get get) {
    py::list list;
    const Options defaults;
    for (const Spec& spec : specs) {
        const bool integer = !std::holds_alternative<float Options::*>(spec.field);
        list.append(option_entry(spec.name, spec.doc, spec.unit, integer, spec.min, spec.max,
                                 get(defaults, spec)));
    }
    return list;
}

/// Pops every option of a module's table from `kwargs` into `options` through `set` (by default
/// the module's set_option; its errors become exceptions).
template <class Options, class Spec, class Set = ModuleSetOption>
void pop_table_options(py::dict& kwargs, Options& options, std::span<const Spec> specs,
                       Set set = {}) {
    for (const Spec& spec : specs) {
        const std::string name = python_name(spec.name);
        const py::object value = pop(kwargs, name.c_str());
        if (!value.is_none()) check(set(options, spec, number(value, name)));
    }
}

}  // namespace exemplar::python
