#include "animate_job.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "json_file.hpp"

namespace exemplar::cli {

namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

}  // namespace

Result<AnimateJob> load_animate_job(const std::string& path) {
    auto parsed = read_json_object(path);
    if (!parsed.ok()) return parsed.status();
    const json& doc = *parsed;
    const fs::path base = fs::path(path).parent_path();
    auto resolve = [&](const std::string& p) {
        if (p.empty() || fs::path(p).is_absolute()) return p;
        return (base / p).lexically_normal().string();
    };
    auto string_of = [&](const json& v, const std::string& key, std::string& out) -> Status {
        if (!v.is_string()) return type_error(path, key, "a string");
        out = v.get<std::string>();
        return Status::ok();
    };
    auto path_of = [&](const json& v, const std::string& key, std::string& out) -> Status {
        if (!v.is_string()) return type_error(path, key, "a string (a file path)");
        out = resolve(v.get<std::string>());
        return Status::ok();
    };
    // An object whose members are paths, e.g. {"input": ..., "output": ...}.
    using Members = std::vector<std::pair<std::string, std::string*>>;
    auto paths_of = [&](const json& v, const std::string& key, const Members& members) -> Status {
        std::string names;
        for (const auto& m : members) names += (names.empty() ? "" : ", ") + m.first;
        if (!v.is_object()) return type_error(path, key, "an object with paths");
        for (const auto& [member_raw, mv] : v.items()) {
            const std::string member = canonical_key(member_raw);
            auto it = std::find_if(members.begin(), members.end(),
                                   [&](const auto& m) { return m.first == member; });
            if (it == members.end()) {
                return invalid_argument(path + ": unknown key '" + key + "." + member_raw + "' (" +
                                        key + " takes " + names + ")");
            }
            EXEMPLAR_RETURN_IF_ERROR(path_of(mv, key + "." + member_raw, *it->second));
        }
        return Status::ok();
    };
    auto number_of = [&](const json& v, const std::string& key, float& out) -> Status {
        if (!v.is_number()) return type_error(path, key, "a number");
        out = v.get<float>();
        return Status::ok();
    };
    auto int_of = [&](const json& v, const std::string& key, int& out) -> Status {
        if (!v.is_number_integer()) return type_error(path, key, "an integer");
        out = v.get<int>();
        return Status::ok();
    };

    // Keys describing inputs: the job's own and each layer's.
    auto parse_source = [&](const std::string& key, const std::string& raw_key, const json& value,
                            AnimateSourceSpec& src, bool& handled) -> Status {
        handled = true;
        if (key == "frames") return path_of(value, raw_key, src.frames);
        if (key == "coverage") return path_of(value, raw_key, src.coverage);
        if (key == "style") {
            EXEMPLAR_RETURN_IF_ERROR(paths_of(
                value, raw_key, {{"input", &src.style_input}, {"output", &src.style_output}}));
            return Status::ok();
        }
        if (key == "lines") {
            EXEMPLAR_RETURN_IF_ERROR(
                paths_of(value, raw_key, {{"style", &src.style_lines}, {"frames", &src.lines}}));
            if (src.style_lines.empty() || src.lines.empty()) {
                return invalid_argument(path + ": key '" + raw_key +
                                        "' needs both \"style\" and \"frames\"");
            }
            return Status::ok();
        }
        if (key == "flows") {
            src.flows_given = true;
            if (value.is_string() && value.get<std::string>() == "estimate") {
                src.estimate_flow = true;
                return Status::ok();
            }
            if (!value.is_object()) {
                return type_error(path, raw_key,
                                  "\"estimate\" or {\"forward\": pattern, \"backward\": "
                                  "pattern, \"layer\": name}");
            }
            src.estimate_flow = false;
            for (const auto& [fk_raw, fv] : value.items()) {
                const std::string fk = canonical_key(fk_raw);
                const std::string name = raw_key + "." + fk_raw;
                if (fk == "forward") {
                    EXEMPLAR_RETURN_IF_ERROR(path_of(fv, name, src.forward_flow));
                } else if (fk == "backward") {
                    EXEMPLAR_RETURN_IF_ERROR(path_of(fv, name, src.backward_flow));
                } else if (fk == "layer") {
                    EXEMPLAR_RETURN_IF_ERROR(string_of(fv, name, src.forward_flow_layer));
                    src.backward_flow_layer = src.forward_flow_layer;
                } else if (fk == "forward-layer") {
                    EXEMPLAR_RETURN_IF_ERROR(string_of(fv, name, src.forward_flow_layer));
                } else if (fk == "backward-layer") {
                    EXEMPLAR_RETURN_IF_ERROR(string_of(fv, name, src.backward_flow_layer));
                } else {
                    return invalid_argument(path + ": unknown key '" + name +
                                            "' (flows take forward, backward, layer, "
                                            "forward_layer, backward_layer)");
                }
            }
            if (src.forward_flow.empty() || src.backward_flow.empty()) {
                return invalid_argument(path + ": key '" + raw_key +
                                        "' needs both \"forward\" and \"backward\" patterns");
            }
            return Status::ok();
        }
        if (key == "keyframes") {
            if (!value.is_array()) return type_error(path, raw_key, "an array of keyframes");
            for (const json& k : value) {
                if (!k.is_object() || !k.contains("frame") || !k.contains("image")) {
                    return type_error(path, raw_key,
                                      "an array of {\"frame\": n, \"image\": path, \"mask\": "
                                      "path} objects");
                }
                AnimateKeySpec spec;
                for (const auto& [kk_raw, kv] : k.items()) {
                    const std::string kk = canonical_key(kk_raw);
                    if (kk == "frame") {
                        EXEMPLAR_RETURN_IF_ERROR(int_of(kv, "keyframes.frame", spec.frame));
                    } else if (kk == "image") {
                        EXEMPLAR_RETURN_IF_ERROR(path_of(kv, "keyframes.image", spec.image));
                    } else if (kk == "mask") {
                        EXEMPLAR_RETURN_IF_ERROR(path_of(kv, "keyframes.mask", spec.mask));
                    } else {
                        return invalid_argument(path + ": unknown key 'keyframes." + kk_raw +
                                                "' (keyframes take frame, image, mask)");
                    }
                }
                src.keyframes.push_back(std::move(spec));
            }
            return Status::ok();
        }
        handled = false;
        return Status::ok();
    };

    AnimateJob job;
    animate::AnimateOptions& o = job.options;
    float fps = static_cast<float>(job.fps);
    const std::map<std::string, int*> integers = {
        {"first", &job.first}, {"last", &job.last},
        {"chunk", &job.chunk}, {"levels", &o.levels},
        {"sweeps", &o.sweeps}, {"backward-em-iterations", &o.backward_em_iterations}};
    const std::map<std::string, float*> numbers = {
        {"fps", &fps},
        {"line-max-distance", &o.line_max_distance_px},
        {"occlusion-tolerance", &o.occlusion_tolerance_sq_px}};
    const std::map<std::string, std::string*> files = {{"output", &job.output}, {"mp4", &job.mp4}};
    for (const auto& [raw_key, value] : doc.items()) {
        const std::string key = canonical_key(raw_key);
        bool handled = false;
        if (key != "coverage") {
            EXEMPLAR_RETURN_IF_ERROR(parse_source(key, raw_key, value, job.base, handled));
        }
        if (handled) continue;
        if (auto i = integers.find(key); i != integers.end()) {
            EXEMPLAR_RETURN_IF_ERROR(int_of(value, raw_key, *i->second));
        } else if (auto n = numbers.find(key); n != numbers.end()) {
            EXEMPLAR_RETURN_IF_ERROR(number_of(value, raw_key, *n->second));
        } else if (auto f = files.find(key); f != files.end()) {
            EXEMPLAR_RETURN_IF_ERROR(path_of(value, raw_key, *f->second));
        } else if (key == "layers") {
            if (!value.is_array() || value.empty()) {
                return type_error(path, raw_key, "a non-empty array of layer objects");
            }
            for (const json& l : value) {
                if (!l.is_object()) return type_error(path, raw_key, "an array of objects");
                AnimateSourceSpec layer;
                for (const auto& [lk_raw, lv] : l.items()) {
                    bool ok = false;
                    const std::string name = "layers." + lk_raw;
                    EXEMPLAR_RETURN_IF_ERROR(
                        parse_source(canonical_key(lk_raw), name, lv, layer, ok));
                    if (!ok) {
                        return invalid_argument(path + ": unknown key '" + name +
                                                "' (layers take frames, coverage, flows, style, "
                                                "keyframes, lines)");
                    }
                }
                job.layers.push_back(std::move(layer));
            }
        } else if (key == "weights") {
            if (!value.is_object()) return type_error(path, raw_key, "an object of numbers");
            for (const auto& [wk_raw, wv] : value.items()) {
                const std::string wk = canonical_key(wk_raw);
                const std::string name = raw_key + "." + wk_raw;
                float* field = wk == "output"             ? &o.output_weight
                               : wk == "input"            ? &o.input_weight
                               : wk == "temporal"         ? &o.temporal_weight
                               : wk == "input-derivative" ? &o.input_derivative_weight
                               : wk == "keyframe"         ? &o.keyframe_weight
                               : wk == "lines"            ? &o.line_weight
                                                          : nullptr;
                if (field == nullptr) {
                    return invalid_argument(path + ": unknown key '" + name +
                                            "' (weights are output, input, temporal, "
                                            "input-derivative, keyframe, lines)");
                }
                EXEMPLAR_RETURN_IF_ERROR(number_of(wv, name, *field));
            }
        } else if (key == "orientation") {
            if (!value.is_boolean()) return type_error(path, raw_key, "true or false");
            o.orientation = value.get<bool>();
        } else if (key == "ribbons") {
            if (!value.is_boolean()) return type_error(path, raw_key, "true or false");
            o.ribbons = value.get<bool>();
        } else if (key == "flow-preset") {
            std::string name;
            EXEMPLAR_RETURN_IF_ERROR(string_of(value, raw_key, name));
            auto preset = video::parse_flow_preset(name);
            if (!preset.ok()) return invalid_argument(path + ": " + preset.status().message());
            o.flow.preset = *preset;
        } else if (key == "usage") {
            EXEMPLAR_RETURN_IF_ERROR(string_of(value, raw_key, job.usage));
        } else if (key == "quality") {
            EXEMPLAR_RETURN_IF_ERROR(string_of(value, raw_key, job.quality));
        } else if (const OptionSpec* spec = find_option(key)) {
            if (!value.is_number()) return type_error(path, raw_key, "a number");
            job.numeric[std::string(spec->name)] = value.get<double>();
        } else {
            return invalid_argument(path + ": unknown key '" + raw_key + "'");
        }
    }
    if (!job.layers.empty()) {
        if (!job.base.keyframes.empty()) {
            return invalid_argument(path +
                                    ": key 'keyframes' belongs to a layer when layers are given");
        }
        // A layer inherits the inputs it does not name.
        for (std::size_t i = 0; i < job.layers.size(); ++i) {
            AnimateSourceSpec& l = job.layers[i];
            const AnimateSourceSpec& b = job.base;
            if (l.frames.empty()) l.frames = b.frames;
            if (!l.flows_given) {
                l.estimate_flow = b.estimate_flow;
                l.forward_flow = b.forward_flow;
                l.backward_flow = b.backward_flow;
                l.forward_flow_layer = b.forward_flow_layer;
                l.backward_flow_layer = b.backward_flow_layer;
            }
            if (l.style_input.empty()) l.style_input = b.style_input;
            if (l.style_output.empty()) l.style_output = b.style_output;
            if (l.lines.empty()) {
                l.lines = b.lines;
                l.style_lines = b.style_lines;
            }
            const std::string name = path + ": layer " + std::to_string(i);
            if (l.frames.empty()) return invalid_argument(name + ": key 'frames' is missing");
            if (l.style_input.empty() || l.style_output.empty()) {
                return invalid_argument(name + ": key 'style' needs \"input\" and \"output\"");
            }
            if (i > 0 && l.coverage.empty()) {
                return invalid_argument(name +
                                        ": key 'coverage' is missing (every layer but the "
                                        "backmost needs one)");
            }
        }
    } else {
        if (job.base.frames.empty()) return invalid_argument(path + ": key 'frames' is missing");
        if (job.base.style_input.empty() || job.base.style_output.empty()) {
            return invalid_argument(path + ": key 'style' needs \"input\" and \"output\"");
        }
    }
    job.fps = fps;
    if (!(job.fps > 0.0)) return invalid_argument(path + ": key 'fps' must be > 0");
    if (job.chunk < 0 || job.chunk == 1) {
        return invalid_argument(path + ": key 'chunk' must be 0 (whole range) or >= 2");
    }
    EXEMPLAR_RETURN_IF_ERROR(build_synthesis_options(job, path));
    return job;
}

Status build_synthesis_options(AnimateJob& job, const std::string& where) {
    Quality quality = Quality::Default;
    if (!job.quality.empty()) {
        auto parsed = parse_quality(job.quality);
        if (!parsed.ok()) return invalid_argument(where + ": " + parsed.status().message());
        quality = *parsed;
    }
    SynthesisOptions& s = job.options.synthesis;
    s = animate::animate_synthesis_options(quality);
    if (!job.usage.empty()) {
        auto usage = parse_usage_strategy(job.usage);
        if (!usage.ok()) return invalid_argument(where + ": " + usage.status().message());
        s.usage = *usage;
    }
    for (const auto& [name, value] : job.numeric) {
        const Status st = set_option(s, *find_option(name), value);
        if (!st.is_ok()) return invalid_argument(where + ": " + st.message());
    }
    return Status::ok();
}

}  // namespace exemplar::cli
