// exemplar.noisy_frame: Color Me Noisy for one frame (the library's noisy::synthesize_frame, the
// call `exemplar noisy` makes per frame). Keywords: the noisy option table
// (noisy_option_specs(): noise, level_ratio, patch_size, ...) plus the CLI's --seed, --filter,
// --noise-map, --exemplar-orientation and --frame-orientation, arrays where it reads files.

#include <pybind11/stl.h>

#include <cstdint>
#include <string>
#include <utility>
#include <variant>

#include "arrays.hpp"
#include "bindings.hpp"
#include "exemplar/noisy/noisy.hpp"
#include "keywords.hpp"
#include "run.hpp"

namespace exemplar::python {

namespace {

std::string python_name(std::string_view name) {
    std::string text(name);
    for (char& c : text) {
        if (c == '-') c = '_';
    }
    return text;
}

// An angle field keyword: HxW float32 radians (the CLI wants a float file for the same reason).
Image angles(py::dict& kwargs, const char* name) {
    const py::object value = pop(kwargs, name);
    if (value.is_none()) return {};
    ImageArg arg = image_from_array(value, name, Shape::Grey);
    if (arg.type != SampleType::Float32) {
        throw InputError(std::string(name) +
                         ": an orientation field holds angles in radians and must be float32");
    }
    return std::move(arg.image);
}

py::array noisy_frame_py(const py::object& exemplar, const py::object& reference,
                         py::kwargs kwargs) {
    py::dict args(kwargs);
    noisy::NoisyOptions options;
    if (!args.contains("noise")) {
        // The CLI's rule: the noise level is the user's choice.
        throw InputError("noise: is required (the low-pass strength f in pixels)");
    }
    for (const noisy::NoisyOptionSpec& spec : noisy::noisy_option_specs()) {
        const std::string name = python_name(spec.name);
        const py::object value = pop(args, name.c_str());
        if (!value.is_none()) check(noisy::set_option(options, spec, number(value, name)));
    }
    if (const py::object seed = pop(args, "seed"); !seed.is_none()) {
        const int value = integer(seed, "seed");
        if (value < 0) {
            throw InputError("seed: " + std::to_string(value) + " is invalid (must be >= 0)");
        }
        options.seed = static_cast<std::uint64_t>(value);
    }
    if (const py::object filter = pop(args, "filter"); !filter.is_none()) {
        options.filter = take(noisy::parse_low_pass_filter(text(filter, "filter")));
    }
    check(noisy::validate(options));
    std::int64_t frame_index = 0;
    if (const py::object frame = pop(args, "frame"); !frame.is_none()) {
        frame_index = integer(frame, "frame");
    }
    const py::object progress = pop(args, "progress");
    const py::object cancel = pop(args, "cancel");
    const py::object threads = pop(args, "threads");

    noisy::NoisyFrame input;
    if (const py::object map = pop(args, "noise_map"); !map.is_none()) {
        input.noise_map = image_from_array(map, "noise_map", Shape::Grey).image;
    }
    const Image source_orientation = angles(args, "exemplar_orientation");
    input.orientation = angles(args, "frame_orientation");
    reject_unknown(args, "noisy_frame");
    if (source_orientation.empty() != input.orientation.empty()) {
        throw InputError("exemplar_orientation and frame_orientation: give both, or neither");
    }
    ImageArg source = image_from_array(exemplar, "exemplar", Shape::Colour);
    input.reference = image_from_array(reference, "reference", Shape::Colour).image;
    if (!input.noise_map.empty() && !input.noise_map.same_size(input.reference)) {
        throw InputError("noise_map: is " + std::to_string(input.noise_map.width()) + "x" +
                         std::to_string(input.noise_map.height()) + " but reference is " +
                         std::to_string(input.reference.width()) + "x" +
                         std::to_string(input.reference.height()));
    }

    PythonRun run(threads_keyword(threads), progress, cancel);
    Image image = run([&](const RunContext& context) {
        return noisy::synthesize_frame(source.image, source_orientation, input, options,
                                       frame_index, context);
    });
    return array_from_image(std::move(image), source.type);
}

}  // namespace

void register_noisy(py::module_& module) {
    module.def("_noisy_frame", &noisy_frame_py, py::arg("exemplar"), py::arg("reference"));
    module.def("_noisy_option_specs", [] {
        py::list specs;
        const noisy::NoisyOptions defaults;
        for (const noisy::NoisyOptionSpec& spec : noisy::noisy_option_specs()) {
            const bool integral = !std::holds_alternative<float noisy::NoisyOptions::*>(spec.field);
            py::dict entry;
            entry["name"] = python_name(spec.name);
            entry["doc"] = std::string(spec.doc);
            entry["unit"] = std::string(spec.unit);
            entry["type"] = integral ? "int" : "float";
            entry["min"] = spec.min;
            entry["max"] = spec.max;
            const double value = noisy::get_option(defaults, spec);
            if (integral) {
                entry["default"] = py::int_(static_cast<long long>(value));
            } else {
                entry["default"] = py::float_(std::stod(std::to_string(static_cast<float>(value))));
            }
            specs.append(entry);
        }
        return specs;
    });
}

}  // namespace exemplar::python
