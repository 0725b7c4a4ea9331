#pragma once
// Keyword arguments of the verbs. The synthesis options come from the library's option table
// (synthesis_option_specs(): `patch_size`, `em_iterations`, ...) plus `quality`, `usage` and
// `vote`, parsed as the CLI parses its flags: the quality preset first, then every option given.

#include <pybind11/pybind11.h>

#include <string>

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

/// The option table for Python: one dict per option (name with '_', doc, unit, min, max,
/// default, type "int" or "float"), in the table's order.
py::list option_specs_for_python();

}  // namespace exemplar::python
