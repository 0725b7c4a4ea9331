// exemplar.animate: TCIA on frames held as numpy arrays. The keywords are the animate job
// file's keys (apps/cli/animate_job.cpp; `weights` entries as <name>_weight), for one layer;
// where the job names files and frame ranges this takes arrays and returns the stylized frames.

#include "exemplar/animate/animate.hpp"

#include <pybind11/stl.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "exemplar/video/optical_flow.hpp"
#include "keywords.hpp"
#include "run.hpp"

namespace exemplar::python {

namespace {

std::string indexed(const char* name, std::size_t i) {
    return std::string(name) + "[" + std::to_string(i) + "]";
}

// A sequence keyword (not a str, not an array: a list of arrays is wanted).
py::sequence sequence_of(const py::handle& value, const char* name, const char* what) {
    if (!py::isinstance<py::sequence>(value) || py::isinstance<py::str>(value) ||
        py::isinstance<py::array>(value)) {
        throw py::type_error(std::string(name) + ": must be a sequence of " + what + " (got " +
                             std::string(py::str(py::type::of(value).attr("__name__"))) + ")");
    }
    return py::reinterpret_borrow<py::sequence>(value);
}

std::vector<Image> images_from(const py::handle& value, const char* name, Shape shape) {
    std::vector<Image> images;
    const py::sequence items = sequence_of(value, name, "arrays");
    for (std::size_t i = 0; i < items.size(); ++i) {
        images.push_back(image_from_array(items[i], indexed(name, i), shape).image);
    }
    return images;
}

float float_keyword(py::dict& args, const char* name, float value) {
    const py::object given = pop(args, name);
    return given.is_none() ? value : static_cast<float>(number(given, name));
}

// Out-of-range values go on to animate::validate, which names the range.
int int_keyword(py::dict& args, const char* name, int value) {
    const py::object given = pop(args, name);
    return given.is_none() ? value : integer(given, name);
}

// The job file's synthesis keys: the animation's quality preset, usage, then the table's options
// (but `levels`, which is the solver's; the solver sets the engine's levels per call).
SynthesisOptions pop_animate_synthesis(py::dict& args) {
    Quality quality = Quality::Default;
    if (const py::object q = pop(args, "quality"); !q.is_none()) {
        quality = take(parse_quality(text(q, "quality")));
    }
    SynthesisOptions options = animate::animate_synthesis_options(quality);
    if (const py::object usage = pop(args, "usage"); !usage.is_none()) {
        options.usage = take(parse_usage_strategy(text(usage, "usage")));
    }
    for (const OptionSpec& spec : synthesis_option_specs()) {
        const std::string name = python_option_name(spec);
        if (name == "levels") continue;
        const py::object value = pop(args, name.c_str());
        if (!value.is_none()) check(set_option(options, spec, number(value, name)));
    }
    return options;
}

py::list animate_py(const py::object& style_input, const py::object& style_output,
                    const py::object& frames, py::kwargs kwargs) {
    py::dict args(kwargs);
    animate::AnimateOptions options;
    options.synthesis = pop_animate_synthesis(args);
    options.output_weight = float_keyword(args, "output_weight", options.output_weight);
    options.input_weight = float_keyword(args, "input_weight", options.input_weight);
    options.temporal_weight = float_keyword(args, "temporal_weight", options.temporal_weight);
    options.input_derivative_weight =
        float_keyword(args, "input_derivative_weight", options.input_derivative_weight);
    options.keyframe_weight = float_keyword(args, "keyframe_weight", options.keyframe_weight);
    options.line_weight = float_keyword(args, "line_weight", options.line_weight);
    options.line_max_distance_px =
        float_keyword(args, "line_max_distance", options.line_max_distance_px);
    options.occlusion_tolerance_sq_px =
        float_keyword(args, "occlusion_tolerance", options.occlusion_tolerance_sq_px);
    options.levels = int_keyword(args, "levels", options.levels);
    options.sweeps = int_keyword(args, "sweeps", options.sweeps);
    options.backward_em_iterations =
        int_keyword(args, "backward_em_iterations", options.backward_em_iterations);
    options.orientation = pop_bool(args, "orientation", options.orientation);
    options.ribbons = pop_bool(args, "ribbons", options.ribbons);
    if (const py::object preset = pop(args, "flow_preset"); !preset.is_none()) {
        options.flow.preset = take(video::parse_flow_preset(text(preset, "flow_preset")));
    }
    const py::object flows = pop(args, "flows");
    const py::object keyframes = pop(args, "keyframes");
    const py::object lines = pop(args, "lines");
    const RunKeywords run_keywords = pop_run_keywords(args);
    reject_unknown(args, "animate");

    // The inputs, copied once into images the solver's callbacks hand out without Python.
    animate::AnimationInput input;
    ImageArg output_arg = image_from_array(style_output, "style_output", Shape::Colour);
    input.style_input = image_from_array(style_input, "style_input", Shape::Colour).image;
    input.style_output = std::move(output_arg.image);
    const std::vector<Image> frame_images = images_from(frames, "frames", Shape::Colour);
    input.frame_count = static_cast<int>(frame_images.size());
    input.frame = [&frame_images](int t) -> Result<Image> {
        return frame_images[static_cast<std::size_t>(t)];
    };
    std::vector<video::FlowPair> flow_pairs;
    if (!flows.is_none()) {
        const py::sequence pairs = sequence_of(flows, "flows", "(forward, backward) pairs");
        if (pairs.size() + 1 != frame_images.size()) {
            throw InputError("flows: " + std::to_string(pairs.size()) + " pairs for " +
                             std::to_string(frame_images.size()) +
                             " frames (must be one per consecutive pair of frames)");
        }
        for (std::size_t i = 0; i < pairs.size(); ++i) {
            const py::sequence pair = sequence_of(pairs[i], indexed("flows", i).c_str(),
                                                  "two arrays (forward, backward)");
            if (pair.size() != 2) {
                throw py::type_error(indexed("flows", i) + ": must be (forward, backward)");
            }
            flow_pairs.push_back(
                {image_from_array(pair[0], indexed("flows", i) + " forward", Shape::Colour).image,
                 image_from_array(pair[1], indexed("flows", i) + " backward", Shape::Colour)
                     .image});
        }
        input.motion = [&flow_pairs](int t) -> Result<video::FlowPair> {
            return flow_pairs[static_cast<std::size_t>(t)];
        };
    }
    if (!keyframes.is_none()) {
        const py::sequence keys = sequence_of(keyframes, "keyframes", "(frame, image[, mask])");
        for (std::size_t i = 0; i < keys.size(); ++i) {
            const std::string what = indexed("keyframes", i);
            const py::sequence key = sequence_of(keys[i], what.c_str(), "(frame, image[, mask])");
            if (key.size() < 2 || key.size() > 3) {
                throw py::type_error(what + ": must be (frame, image[, mask])");
            }
            animate::Keyframe keyframe;
            keyframe.frame = integer(key[0], what + " frame");
            keyframe.image = image_from_array(key[1], what + " image", Shape::Colour).image;
            if (key.size() == 3) {
                keyframe.mask = image_from_array(key[2], what + " mask", Shape::Grey).image;
            }
            input.keyframes.push_back(std::move(keyframe));
        }
    }
    std::vector<Image> line_images;
    if (!lines.is_none()) {
        const py::sequence pair = sequence_of(lines, "lines", "(style_lines, frame_lines)");
        if (pair.size() != 2) throw py::type_error("lines: must be (style_lines, frame_lines)");
        input.style_lines = image_from_array(pair[0], "lines style", Shape::Grey).image;
        line_images = images_from(pair[1], "lines frames", Shape::Grey);
        if (line_images.size() != frame_images.size()) {
            throw InputError("lines: " + std::to_string(line_images.size()) +
                             " line drawings for " + std::to_string(frame_images.size()) +
                             " frames");
        }
        input.lines = [&line_images](int t) -> Result<Image> {
            return line_images[static_cast<std::size_t>(t)];
        };
    }
    check(animate::validate(input, options));

    PythonRun run(run_keywords);
    animate::AnimationResult result =
        run([&](const RunContext& context) { return animate::animate(input, options, context); });
    // The frames in the style output's dtype.
    py::list out;
    for (Image& frame : result.frames)
        out.append(array_from_image(std::move(frame), output_arg.type));
    return out;
}

}  // namespace

void register_animate(py::module_& module) {
    // The engine's defaults differ for animation (animate_default_synthesis_options): the
    // signature shows these.
    module.def("_animate_defaults", [] {
        const SynthesisOptions defaults = animate::animate_synthesis_options(Quality::Default);
        py::dict out = python_option_values(defaults);
        out["usage"] = std::string(to_string(defaults.usage));
        return out;
    });
    module.def("_animate", &animate_py, py::arg("style_input"), py::arg("style_output"),
               py::arg("frames"));
}

}  // namespace exemplar::python
