// exemplar.fluid_frame and exemplar.fluid_simulate: LazyFluids one frame at a time (the library's
// synthesize_fluid_frame, the step `exemplar fluid` takes per frame) and the stable-fluids
// simulator (`exemplar fluid simulate` with the built-in plume scene). The keywords of
// fluid_frame are the fluid option table's (fluid_option_specs(): patch_size, temporal_weight,
// ...) plus the CLI's --seed, --usage and --rotations.

#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "exemplar/fluid/lazy_fluids.hpp"
#include "exemplar/fluid/simulate.hpp"
#include "keywords.hpp"
#include "run.hpp"

namespace exemplar::python {

namespace {

// An optional image keyword (Colour: HxWxC).
std::optional<Image> optional_input(py::dict& kwargs, const char* name) {
    const py::object value = pop(kwargs, name);
    if (value.is_none()) return std::nullopt;
    return image_from_array(value, name, Shape::Colour).image;
}

py::array fluid_frame_py(const py::object& exemplar, const py::object& target_alpha,
                         py::kwargs kwargs) {
    py::dict args(kwargs);
    // Options, as the CLI sets them: defaults, the table's options, seed, rotations, usage.
    fluid::FluidOptions options;
    pop_table_options(args, options, fluid::fluid_option_specs());
    pop_seed(args, options.synthesis.seed);
    options.rotations = pop_bool(args, "rotations", options.rotations);
    if (const py::object usage = pop(args, "usage"); !usage.is_none()) {
        const std::string value = text(usage, "usage");
        if (value != "uniform" && value != "none") {
            throw InputError("usage: '" + value + "' is invalid (must be one of uniform, none)");
        }
        options.uniform_usage = value == "uniform";
    }
    const RunKeywords run_keywords = pop_run_keywords(args);
    check(fluid::validate(options));

    const std::optional<Image> previous_exemplar = optional_input(args, "previous_exemplar");
    const std::optional<Image> previous_output = optional_input(args, "previous_output");
    const std::optional<Image> previous_motion = optional_input(args, "previous_motion");
    const std::optional<Image> motion = optional_input(args, "motion");
    reject_unknown(args, "fluid_frame");

    ImageArg exemplar_arg = image_from_array(exemplar, "exemplar", Shape::Colour);
    const Image alpha = image_from_array(target_alpha, "target_alpha", Shape::Grey).image;

    fluid::FluidFrameInput input;
    input.exemplar = &exemplar_arg.image;
    input.previous_exemplar = previous_exemplar ? &*previous_exemplar : nullptr;
    input.target_alpha = &alpha;
    input.previous_output = previous_output ? &*previous_output : nullptr;
    input.previous_motion = previous_motion ? &*previous_motion : nullptr;
    input.motion = motion ? &*motion : nullptr;

    PythonRun run(run_keywords);
    fluid::FluidFrameResult result = run([&](const RunContext& context) {
        return fluid::synthesize_fluid_frame(input, options, context);
    });
    return array_from_image(std::move(result.rgba), exemplar_arg.type);
}

// The built-in plume scene of `exemplar fluid simulate` (width, height, frames, seed, warm-up);
// returns (alphas, motions): per frame an HxW float32 alpha mask and an HxWx2 float32 motion to
// the next frame.
py::tuple fluid_simulate_py(py::kwargs kwargs) {
    py::dict args(kwargs);
    const auto required = [&](const char* name) {
        const py::object value = pop(args, name);
        if (value.is_none()) {
            throw py::type_error(
                std::string("fluid_simulate() missing required keyword argument '") + name + "'");
        }
        return integer(value, name);
    };
    const int width = required("width");
    const int height = required("height");
    const int frames = required("frames");
    fluid::FluidScene scene = fluid::plume_scene(width, height);
    if (const py::object seed = pop(args, "seed"); !seed.is_none()) {
        const int value = integer(seed, "seed");
        if (value < 0) {
            throw InputError("seed: " + std::to_string(value) + " is invalid (must be >= 0)");
        }
        scene.seed = static_cast<std::uint64_t>(value);
    }
    if (const py::object warmup = pop(args, "warmup_frames"); !warmup.is_none()) {
        scene.warmup_frames = integer(warmup, "warmup_frames");
    }
    const RunKeywords run_keywords = pop_run_keywords(args);
    reject_unknown(args, "fluid_simulate");
    check(fluid::validate(scene));

    std::vector<Image> alphas, motions;
    PythonRun run(run_keywords);
    run([&](const RunContext& context) -> Result<int> {
        const Status status = fluid::simulate(
            scene, frames,
            [&](int, const Image& alpha, const Image& motion) {
                alphas.push_back(alpha);
                motions.push_back(motion);
                return Status::ok();
            },
            context);
        if (!status.is_ok()) return status;
        return frames;
    });
    py::list alpha_list, motion_list;
    for (Image& image : alphas) alpha_list.append(grey_array_from_image(std::move(image)));
    for (Image& image : motions) {
        motion_list.append(array_from_image(std::move(image), SampleType::Float32));
    }
    return py::make_tuple(alpha_list, motion_list);
}

}  // namespace

void register_fluid(py::module_& module) {
    module.def("_fluid_frame", &fluid_frame_py, py::arg("exemplar"), py::arg("target_alpha"));
    module.def("_fluid_simulate", &fluid_simulate_py);
    module.def("_fluid_option_specs", [] {
        return table_specs_for_python<fluid::FluidOptions>(
            fluid::fluid_option_specs(),
            [](const fluid::FluidOptions& o, const fluid::FluidOptionSpec& spec) {
                return fluid::get_option(o, spec);
            });
    });
}

}  // namespace exemplar::python
