// exemplar.render: a built-in or JSON scene path-traced into light-path buffers, returned as
// numpy arrays. The keywords are `exemplar render`'s flags (apps/cli/render_command.cpp); where
// the CLI writes files this returns a dict of arrays, and an animation is rendered one `frame`
// per call.

#include "exemplar/render/render.hpp"

#include <algorithm>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <utility>

#include "arrays.hpp"
#include "bindings.hpp"
#include "exemplar/render/animation.hpp"
#include "exemplar/render/scene.hpp"
#include "keywords.hpp"
#include "run.hpp"

namespace exemplar::python {

namespace {

// The library names RenderOptions fields in its messages; the user knows the keywords.
Status with_keyword_names(const Status& status) {
    static const std::map<std::string, std::string> keywords = {{"samples_per_pixel", "spp"}};
    for (const auto& [field, keyword] : keywords) {
        if (status.message().rfind(field + ":", 0) == 0) {
            return Status(status.code(), keyword + status.message().substr(field.size()));
        }
    }
    return status;
}

// An integer keyword (int or numpy integer; not bool, not a float).
bool pop_integer(py::dict& args, const char* name, long long& out) {
    const py::object value = pop(args, name);
    if (value.is_none()) return false;
    if (py::isinstance<py::bool_>(value) || !PyIndex_Check(value.ptr())) {
        integer(value, name);  // raises the TypeError naming the keyword
    }
    out = py::int_(value).cast<long long>();
    return true;
}

py::dict render_py(const std::string& scene, py::kwargs kwargs) {
    py::dict args(kwargs);
    render::RenderOptions options;
    long long value = 0;
    // Out-of-range values are left to render::validate, which names the range; values beyond
    // int are clamped to its limits first, so they fail there too.
    const auto as_int = [](long long v) {
        return static_cast<int>(std::clamp<long long>(v, std::numeric_limits<int>::min(),
                                                      std::numeric_limits<int>::max()));
    };
    if (pop_integer(args, "width", value)) options.width = as_int(value);
    if (pop_integer(args, "height", value)) options.height = as_int(value);
    if (pop_integer(args, "spp", value)) options.samples_per_pixel = as_int(value);
    if (pop_integer(args, "max_bounces", value)) options.max_bounces = as_int(value);
    if (pop_integer(args, "seed", value)) {
        if (value < 0) throw InputError("seed: " + std::to_string(value) + " is invalid (>= 0)");
        options.seed = static_cast<std::uint64_t>(value);
    }
    long long frame = 0;
    const bool frame_given = pop_integer(args, "frame", frame);
    const RunKeywords run_keywords = pop_run_keywords(args);
    reject_unknown(args, "render");

    // Checks that need no file, then the scene: a file if one exists by that name (or it looks
    // like one), else a built-in.
    check(with_keyword_names(render::validate(options)));
    if (frame_given && (frame < 0 || frame > 1000000)) {
        throw InputError("frame: " + std::to_string(frame) + " is invalid (must be 0..1000000)");
    }
    std::error_code ec;
    const bool is_file =
        std::filesystem::exists(scene, ec) || std::filesystem::path(scene).extension() == ".json";
    Result<render::Animation> loaded =
        is_file ? render::load_animation(scene) : render::builtin_animation(scene);
    if (!loaded.ok() && !is_file) {
        throw StatusError(Status(loaded.status().code(), "scene: " + loaded.status().message()));
    }
    const render::Animation animation = take(std::move(loaded));
    if (animation.is_animated() && !frame_given) {
        throw InputError("frame: required: " + animation.source +
                         " is animated (render it one frame at a time)");
    }

    PythonRun run(run_keywords);
    render::RenderBuffers buffers = run([&](const RunContext& context) {
        Result<render::RenderBuffers> result =
            frame_given ? render::render_frame(animation, static_cast<int>(frame), options, context)
                        : render::render(animation.at(0), options, context);
        if (!result.ok()) return Result<render::RenderBuffers>(with_keyword_names(result.status()));
        return result;
    });
    py::dict out;
    for (const auto& [name, image] : buffers.layers()) {
        // The buffers are ours: move each image into its array instead of copying it.
        out[py::str(name)] =
            array_from_image(std::move(const_cast<Image&>(*image)), SampleType::Float32);
    }
    return out;
}

}  // namespace

void register_render(py::module_& module) {
    module.def("_render", &render_py, py::arg("scene"));
    py::list names;
    for (const std::string& name : render::builtin_scene_names()) names.append(name);
    module.attr("builtin_scenes") = py::tuple(names);
}

}  // namespace exemplar::python
