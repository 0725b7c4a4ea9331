// exemplar.noisy_frame: Color Me Noisy for one frame (the library's noisy::synthesize_frame, the
// call `exemplar noisy` makes per frame). Keywords: the noisy option table
// (noisy_option_specs(): noise, level_ratio, patch_size, ...) plus the CLI's --seed, --filter,
// --noise-map, --source-map, --exemplar-orientation and --frame-orientation, arrays where it
// reads files; several media as a list of exemplars.

#include "exemplar/noisy/noisy.hpp"

#include <pybind11/stl.h>

#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "keywords.hpp"
#include "run.hpp"

namespace exemplar::python {

namespace {

py::array noisy_frame_py(const py::object& exemplar, const py::object& reference,
                         py::kwargs kwargs) {
    py::dict args(kwargs);
    noisy::NoisyOptions options;
    if (!args.contains("noise")) {
        // The CLI's rule: the noise level is the user's choice.
        throw InputError("noise: is required (the low-pass strength f in pixels)");
    }
    pop_table_options(args, options, noisy::noisy_option_specs());
    pop_seed(args, options.seed);
    if (const py::object filter = pop(args, "filter"); !filter.is_none()) {
        options.filter = take(noisy::parse_low_pass_filter(text(filter, "filter")));
    }
    check(noisy::validate(options));
    std::int64_t frame_index = 0;
    if (const py::object frame = pop(args, "frame"); !frame.is_none()) {
        frame_index = integer(frame, "frame");
    }
    const RunKeywords run_keywords = pop_run_keywords(args);

    noisy::NoisyFrame input;
    if (const py::object map = pop(args, "noise_map"); !map.is_none()) {
        input.noise_map = image_from_array(map, "noise_map", Shape::Grey).image;
    }
    // Several media (a list) are chosen per pixel by source_map, an HxW array of their indices.
    if (const py::object map = pop(args, "source_map"); !map.is_none()) {
        input.source_map = integer_ids(map, "source_map", "source index", 255);
    }
    const py::object orientations = pop(args, "exemplar_orientation");
    input.orientation = pop_angles(args, "frame_orientation");
    reject_unknown(args, "noisy_frame");
    if (orientations.is_none() != input.orientation.empty()) {
        throw InputError("exemplar_orientation and frame_orientation: give both, or neither");
    }
    const bool several = py::isinstance<py::list>(exemplar) || py::isinstance<py::tuple>(exemplar);
    const py::sequence media = several ? py::reinterpret_borrow<py::sequence>(exemplar)
                                       : py::sequence(py::make_tuple(exemplar));
    if (media.size() == 0) throw InputError("exemplar: the list is empty (need at least one)");
    if (!orientations.is_none() && several &&
        (!(py::isinstance<py::list>(orientations) || py::isinstance<py::tuple>(orientations)) ||
         py::len(orientations) != media.size())) {
        throw InputError("exemplar_orientation: must be a list of " + std::to_string(media.size()) +
                         " fields, one per exemplar");
    }
    std::vector<noisy::NoisySource> sources;
    SampleType type = SampleType::Float32;
    for (std::size_t k = 0; k < media.size(); ++k) {
        const std::string name = several ? "exemplar[" + std::to_string(k) + "]" : "exemplar";
        ImageArg medium = image_from_array(media[k], name, Shape::Colour);
        if (k == 0) type = medium.type;
        Image field;
        if (!orientations.is_none()) {
            field = several ? angles_from(orientations[py::int_(k)],
                                          "exemplar_orientation[" + std::to_string(k) + "]")
                            : angles_from(orientations, "exemplar_orientation");
        }
        sources.push_back({std::move(medium.image), std::move(field)});
    }
    input.reference = image_from_array(reference, "reference", Shape::Colour).image;
    if (!input.noise_map.empty() && !input.noise_map.same_size(input.reference)) {
        throw InputError("noise_map: is " + std::to_string(input.noise_map.width()) + "x" +
                         std::to_string(input.noise_map.height()) + " but reference is " +
                         std::to_string(input.reference.width()) + "x" +
                         std::to_string(input.reference.height()));
    }

    PythonRun run(run_keywords);
    Image image = run([&](const RunContext& context) {
        return noisy::synthesize_frame(sources, input, options, frame_index, context);
    });
    return array_from_image(std::move(image), type);
}

}  // namespace

void register_noisy(py::module_& module) {
    module.def("_noisy_frame", &noisy_frame_py, py::arg("exemplar"), py::arg("reference"));
    module.def("_noisy_option_specs", [] {
        return table_specs_for_python<noisy::NoisyOptions>(
            noisy::noisy_option_specs(),
            [](const noisy::NoisyOptions& o, const noisy::NoisyOptionSpec& spec) {
                return noisy::get_option(o, spec);
            });
    });
}

}  // namespace exemplar::python
