#include "animate_job.hpp"

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "json_file.hpp"

namespace exemplar::cli {

namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

Status type_error(const std::string& file, const std::string& key, const char* expected) {
    return invalid_argument(file + ": key '" + key + "' must be " + expected);
}

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

    AnimateJob job;
    animate::AnimateOptions& o = job.options;
    for (const auto& [raw_key, value] : doc.items()) {
        const std::string key = canonical_key(raw_key);
        if (key == "frames") {
            EXEMPLAR_RETURN_IF_ERROR(path_of(value, raw_key, job.frames));
        } else if (key == "first") {
            EXEMPLAR_RETURN_IF_ERROR(int_of(value, raw_key, job.first));
        } else if (key == "last") {
            EXEMPLAR_RETURN_IF_ERROR(int_of(value, raw_key, job.last));
        } else if (key == "output") {
            EXEMPLAR_RETURN_IF_ERROR(path_of(value, raw_key, job.output));
        } else if (key == "mp4") {
            EXEMPLAR_RETURN_IF_ERROR(path_of(value, raw_key, job.mp4));
        } else if (key == "fps") {
            float fps = 0.0f;
            EXEMPLAR_RETURN_IF_ERROR(number_of(value, raw_key, fps));
            job.fps = fps;
        } else if (key == "chunk") {
            EXEMPLAR_RETURN_IF_ERROR(int_of(value, raw_key, job.chunk));
        } else if (key == "flows") {
            if (value.is_string() && value.get<std::string>() == "estimate") {
                job.estimate_flow = true;
                continue;
            }
            if (!value.is_object()) {
                return type_error(path, raw_key,
                                  "\"estimate\" or {\"forward\": pattern, \"backward\": "
                                  "pattern, \"layer\": name}");
            }
            job.estimate_flow = false;
            for (const auto& [fk_raw, fv] : value.items()) {
                const std::string fk = canonical_key(fk_raw);
                const std::string name = raw_key + "." + fk_raw;
                if (fk == "forward") {
                    EXEMPLAR_RETURN_IF_ERROR(path_of(fv, name, job.forward_flow));
                } else if (fk == "backward") {
                    EXEMPLAR_RETURN_IF_ERROR(path_of(fv, name, job.backward_flow));
                } else if (fk == "layer") {
                    EXEMPLAR_RETURN_IF_ERROR(string_of(fv, name, job.flow_layer));
                } else {
                    return invalid_argument(path + ": unknown key '" + name +
                                            "' (flows take forward, backward, layer)");
                }
            }
            if (job.forward_flow.empty() || job.backward_flow.empty()) {
                return invalid_argument(path + ": key '" + raw_key +
                                        "' needs both \"forward\" and \"backward\" patterns");
            }
        } else if (key == "style") {
            EXEMPLAR_RETURN_IF_ERROR(paths_of(
                value, raw_key, {{"input", &job.style_input}, {"output", &job.style_output}}));
        } else if (key == "keyframes") {
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
                job.keyframes.push_back(std::move(spec));
            }
        } else if (key == "lines") {
            EXEMPLAR_RETURN_IF_ERROR(
                paths_of(value, raw_key, {{"style", &job.style_lines}, {"frames", &job.lines}}));
            if (job.style_lines.empty() || job.lines.empty()) {
                return invalid_argument(path + ": key '" + raw_key +
                                        "' needs both \"style\" and \"frames\"");
            }
        } else if (key == "line-max-distance") {
            EXEMPLAR_RETURN_IF_ERROR(number_of(value, raw_key, o.line_max_distance_px));
        } else if (key == "weights") {
            if (!value.is_object()) return type_error(path, raw_key, "an object of numbers");
            for (const auto& [wk_raw, wv] : value.items()) {
                const std::string wk = canonical_key(wk_raw);
                const std::string name = raw_key + "." + wk_raw;
                float* field = wk == "output"     ? &o.output_weight
                               : wk == "input"    ? &o.input_weight
                               : wk == "temporal" ? &o.temporal_weight
                               : wk == "keyframe" ? &o.keyframe_weight
                               : wk == "lines"    ? &o.line_weight
                                                  : nullptr;
                if (field == nullptr) {
                    return invalid_argument(
                        path + ": unknown key '" + name +
                        "' (weights are output, input, temporal, keyframe, lines)");
                }
                EXEMPLAR_RETURN_IF_ERROR(number_of(wv, name, *field));
            }
        } else if (key == "levels") {
            EXEMPLAR_RETURN_IF_ERROR(int_of(value, raw_key, o.levels));
        } else if (key == "sweeps") {
            EXEMPLAR_RETURN_IF_ERROR(int_of(value, raw_key, o.sweeps));
        } else if (key == "backward-em-iterations") {
            EXEMPLAR_RETURN_IF_ERROR(int_of(value, raw_key, o.backward_em_iterations));
        } else if (key == "occlusion-tolerance") {
            EXEMPLAR_RETURN_IF_ERROR(number_of(value, raw_key, o.occlusion_tolerance_sq_px));
        } else if (key == "orientation") {
            if (!value.is_boolean()) return type_error(path, raw_key, "true or false");
            o.orientation = value.get<bool>();
        } else if (key == "flow-preset") {
            std::string name;
            EXEMPLAR_RETURN_IF_ERROR(string_of(value, raw_key, name));
            auto preset = video::parse_flow_preset(name);
            if (!preset.ok()) return invalid_argument(path + ": " + preset.status().message());
            o.flow.preset = *preset;
        } else if (key == "usage") {
            std::string name;
            EXEMPLAR_RETURN_IF_ERROR(string_of(value, raw_key, name));
            auto usage = parse_usage_strategy(name);
            if (!usage.ok()) return invalid_argument(path + ": " + usage.status().message());
            o.synthesis.usage = *usage;
        } else if (const OptionSpec* spec = find_option(key)) {
            if (!value.is_number()) return type_error(path, raw_key, "a number");
            const Status st = set_option(o.synthesis, *spec, value.get<double>());
            if (!st.is_ok()) return invalid_argument(path + ": " + st.message());
        } else {
            return invalid_argument(path + ": unknown key '" + raw_key + "'");
        }
    }
    if (job.frames.empty()) return invalid_argument(path + ": key 'frames' is missing");
    if (job.style_input.empty() || job.style_output.empty()) {
        return invalid_argument(path + ": key 'style' needs \"input\" and \"output\"");
    }
    if (!(job.fps > 0.0)) return invalid_argument(path + ": key 'fps' must be > 0");
    if (job.chunk < 0 || job.chunk == 1) {
        return invalid_argument(path + ": key 'chunk' must be 0 (whole range) or >= 2");
    }
    return job;
}

}  // namespace exemplar::cli
