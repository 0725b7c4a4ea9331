#include "stylize_job.hpp"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "exemplar/synth/options.hpp"
#include "json_file.hpp"

namespace exemplar::cli {

namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

Status type_error(const std::string& file, const std::string& key, const char* expected) {
    return invalid_argument(file + ": key '" + key + "' must be " + expected);
}

}  // namespace

Result<StylizeJob> load_job_file(const std::string& path) {
    auto parsed = read_json_object(path);
    if (!parsed.ok()) return parsed.status();
    const json& doc = *parsed;
    const fs::path base = fs::path(path).parent_path();
    auto resolve = [&](const std::string& p) {
        if (p.empty() || fs::path(p).is_absolute()) return p;
        return (base / p).lexically_normal().string();
    };

    StylizeJob job;
    const std::map<std::string, std::string StylizeJob::*> paths = {
        {"style", &StylizeJob::style},
        {"output", &StylizeJob::output},
        {"target-mask", &StylizeJob::target_mask},
        {"source-mask", &StylizeJob::source_mask},
        {"source-labels", &StylizeJob::source_labels},
        {"target-labels", &StylizeJob::target_labels},
        {"source-orientation", &StylizeJob::source_orientation},
        {"target-orientation", &StylizeJob::target_orientation},
        {"init", &StylizeJob::init},
        {"init-nnf", &StylizeJob::init_nnf},
        {"save-nnf", &StylizeJob::save_nnf},
        {"save-error", &StylizeJob::save_error},
    };
    const std::map<std::string, std::string StylizeJob::*> words = {
        {"usage", &StylizeJob::usage}, {"vote", &StylizeJob::vote}, {"size", &StylizeJob::size}};

    for (const auto& [raw_key, value] : doc.items()) {
        const std::string key = canonical_key(raw_key);
        if (auto it = paths.find(key); it != paths.end()) {
            if (!value.is_string()) return type_error(path, raw_key, "a string (a file path)");
            job.*(it->second) = resolve(value.get<std::string>());
        } else if (auto w = words.find(key); w != words.end()) {
            if (!value.is_string()) return type_error(path, raw_key, "a string");
            job.*(w->second) = value.get<std::string>();
        } else if (key == "guides") {
            if (!value.is_array()) return type_error(path, raw_key, "an array of guides");
            for (const json& g : value) {
                if (!g.is_object() || !g.contains("source") || !g.contains("target") ||
                    !g["source"].is_string() || !g["target"].is_string()) {
                    return type_error(path, raw_key,
                                      "an array of {\"source\": ..., \"target\": ..., "
                                      "\"weight\": ...} objects");
                }
                GuideSpec spec;
                for (const auto& [gk_raw, gv] : g.items()) {
                    const std::string gk = canonical_key(gk_raw);
                    if (gk == "source" || gk == "target") continue;
                    if (gk == "weight") {
                        if (!gv.is_number()) return type_error(path, "guides.weight", "a number");
                        spec.weight = gv.get<float>();
                    } else if (gk == "weight-map") {
                        if (!gv.is_string()) return type_error(path, "guides.weight-map", "a path");
                        spec.weight_map = resolve(gv.get<std::string>());
                    } else {
                        return invalid_argument(path + ": unknown key 'guides." + gk_raw +
                                                "' (guides take source, target, weight, "
                                                "weight-map)");
                    }
                }
                spec.source = resolve(g["source"].get<std::string>());
                spec.target = resolve(g["target"].get<std::string>());
                job.guides.push_back(std::move(spec));
            }
        } else if (key == "style-weights") {
            if (!value.is_array()) return type_error(path, raw_key, "an array of numbers");
            for (const json& v : value) {
                if (!v.is_number()) return type_error(path, raw_key, "an array of numbers");
                job.style_weights.push_back(v.get<float>());
            }
        } else if (key == "threads") {
            if (!value.is_number_integer()) return type_error(path, raw_key, "an integer");
            job.threads = value.get<int>();
        } else if (key == "quiet") {
            if (!value.is_boolean()) return type_error(path, raw_key, "true or false");
            job.quiet = value.get<bool>();
        } else if (find_option(key) != nullptr) {
            if (!value.is_number()) return type_error(path, raw_key, "a number");
            job.numeric[std::string(find_option(key)->name)] = value.get<double>();
        } else {
            return invalid_argument(path + ": unknown key '" + raw_key + "'");
        }
    }
    return job;
}

StylizeJob merge_jobs(const StylizeJob& base, const StylizeJob& over) {
    StylizeJob out = base;
    auto take = [](std::string& dst, const std::string& src) {
        if (!src.empty()) dst = src;
    };
    take(out.style, over.style);
    take(out.output, over.output);
    take(out.usage, over.usage);
    take(out.vote, over.vote);
    take(out.target_mask, over.target_mask);
    take(out.source_mask, over.source_mask);
    take(out.source_labels, over.source_labels);
    take(out.target_labels, over.target_labels);
    take(out.source_orientation, over.source_orientation);
    take(out.target_orientation, over.target_orientation);
    take(out.init, over.init);
    take(out.init_nnf, over.init_nnf);
    take(out.save_nnf, over.save_nnf);
    take(out.save_error, over.save_error);
    take(out.size, over.size);
    if (!over.guides.empty()) out.guides = over.guides;
    if (!over.style_weights.empty()) out.style_weights = over.style_weights;
    for (const auto& [k, v] : over.numeric) out.numeric[k] = v;
    if (over.threads) out.threads = over.threads;
    if (over.quiet) out.quiet = over.quiet;
    return out;
}

}  // namespace exemplar::cli
