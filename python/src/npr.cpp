// exemplar.npr_frame: one frame of `exemplar npr` (the library's npr::stylize_frame): the frame's
// render buffers as a dict of arrays (what exemplar.render(scene, frame=n) returns, or the files
// of a frame folder), the previous frame's exemplar.NprState, and keywords from the npr option
// table (npr_option_specs(): levels, patch_size, coherence_weight, motion_levels, paper_grain,
// erosion) plus the CLI's --style, --tone, --orientation, --lines, --tone-correction, --paper
// and --seed. Returns (image, state). (The CLI's --bidirectional orders whole blocks of frames
// and is not a per-frame keyword.)

#include "exemplar/npr/npr.hpp"

#include <pybind11/stl.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "arrays.hpp"
#include "bindings.hpp"
#include "keywords.hpp"
#include "run.hpp"

namespace exemplar::python {

namespace {

// A frame's synthesis state, and the prepared pattern it indexes (reused by the next frame when
// it passes the same pattern with the same levels, so a loop prepares the pattern once).
struct NprState {
    npr::FrameState state;
    std::shared_ptr<const npr::Pattern> pattern;
    Image pattern_image;
    // The paper layer's (paper=): its state and prepared paper; null without it
    npr::FrameState paper_state;
    std::shared_ptr<const npr::Pattern> paper;
    Image paper_image;
    int levels = 0;
    int frame = 0;
};

bool same_pixels(const Image& a, const Image& b) {
    return a.width() == b.width() && a.height() == b.height() && a.channels() == b.channels() &&
           std::equal(a.data().begin(), a.data().end(), b.data().begin());
}

// A buffer array: HxW (one channel) or HxWxC.
ImageArg buffer_from_array(const py::handle& value, const std::string& name) {
    const bool grey =
        py::isinstance<py::array>(value) && py::reinterpret_borrow<py::array>(value).ndim() == 2;
    return image_from_array(value, "buffers['" + name + "']", grey ? Shape::Grey : Shape::Colour);
}

py::tuple npr_frame_py(const py::object& pattern, const py::object& buffers, py::kwargs kwargs) {
    py::dict args(kwargs);
    // Options, as the CLI sets them
    npr::NprOptions options;
    if (const py::object style = pop(args, "style"); !style.is_none())
        options.style = take(npr::parse_style(text(style, "style")));
    // The paper layer (the CLI's --paper); its options need it
    const py::object paper_object = pop(args, "paper");
    options.paper = !paper_object.is_none();
    for (const char* name : {"paper_grain", "erosion"})
        if (!options.paper && args.contains(name))
            check(invalid_argument(std::string(name) + ": needs paper="));
    pop_table_options(args, options, npr::npr_option_specs());
    if (const py::object tone = pop(args, "tone"); !tone.is_none())
        options.tone = text(tone, "tone");
    if (const py::object orientation = pop(args, "orientation"); !orientation.is_none())
        options.orientation = text(orientation, "orientation");
    options.lines = pop_bool(args, "lines", options.lines);
    options.tone_correction = pop_bool(args, "tone_correction", options.tone_correction);
    pop_seed(args, options.seed);
    check(npr::validate(options));
    int frame_index = 0;
    if (const py::object frame = pop(args, "frame"); !frame.is_none())
        frame_index = integer(frame, "frame");
    // None: from the tone's dtype (float32 = linear, as render() returns it)
    std::optional<bool> linear_tone;
    if (args.contains("linear_tone") && !args["linear_tone"].is_none())
        linear_tone = pop_bool(args, "linear_tone", false);
    pop(args, "linear_tone");
    const py::object previous_object = pop(args, "previous");
    const RunKeywords run_keywords = pop_run_keywords(args);
    reject_unknown(args, "npr_frame");

    const NprState* previous = nullptr;
    if (!previous_object.is_none()) {
        if (!py::isinstance<NprState>(previous_object))
            throw py::type_error(
                "previous: must be an exemplar.NprState (got " +
                std::string(py::str(py::type::of(previous_object).attr("__name__"))) + ")");
        previous = &previous_object.cast<const NprState&>();
    }
    ImageArg pattern_arg = image_from_array(pattern, "pattern", Shape::Colour);
    std::optional<ImageArg> paper_arg;
    if (options.paper) paper_arg = image_from_array(paper_object, "paper", Shape::Colour);
    if (!py::isinstance<py::dict>(buffers))
        throw py::type_error("buffers: must be a dict of buffer name -> array (got " +
                             std::string(py::str(py::type::of(buffers).attr("__name__"))) + ")");
    // The buffers this frame reads; the others in the dict (render returns all) are ignored
    const auto dict = py::reinterpret_borrow<py::dict>(buffers);
    npr::NprFrame frame;
    for (const npr::BufferNeed& need : npr::needed_buffers(options, previous != nullptr)) {
        if (!dict.contains(need.name)) continue;  // the library names it
        ImageArg arg = buffer_from_array(dict[py::str(need.name)], need.name);
        if (need.role == npr::BufferRole::Tone) {
            frame.tone_linear = linear_tone.value_or(arg.type == SampleType::Float32);
        }
        frame[need.role] = std::move(arg.image);
    }

    // The pattern, prepared unless the previous frame's is the same
    auto next = std::make_unique<NprState>();
    next->levels = options.levels;
    next->frame = frame_index;
    if (previous != nullptr && previous->levels == options.levels &&
        same_pixels(previous->pattern_image, pattern_arg.image)) {
        next->pattern = previous->pattern;
        next->pattern_image = previous->pattern_image;
    } else {
        next->pattern_image = pattern_arg.image;
    }
    if (paper_arg) {
        if (previous != nullptr && previous->paper != nullptr &&
            previous->levels == options.levels &&
            same_pixels(previous->paper_image, paper_arg->image)) {
            next->paper = previous->paper;
            next->paper_image = previous->paper_image;
        } else {
            next->paper_image = paper_arg->image;
        }
    }
    PythonRun run(run_keywords);
    Image image = run([&](const RunContext& context) -> Result<Image> {
        if (next->pattern == nullptr) {
            auto prepared = npr::prepare_pattern(next->pattern_image, options, context);
            if (!prepared.ok()) return prepared.status();
            next->pattern = std::make_shared<const npr::Pattern>(std::move(prepared).value());
        }
        npr::NprPaper paper_layer;
        if (options.paper) {
            if (next->paper == nullptr) {
                auto prepared = npr::prepare_pattern(next->paper_image, options, context);
                if (!prepared.ok())
                    return Status(prepared.status().code(),
                                  "paper: " + prepared.status().message());
                next->paper = std::make_shared<const npr::Pattern>(std::move(prepared).value());
            }
            paper_layer.pattern = next->paper.get();
            if (previous != nullptr && previous->paper != nullptr)
                paper_layer.previous = &previous->paper_state;
        }
        auto styled = npr::stylize_frame(*next->pattern, frame,
                                         previous != nullptr ? &previous->state : nullptr,
                                         frame_index, options, context, paper_layer);
        if (!styled.ok()) return styled.status();
        next->state = std::move(styled->state);
        next->paper_state = std::move(styled->paper_state);
        return std::move(styled->image);
    });
    return py::make_tuple(array_from_image(std::move(image), pattern_arg.type),
                          py::cast(std::move(next)));
}

}  // namespace

void register_npr(py::module_& module) {
    py::class_<NprState, std::unique_ptr<NprState>>(
        module, "NprState",
        "The synthesis state of one npr_frame (the pattern coordinates of every level, and the "
        "prepared pattern): pass it as the next frame's previous=.")
        .def_readonly("frame", &NprState::frame, "The frame number it was made for.")
        .def_readonly("levels", &NprState::levels, "Pyramid levels.")
        .def_property_readonly(
            "coords",
            [](const NprState& s) {
                py::list levels;
                for (Image coords : s.state.coords)
                    levels.append(array_from_image(std::move(coords), SampleType::Float32));
                return levels;
            },
            "Pattern coordinates (x, y) per level, finest first: HxWx2 float32 arrays (level l "
            "at 1/2^l the frame's size).")
        .def("__repr__", [](const NprState& s) {
            const Image& finest = s.state.coords.at(0);
            return "<exemplar.NprState frame " + std::to_string(s.frame) + ", " +
                   std::to_string(finest.width()) + "x" + std::to_string(finest.height()) + ", " +
                   std::to_string(s.levels) + " levels>";
        });
    module.def("_npr_frame", &npr_frame_py, py::arg("pattern"), py::arg("buffers"));
    module.def("_npr_option_specs", [] {
        return table_specs_for_python<npr::NprOptions>(
            npr::npr_option_specs(), [](const npr::NprOptions& o, const npr::NprOptionSpec& spec) {
                return npr::get_option(o, spec);
            });
    });
}

}  // namespace exemplar::python
