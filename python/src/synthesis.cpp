// exemplar.stylize, exemplar.apply_nnf and exemplar.stylit: numpy arrays in, the library's
// synthesis, numpy arrays out. The keywords and their defaults are the CLI's (apps/cli
// stylize_command.cpp, apply_nnf_command.cpp, stylit_command.cpp); where the CLI reads a file
// these take an array.

#include <pybind11/stl.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "arrays.hpp"
#include "bindings.hpp"
#include "exemplar/stylit/stylit.hpp"
#include "exemplar/synth/nnf.hpp"
#include "exemplar/synth/synthesize.hpp"
#include "keywords.hpp"
#include "run.hpp"

namespace exemplar::python {

namespace {

/// What stylize and stylit return.
struct StylizeResult {
    py::array image;
    py::array nnf;
    py::array error;
    int nnf_patch_size = 0;
    int vote_size = 0;
    bool vote_seams = false;
    float vote_coherence = 0.0f;
    int guide_channels = 0;
    double explained_variance = 1.0;
    std::vector<int> unlabelled_levels;
};

StylizeResult make_result(SynthesisResult&& result, SampleType type, int guide_channels,
                          double explained_variance) {
    StylizeResult out;
    out.image = array_from_image(std::move(result.image), type);
    out.nnf = array_from_image(nnf_to_image(result.nnf), SampleType::Float32);
    out.error = grey_array_from_image(std::move(result.error));
    out.nnf_patch_size = result.nnf_patch_size;
    out.vote_size = result.vote_size;
    out.vote_seams = result.vote_seams;
    out.vote_coherence = result.vote_coherence;
    out.guide_channels = guide_channels;
    out.explained_variance = explained_variance;
    out.unlabelled_levels = std::move(result.unlabelled_levels);
    return out;
}

std::string indexed(const char* name, std::size_t i) {
    return std::string(name) + "[" + std::to_string(i) + "]";
}

// guides: a sequence of (source, target[, weight[, weight_map]]) tuples or of dicts with the
// job file's keys (source, target, weight, weight_map).
std::vector<GuidePair> guides_from(const py::handle& guides) {
    if (!py::isinstance<py::sequence>(guides) || py::isinstance<py::str>(guides) ||
        py::isinstance<py::array>(guides)) {
        throw py::type_error(
            "guides: must be a sequence of (source, target[, weight]) tuples (got " +
            std::string(py::str(py::type::of(guides).attr("__name__"))) + ")");
    }
    std::vector<GuidePair> pairs;
    const auto sequence = py::reinterpret_borrow<py::sequence>(guides);
    for (std::size_t i = 0; i < sequence.size(); ++i) {
        const std::string what = indexed("guides", i);
        const py::object item = sequence[i];
        py::object source, target, weight = py::none(), weight_map = py::none();
        if (py::isinstance<py::dict>(item)) {
            // A copy (dict.copy(); py::dict(d) shares d): pop() must not change the caller's.
            py::dict entry = item.attr("copy")();
            source = pop(entry, "source");
            target = pop(entry, "target");
            weight = pop(entry, "weight");
            weight_map = pop(entry, "weight_map");
            for (const auto& key : entry) {
                throw py::type_error(what + ": unknown key '" + std::string(py::str(key.first)) +
                                     "' (keys: source, target, weight, weight_map)");
            }
            if (source.is_none() || target.is_none()) {
                throw py::type_error(what + ": needs 'source' and 'target'");
            }
        } else if (py::isinstance<py::tuple>(item) || py::isinstance<py::list>(item)) {
            const auto tuple = py::reinterpret_borrow<py::sequence>(item);
            if (tuple.size() < 2 || tuple.size() > 4) {
                throw py::type_error(what +
                                     ": must be (source, target[, weight[, weight_map]]) "
                                     "(got " +
                                     std::to_string(tuple.size()) + " items)");
            }
            source = tuple[0];
            target = tuple[1];
            if (tuple.size() > 2) weight = tuple[2];
            if (tuple.size() > 3) weight_map = tuple[3];
        } else {
            throw py::type_error(what + ": must be a (source, target[, weight]) tuple or a dict");
        }
        GuidePair pair;
        pair.source = image_from_array(source, what + " source", Shape::Colour).image;
        pair.target = image_from_array(target, what + " target", Shape::Colour).image;
        if (!weight.is_none()) {
            pair.weight = static_cast<float>(number(weight, what + " weight"));
        }
        if (!weight_map.is_none()) {
            pair.target_weight_map =
                image_from_array(weight_map, what + " weight_map", Shape::Grey).image;
        }
        pairs.push_back(std::move(pair));
    }
    return pairs;
}

// An optional image keyword.
Image optional_image(py::dict& kwargs, const char* name, Shape shape) {
    const py::object value = pop(kwargs, name);
    if (value.is_none()) return {};
    return image_from_array(value, name, shape).image;
}

// Label maps of both sides as dense indices, as the CLI reads label files: each distinct value
// (all channels) is one label, the same value on both sides the same label. `values` keeps each
// label's value for messages.
void labels_from(py::dict& kwargs, SynthesisInput& input, std::vector<std::vector<float>>& values) {
    const py::object source = pop(kwargs, "source_labels");
    const py::object target = pop(kwargs, "target_labels");
    if (source.is_none() != target.is_none()) {
        throw InputError(std::string(source.is_none() ? "target_labels" : "source_labels") +
                         ": needs " + (source.is_none() ? "source_labels" : "target_labels") +
                         " too (give both label maps, or neither)");
    }
    if (source.is_none()) return;
    std::map<std::vector<float>, int> ids;
    const auto index = [&](const py::object& object, const char* name) {
        const Image labels = image_from_array(object, name, Shape::Colour).image;
        if (!all_finite(labels)) throw InputError(std::string(name) + ": contains NaN or infinity");
        const int channels = labels.channels();
        Image out(labels.width(), labels.height(), 1);
        std::vector<float> key(static_cast<std::size_t>(channels));
        for (std::size_t i = 0; i < labels.pixel_count(); ++i) {
            const float* p = labels.data().data() + i * static_cast<std::size_t>(channels);
            key.assign(p, p + channels);
            auto [it, added] = ids.emplace(key, static_cast<int>(ids.size()));
            if (added) values.push_back(key);
            out.data()[i] = static_cast<float>(it->second);
        }
        return out;
    };
    const auto label_array = [](const py::object& object) {
        // HxW label maps are common (integer ids); give them their channel axis.
        if (py::isinstance<py::array>(object) && py::array(object).ndim() == 2) {
            return py::object(py::array(object)[py::make_tuple(py::ellipsis(), py::none())]);
        }
        return object;
    };
    input.source_labels = index(label_array(source), "source_labels");
    input.target_labels = index(label_array(target), "target_labels");
    if (input.source_labels.channels() != input.target_labels.channels()) {
        throw InputError("source_labels and target_labels have different channel counts");
    }
}

// "target labels: label 3 does not occur ..." names the label by its value in the array.
Status with_label_values(const Status& status, const std::vector<std::vector<float>>& values) {
    const std::string prefix = "target labels: label ";
    const std::string& message = status.message();
    if (status.is_ok() || message.rfind(prefix, 0) != 0) return status;
    std::size_t end = prefix.size();
    while (end < message.size() && std::isdigit(static_cast<unsigned char>(message[end]))) ++end;
    if (end == prefix.size()) return status;
    const std::size_t id = std::stoul(message.substr(prefix.size(), end - prefix.size()));
    if (id >= values.size()) return status;
    std::string value;
    for (std::size_t c = 0; c < values[id].size(); ++c) {
        char number_text[32];
        std::snprintf(number_text, sizeof number_text, "%g", static_cast<double>(values[id][c]));
        value += (c > 0 ? ", " : "") + std::string(number_text);
    }
    if (values[id].size() > 1) value = "(" + value + ")";
    return Status(status.code(), "target labels: value " + value + message.substr(end));
}

StylizeResult stylize(const py::object& style, const py::object& guides, py::kwargs kwargs) {
    // Keywords, in the CLI's order of checks: options, then inputs.
    py::dict args(kwargs);
    const SynthesisOptions options = pop_synthesis_options(args);
    const RunKeywords run_keywords = pop_run_keywords(args);

    SynthesisInput input;
    ImageArg style_arg = image_from_array(style, "style", Shape::Colour);
    input.style = std::move(style_arg.image);
    input.guides = guides_from(guides);
    if (const py::object weights = pop(args, "style_weights"); !weights.is_none()) {
        for (const py::handle w : weights) {
            input.style_channel_weights.push_back(static_cast<float>(number(w, "style_weights")));
        }
    }
    input.target_mask = optional_image(args, "target_mask", Shape::Grey);
    input.source_mask = optional_image(args, "source_mask", Shape::Grey);
    std::vector<std::vector<float>> label_values;
    labels_from(args, input, label_values);
    input.source_orientation = pop_angles(args, "source_orientation");
    input.target_orientation = pop_angles(args, "target_orientation");
    input.initial_target = optional_image(args, "init", Shape::Colour);
    if (const py::object nnf = pop(args, "init_nnf"); !nnf.is_none()) {
        ImageArg arg = image_from_array(nnf, "init_nnf", Shape::Colour);
        Result<Nnf> field = nnf_from_image(arg.image);
        // nnf_from_image names its argument "nnf"; here it is init_nnf.
        if (!field.ok()) throw InputError("init_" + field.status().message());
        input.initial_nnf = std::move(*field);
    }
    if (const py::object size = pop(args, "size"); !size.is_none()) {
        if (!py::isinstance<py::sequence>(size) || py::isinstance<py::str>(size) ||
            py::len(size) != 2) {
            throw py::type_error("size: must be (width, height)");
        }
        const auto given = py::reinterpret_borrow<py::sequence>(size);
        const std::pair<int, int> pair{integer(given[0], "size"), integer(given[1], "size")};
        if (pair.first <= 0 || pair.second <= 0) {
            throw InputError("size: (" + std::to_string(pair.first) + ", " +
                             std::to_string(pair.second) +
                             ") is invalid (must be (width, height), both > 0)");
        }
        input.target_width = pair.first;
        input.target_height = pair.second;
    }
    reject_unknown(args, "stylize");

    // The CLI's rule: a size must agree with what the guides or the initial target say.
    if (input.target_width > 0) {
        const Image* sized = !input.guides.empty()           ? &input.guides.front().target
                             : !input.initial_target.empty() ? &input.initial_target
                                                             : nullptr;
        if (sized != nullptr &&
            (sized->width() != input.target_width || sized->height() != input.target_height)) {
            throw InputError("size: (" + std::to_string(input.target_width) + ", " +
                             std::to_string(input.target_height) + ") but the " +
                             (input.guides.empty() ? "initial target" : "target guides") + " are " +
                             std::to_string(sized->width()) + "x" +
                             std::to_string(sized->height()));
        }
    }
    check(with_label_values(validate_input(input, options), label_values));

    PythonRun run(run_keywords);
    SynthesisResult result = run(
        [&](const RunContext& context) { return synthesize(std::move(input), options, context); });
    const SynthesisResult::GuideCompression compression = result.guide_compression;
    return make_result(std::move(result), style_arg.type, compression.channels_after,
                       compression.explained_variance);
}

py::array apply_nnf_py(const py::object& nnf, const py::object& source, py::kwargs kwargs) {
    py::dict args(kwargs);
    // The options, checked as the CLI checks them (the table's rules).
    const py::object patch_size = pop(args, "patch_size");
    if (patch_size.is_none()) {
        throw py::type_error(
            "apply_nnf() missing required keyword argument 'patch_size' (the "
            "result's nnf_patch_size)");
    }
    SynthesisOptions options;
    check(set_option(options, *find_option("patch-size"), number(patch_size, "patch_size")));
    // vote_size is stylize's final_vote_size: the same rule under this function's name.
    const py::object vote_size = pop(args, "vote_size");
    const OptionSpec& vote_size_spec = *find_option("final-vote-size");
    if (const Status s = set_option(options, vote_size_spec,
                                    vote_size.is_none() ? 3.0 : number(vote_size, "vote_size"));
        !s.is_ok()) {
        throw InputError("vote_size" + s.message().substr(vote_size_spec.name.size()));
    }
    if (const py::object vote = pop(args, "vote"); !vote.is_none()) {
        options.vote = take(parse_vote_mode(text(vote, "vote")));
    }
    if (const py::object coherence = pop(args, "vote_coherence"); !coherence.is_none()) {
        check(set_option(options, *find_option("vote-coherence"),
                         number(coherence, "vote_coherence")));
    }
    const bool vote_seams = pop_bool(args, "vote_seams", false);
    const py::object threads = pop(args, "threads");
    const int thread_count = threads_keyword(threads);
    reject_unknown(args, "apply_nnf");

    // The field and the source.
    ImageArg nnf_arg = image_from_array(nnf, "nnf", Shape::Colour);
    if (nnf_arg.type != SampleType::Float32) {
        throw InputError(
            "nnf: must be float32 (x, y, angle[, error] per pixel, as "
            "StylizeResult.nnf)");
    }
    Result<Nnf> field = nnf_from_image(nnf_arg.image);
    if (!field.ok()) throw InputError(field.status().message());  // names the nnf
    ImageArg source_arg = image_from_array(source, "source", Shape::Colour);
    if (!all_finite(source_arg.image)) throw InputError("source: contains NaN or infinity");

    Result<Image> result = [&] {
        py::gil_scoped_release release;
        return apply_nnf(*field, source_arg.image, options.patch_size, options.vote, thread_count,
                         options.final_vote_size, options.vote_coherence, vote_seams);
    }();
    return array_from_image(take(std::move(result)), source_arg.type);
}

// A render's buffers: a sequence of arrays (one buffer each, in guide order), or what the CLI
// takes: paths of files, one multi-layer EXR or one folder, whose layers or files `preset` names.
std::vector<LpeBuffer> buffers_from(const py::object& buffers, const char* name,
                                    const LayerPreset& preset) {
    if (py::isinstance<py::str>(buffers)) {
        return take(load_lpe_buffers({buffers.cast<std::string>()}, preset));
    }
    if (!py::isinstance<py::sequence>(buffers)) {
        throw py::type_error(std::string(name) +
                             ": must be a sequence of arrays (or of paths, or one path)");
    }
    const auto sequence = py::reinterpret_borrow<py::sequence>(buffers);
    if (sequence.size() > 0 && py::isinstance<py::str>(sequence[0])) {
        std::vector<std::string> paths;
        for (std::size_t i = 0; i < sequence.size(); ++i) {
            paths.push_back(text(sequence[i], indexed(name, i)));
        }
        return take(load_lpe_buffers(paths, preset));
    }
    std::vector<LpeBuffer> out;
    for (std::size_t i = 0; i < sequence.size(); ++i) {
        const std::string what = indexed(name, i);
        out.push_back({what, what, image_from_array(sequence[i], what, Shape::Colour).image});
    }
    return out;
}

StylizeResult stylit_py(const py::object& exemplar, const py::object& source,
                        const py::object& target, py::kwargs kwargs) {
    py::dict args(kwargs);
    StylitOptions options;
    options.synthesis = pop_synthesis_options(args);
    if (const py::object weight = pop(args, "guidance_weight"); !weight.is_none()) {
        options.guidance_weight = static_cast<float>(number(weight, "guidance_weight"));
    }
    if (const py::object preview = pop(args, "preview"); !preview.is_none()) {
        if (!py::isinstance<py::bool_>(preview)) throw py::type_error("preview: must be a bool");
        options.preview = preview.cast<bool>();
    }
    const py::object preset_name = pop(args, "preset");
    const py::object layers = pop(args, "layers");
    const LayerPreset preset =
        layers.is_none() ? take(find_layer_preset(
                               preset_name.is_none() ? "exemplar" : text(preset_name, "preset")))
                         : take(custom_layer_preset(text(layers, "layers")));
    const RunKeywords run_keywords = pop_run_keywords(args);
    reject_unknown(args, "stylit");

    ImageArg painting = image_from_array(exemplar, "exemplar", Shape::Colour);
    const std::vector<LpeBuffer> source_buffers = buffers_from(source, "source", preset);
    const std::vector<LpeBuffer> target_buffers = buffers_from(target, "target", preset);
    // The CLI's checks before the run: pairing and ranges (stylit_input), then the engine's.
    const SynthesisInput input =
        take(stylit_input(painting.image, source_buffers, target_buffers, options));
    check(validate_input(input, options.synthesis));

    PythonRun run(run_keywords);
    StylitResult result = run([&](const RunContext& context) {
        return stylize_render(painting.image, source_buffers, target_buffers, options, context);
    });
    return make_result(std::move(result.synthesis), painting.type, result.guide_channels,
                       result.explained_variance);
}

}  // namespace

void register_synthesis(py::module_& module) {
    py::class_<StylizeResult>(module, "StylizeResult",
                              "What stylize and stylit return: the image and the correspondences "
                              "that made it.")
        .def_readonly("image", &StylizeResult::image,
                      "The result B': HxWxC, the style's channels and dtype (uint8 style -> "
                      "uint8, rounded as 8-bit PNG files are written).")
        .def_readonly("nnf", &StylizeResult::nnf,
                      "The final nearest-neighbour field, HxWx4 float32: source x, source y, "
                      "angle (radians) and patch error per target pixel (the CLI's --save-nnf).")
        .def_readonly("error", &StylizeResult::error,
                      "Per-pixel patch distance of the final field, HxW float32 (--save-error).")
        .def_readonly("nnf_patch_size", &StylizeResult::nnf_patch_size,
                      "Patch size of the final field (patch_size, or 3 after a final 3x3 pass); "
                      "apply_nnf's patch_size.")
        .def_readonly("vote_size", &StylizeResult::vote_size,
                      "Footprint of the last vote; apply_nnf's vote_size.")
        .def_readonly("vote_seams", &StylizeResult::vote_seams,
                      "Whether the last vote blended seams (final_vote_seams); apply_nnf's "
                      "vote_seams.")
        .def_readonly("vote_coherence", &StylizeResult::vote_coherence,
                      "Coherence variance of the last vote's weights (vote_coherence, 0 = none); "
                      "apply_nnf's vote_coherence.")
        .def_readonly("guide_channels", &StylizeResult::guide_channels,
                      "Guide channels the patch distance compared (fewer with guide_pca or a "
                      "stylit preview).")
        .def_readonly("explained_variance", &StylizeResult::explained_variance,
                      "Fraction of the weighted guide variance kept (1 unless compressed).")
        .def_readonly("unlabelled_levels", &StylizeResult::unlabelled_levels,
                      "With label maps: the pyramid levels (0 = finest) on which the labels were "
                      "not enforced because a segment had no valid source patch there (narrower "
                      "than a patch at that scale, or behind the source mask); empty when they "
                      "held everywhere.")
        .def("__repr__", [](const StylizeResult& r) {
            return "<exemplar.StylizeResult image " +
                   std::string(py::str(py::tuple(r.image.attr("shape")))) + " " +
                   std::string(py::str(r.image.dtype())) + ">";
        });
    // stylize and stylit start from the default quality preset when no quality is given: the
    // signature shows its values.
    module.def("_stylize_defaults",
               [] { return python_option_values(SynthesisOptions::preset(Quality::Default)); });
    module.def("_stylize", &stylize, py::arg("style"), py::arg("guides"));
    module.def("_apply_nnf", &apply_nnf_py, py::arg("nnf"), py::arg("source"));
    module.def("_stylit", &stylit_py, py::arg("exemplar"), py::arg("source"), py::arg("target"));
}

}  // namespace exemplar::python
