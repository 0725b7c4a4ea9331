// exemplar.flow: optical flow between two frames (DIS), its backward flow and occlusion mask, as
// `exemplar flow` computes them (apps/cli/flow_command.cpp); arrays where it writes files.

#include <cmath>
#include <string>
#include <utility>

#include "arrays.hpp"
#include "bindings.hpp"
#include "exemplar/video/occlusion.hpp"
#include "exemplar/video/optical_flow.hpp"
#include "keywords.hpp"

namespace exemplar::python {

namespace {

py::dict flow_py(const py::object& from_frame, const py::object& to_frame, py::kwargs kwargs) {
    py::dict args(kwargs);
    // Checks that need no frame.
    video::FlowOptions flow_options;
    if (const py::object preset = pop(args, "preset"); !preset.is_none()) {
        const Result<video::FlowPreset> parsed = video::parse_flow_preset(text(preset, "preset"));
        if (!parsed.ok()) throw InputError("preset: " + parsed.status().message());
        flow_options.preset = *parsed;
    }
    float epsilon = 2.0f;
    if (const py::object given = pop(args, "epsilon"); !given.is_none()) {
        epsilon = static_cast<float>(number(given, "epsilon"));
    }
    if (!(std::isfinite(epsilon) && epsilon > 0.0f)) {
        throw InputError("epsilon: " + std::to_string(epsilon) +
                         " is invalid (must be > 0, in px^2)");
    }
    const bool want_backward = pop_bool(args, "backward", false);
    const bool want_occlusion = pop_bool(args, "occlusion", false);
    reject_unknown(args, "flow");

    const Image from = image_from_array(from_frame, "from_frame", Shape::Colour).image;
    const Image to = image_from_array(to_frame, "to_frame", Shape::Colour).image;
    if (!from.same_size(to)) {
        throw InputError("from_frame is " + std::to_string(from.width()) + "x" +
                         std::to_string(from.height()) + " but to_frame is " +
                         std::to_string(to.width()) + "x" + std::to_string(to.height()));
    }
    Image forward, backward, mask;
    {
        py::gil_scoped_release release;
        forward = take(video::estimate_flow(from, to, flow_options));
        if (want_backward || want_occlusion) {
            backward = take(video::estimate_flow(to, from, flow_options));
        }
        if (want_occlusion) {
            mask = take(video::occlusion_mask(forward, backward, video::OcclusionOptions{epsilon}));
        }
    }
    py::dict out;
    out["forward"] = array_from_image(std::move(forward), SampleType::Float32);
    if (want_backward) out["backward"] = array_from_image(std::move(backward), SampleType::Float32);
    if (want_occlusion) out["occlusion"] = grey_array_from_image(std::move(mask));
    return out;
}

}  // namespace

void register_flow(py::module_& module) {
    module.def("_flow", &flow_py, py::arg("from_frame"), py::arg("to_frame"));
}

}  // namespace exemplar::python
